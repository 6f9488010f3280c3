//! The renderers of a [`Setup`]: the CPU reference ray caster, the GPU one,
//! the cell projection or shear-warp ([`RendererChoice`]), each ready to
//! render frames of it from any camera.

use tetray_core::{Camera, Method, WalkCounters};
use tetray_gpu::{GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene};
use tetray_project::{ProjectOptions, Projection};
use tetray_raycast::{RenderOptions, render_scalar_watched};

use crate::error::{Context, EngineError, bail, error_chain};
use crate::frame::{Frame, FrameStats};
use crate::options::{RendererChoice, WalkOptions};
use crate::setup::Setup;

/// A ready renderer.
pub enum Engine {
    Cpu,
    Gpu(Box<GpuEngine>),
    Project(Box<ProjectEngine>),
    ShearWarp(Box<tetray_shearwarp::ShearWarp>),
}

/// The cell projection with the mesh and integrator uploaded.
pub struct ProjectEngine {
    ctx: GpuContext,
    integrator: GpuIntegrator,
    projection: Projection,
}

/// The GPU ray caster with the mesh and integrator uploaded.
pub struct GpuEngine {
    ctx: GpuContext,
    raycaster: GpuRaycaster,
    scene: GpuScene,
    integrator: GpuIntegrator,
}

impl Engine {
    /// The renderer chosen (`--renderer`). `auto` takes the GPU ray caster
    /// on a hardware adapter and the CPU one otherwise (no adapter, or a
    /// CPU implementation such as lavapipe, which the CPU ray caster
    /// outruns), saying so.
    pub fn new(
        choice: impl Into<RendererChoice>,
        setup: &Setup,
        log: &dyn Fn(String),
    ) -> Result<Engine, EngineError> {
        let choice = choice.into();
        let gpu_method = setup.method.has_gpu_kernel();
        // The adapter for a renderer asked for by name, which must be able
        // to run the method.
        let gpu_context = |renderer: RendererChoice| -> Result<GpuContext, EngineError> {
            if !gpu_method {
                bail!(
                    "integrator {}: the f64 reference has no GPU kernel (the {} renderer runs {}); \
                     use the cpu renderer",
                    setup.method,
                    renderer.name(),
                    Method::gpu_names()
                );
            }
            GpuContext::new().with_context(|| format!("renderer {}", renderer.name()))
        };
        match choice {
            RendererChoice::Cpu => Ok(Engine::Cpu),
            RendererChoice::Gpu => Engine::gpu(gpu_context(choice)?, setup, log),
            RendererChoice::Project => Engine::project(gpu_context(choice)?, setup, log),
            RendererChoice::ShearWarp => {
                let sw = setup.shear_warp(
                    setup.method,
                    &setup.tf,
                    setup.unit_distance,
                    setup.integrator_options.opacity_mode,
                )?;
                log(crate::grid::describe(&sw));
                Ok(Engine::ShearWarp(Box::new(sw)))
            }
            RendererChoice::Auto => {
                if !gpu_method {
                    log(format!(
                        "renderer: cpu (the {} integrator is CPU only)",
                        setup.method
                    ));
                    return Ok(Engine::Cpu);
                }
                match GpuContext::new() {
                    Ok(ctx) if !ctx.is_cpu() => Engine::gpu(ctx, setup, log),
                    Ok(ctx) => {
                        log(format!(
                            "renderer: cpu (the adapter {} is a CPU implementation; \
                             --renderer gpu uses it anyway)",
                            ctx.adapter_name()
                        ));
                        Ok(Engine::Cpu)
                    }
                    Err(e) => {
                        log(format!("renderer: cpu ({})", error_chain(&e)));
                        Ok(Engine::Cpu)
                    }
                }
            }
        }
    }

    fn gpu(ctx: GpuContext, setup: &Setup, log: &dyn Fn(String)) -> Result<Engine, EngineError> {
        log(format!("renderer: gpu on {}", ctx.adapter_name()));
        let raycaster = GpuRaycaster::new(&ctx).context("compiling the GPU kernel")?;
        let scene = GpuScene::new(&ctx, setup.scene()?).context("uploading the mesh to the GPU")?;
        let integrator = GpuIntegrator::new(&ctx, &setup.integrator)
            .context("uploading the transfer function to the GPU")?;
        log(format!(
            "uploaded {} tetrahedra ({:.1} MB, {:.1} bytes per tetrahedron)",
            scene.tet_count(),
            scene.bytes() as f64 / 1e6,
            scene.bytes() as f64 / scene.tet_count().max(1) as f64
        ));
        Ok(Engine::Gpu(Box::new(GpuEngine {
            ctx,
            raycaster,
            scene,
            integrator,
        })))
    }

    fn project(
        ctx: GpuContext,
        setup: &Setup,
        log: &dyn Fn(String),
    ) -> Result<Engine, EngineError> {
        let integrator = GpuIntegrator::new(&ctx, &setup.integrator)
            .context("uploading the transfer function to the GPU")?;
        let projection = Projection::new(&ctx, setup.scene()?, &integrator)
            .context("preparing the mesh for projection")?;
        log(format!(
            "renderer: project on {} into {:?} ({} tetrahedra, {:.1} MB; adaptive sampling \
             would draw {} pieces)",
            ctx.adapter_name(),
            projection.projector().format(),
            projection.scene.tet_count(),
            projection.gpu_bytes() as f64 / 1e6,
            projection.intervals.pieces
        ));
        Ok(Engine::Project(Box::new(ProjectEngine {
            ctx,
            integrator,
            projection,
        })))
    }

    /// Follows `setup` after it took a time step's fields
    /// ([`Setup::take_fields`]): the GPU ray caster writes the points'
    /// scalars and the integrator's tables over what it uploaded; the
    /// cell projection and shear-warp are made again.
    pub fn take_fields(&mut self, setup: &Setup, log: &dyn Fn(String)) -> Result<(), EngineError> {
        let again = match self {
            Engine::Cpu => return Ok(()),
            Engine::Gpu(gpu) => {
                gpu.scene
                    .write_points(&gpu.ctx, setup.scene()?)
                    .context("writing the time step's field to the GPU")?;
                gpu.integrator = GpuIntegrator::new(&gpu.ctx, &setup.integrator)
                    .context("uploading the transfer function to the GPU")?;
                return Ok(());
            }
            Engine::Project(_) => RendererChoice::Project,
            Engine::ShearWarp(_) => RendererChoice::ShearWarp,
        };
        *self = Engine::new(again, setup, log)?;
        Ok(())
    }

    /// "cpu", "gpu" or "project".
    pub fn name(&self) -> &'static str {
        match self {
            Engine::Cpu => "cpu",
            Engine::Gpu(_) => "gpu",
            Engine::Project(_) => "project",
            Engine::ShearWarp(_) => "shear-warp",
        }
    }

    /// The device the frames run on.
    pub fn adapter(&self) -> String {
        match self {
            // The ray caster's walk runs as compiled for x86-64-v3 where
            // the CPU has it; shear-warp runs the baseline build.
            Engine::Cpu if tetray_raycast::wide_cpu() => format!(
                "cpu (rayon, x86-64-v3), {} threads",
                rayon::current_num_threads()
            ),
            Engine::Cpu | Engine::ShearWarp(_) => {
                format!("cpu (rayon), {} threads", rayon::current_num_threads())
            }
            Engine::Gpu(gpu) => gpu.ctx.adapter_name(),
            Engine::Project(p) => p.ctx.adapter_name(),
        }
    }

    /// Whether frame times come from GPU timestamp queries.
    pub fn gpu_timestamps(&self) -> bool {
        match self {
            Engine::Cpu | Engine::ShearWarp(_) => false,
            Engine::Gpu(gpu) => gpu.ctx.timestamps,
            Engine::Project(p) => p.ctx.timestamps,
        }
    }

    /// One frame of `setup` from `camera`.
    pub fn render(
        &self,
        setup: &Setup,
        camera: &Camera,
        walk: impl Into<WalkOptions>,
        size: (u32, u32),
        progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    ) -> Result<Frame, EngineError> {
        self.render_watched(setup, camera, walk, size, progress, None)
    }

    /// [`Engine::render`] that stops once `cancel` is set, with an error
    /// that says so: the CPU ray caster between bands of rows; the GPU
    /// renderers and shear-warp finish the frame they started.
    pub fn render_watched(
        &self,
        setup: &Setup,
        camera: &Camera,
        walk: impl Into<WalkOptions>,
        (width, height): (u32, u32),
        progress: Option<&(dyn Fn(usize, usize) + Sync)>,
        cancel: Option<&std::sync::atomic::AtomicBool>,
    ) -> Result<Frame, EngineError> {
        let walk: WalkOptions = walk.into();
        match self {
            Engine::ShearWarp(sw) => {
                crate::grid::render(sw, camera, walk.early_termination, (width, height))
            }
            Engine::Cpu => {
                let options = RenderOptions {
                    width,
                    height,
                    early_termination: walk.early_termination,
                    max_steps_per_ray: walk.max_steps,
                    // The global pool, sized once by --threads.
                    threads: None,
                };
                let out = render_scalar_watched(
                    setup.scene()?,
                    camera,
                    &setup.integrator,
                    &options,
                    progress,
                    cancel,
                )
                .context("rendering")?;
                let s = out.stats;
                Ok(Frame {
                    image: out.image,
                    stats: FrameStats {
                        counters: s.counters,
                        entry_lists: s.entry_lists,
                        elapsed: s.elapsed,
                        project: None,
                    },
                })
            }
            Engine::Gpu(gpu) => {
                let options = GpuRenderOptions {
                    width,
                    height,
                    early_termination: walk.early_termination,
                    max_steps_per_ray: walk.max_steps,
                };
                let out = gpu
                    .raycaster
                    .render(&gpu.ctx, &gpu.scene, &gpu.integrator, camera, &options)
                    .context("rendering on the GPU")?;
                let s = out.stats;
                Ok(Frame {
                    image: out.image,
                    stats: FrameStats {
                        counters: s.counters,
                        entry_lists: false,
                        elapsed: s.frame_time(),
                        project: None,
                    },
                })
            }
            Engine::Project(p) => {
                let options = ProjectOptions {
                    width,
                    height,
                    sort: walk.sort,
                    adaptive_tf: walk.adaptive_tf && setup.integrator.splits_at_knots(),
                };
                let out = p
                    .projection
                    .render(&p.ctx, &p.integrator, camera, &options)
                    .context("projecting")?;
                let s = out.stats;
                Ok(Frame {
                    stats: FrameStats {
                        counters: WalkCounters::of_image(&out.image, s.segments, s.draws as u64),
                        elapsed: s.sort_time + s.expand_time + s.draw_time,
                        project: Some(s),
                        ..FrameStats::default()
                    },
                    image: out.image,
                })
            }
        }
    }
}
