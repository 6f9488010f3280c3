//! A frame of the projection: sort, expand into draws, draw, with each
//! stage timed on its own.

use std::time::{Duration, Instant};

use tetray_core::{Camera, Image};
use tetray_gpu::{GpuContext, GpuIntegrator, IntegratorData};
use tetray_scene::Scene;

use crate::ProjectError;
use crate::draws::{TetIntervals, expand};
use crate::layout::knot_scalars;
use crate::render::{GpuProjectScene, GpuProjector};
use crate::scene::ProjectScene;
use crate::sort::{SortKind, visibility_order};
use crate::view::View;

/// How to project.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProjectOptions {
    pub width: u32,
    pub height: u32,
    pub sort: SortKind,
    /// Adaptive transfer-function sampling (section 4.3).
    pub adaptive_tf: bool,
}

impl Default for ProjectOptions {
    fn default() -> Self {
        ProjectOptions {
            width: 512,
            height: 512,
            sort: SortKind::Mpvonc,
            adaptive_tf: true,
        }
    }
}

/// Whether the integrator's method integrates between knot-interval
/// materials (every method but the Riemann sum and full pre-integration,
/// which look the transfer function up themselves): only those gain from
/// adaptive sampling.
pub fn samples_adaptively(integrator: &IntegratorData) -> bool {
    use tetray_integrate::Method;
    let code = |m: Method| m.gpu_code();
    integrator.method != code(Method::Riemann).unwrap_or(u32::MAX)
        && integrator.method != code(Method::Preintegrated).unwrap_or(u32::MAX)
}

/// The draws of one view, with what making them took.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub draws: Vec<[u32; 2]>,
    pub tets: usize,
    pub cycle_breaks: usize,
    pub sort_time: Duration,
    pub expand_time: Duration,
}

/// Sorts the tetrahedra for `view` and expands them into draws.
pub fn plan(
    scene: &ProjectScene,
    intervals: Option<&TetIntervals>,
    view: &View,
    sort: SortKind,
) -> Plan {
    let start = Instant::now();
    let order = visibility_order(scene, view, sort);
    let sort_time = start.elapsed();
    let start = Instant::now();
    let draws = expand(scene, intervals, &order.tets, view);
    Plan {
        draws,
        tets: order.tets.len(),
        cycle_breaks: order.cycle_breaks,
        sort_time,
        expand_time: start.elapsed(),
    }
}

/// Counters and times of one frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProjectStats {
    /// Whether cells were drawn per knot interval.
    pub adaptive_tf: bool,
    pub tets: usize,
    pub draws: usize,
    /// Draws beyond one per tetrahedron (adaptive sampling's pieces).
    pub extra_draws: usize,
    /// Fragments integrated.
    pub segments: u64,
    pub cycle_breaks: usize,
    pub sort_time: Duration,
    /// Order to draws (pieces ordered within each cell).
    pub expand_time: Duration,
    /// The render pass: GPU timestamps where the adapter has them, else the
    /// wall time of submission to completion.
    pub draw_time: Duration,
    pub draw_timed_on_gpu: bool,
    /// The whole frame, read-back included.
    pub wall_time: Duration,
}

pub struct ProjectFrame {
    pub image: Image,
    pub stats: ProjectStats,
}

/// A mesh and transfer function ready to project on a device.
pub struct Projection {
    pub scene: ProjectScene,
    pub intervals: TetIntervals,
    gpu_scene: GpuProjectScene,
    projector: GpuProjector,
}

impl Projection {
    pub fn new(
        ctx: &GpuContext,
        scene: &Scene,
        integrator: &GpuIntegrator,
    ) -> Result<Projection, ProjectError> {
        let scene = ProjectScene::new(scene)?;
        let intervals = TetIntervals::new(&scene, &knot_scalars(integrator.data()));
        Ok(Projection {
            gpu_scene: GpuProjectScene::upload(ctx, &scene)?,
            projector: GpuProjector::new(ctx)?,
            scene,
            intervals,
        })
    }

    pub fn projector(&self) -> &GpuProjector {
        &self.projector
    }

    /// Bytes of mesh data on the GPU.
    pub fn gpu_bytes(&self) -> u64 {
        self.gpu_scene.bytes()
    }

    /// The pieces to draw with adaptive sampling on, when it applies.
    pub fn intervals_for(
        &self,
        integrator: &IntegratorData,
        adaptive: bool,
    ) -> Option<&TetIntervals> {
        (adaptive && samples_adaptively(integrator)).then_some(&self.intervals)
    }

    pub fn render(
        &self,
        ctx: &GpuContext,
        integrator: &GpuIntegrator,
        camera: &Camera,
        opts: &ProjectOptions,
    ) -> Result<ProjectFrame, ProjectError> {
        ctx.check()?;
        let start = Instant::now();
        let view = View::new(camera, opts.width, opts.height)?;
        let intervals = self.intervals_for(integrator.data(), opts.adaptive_tf);
        let plan = plan(&self.scene, intervals, &view, opts.sort);
        let (image, draw) =
            self.projector
                .draw(ctx, &self.gpu_scene, integrator, &view, &plan.draws)?;
        Ok(ProjectFrame {
            image,
            stats: ProjectStats {
                adaptive_tf: intervals.is_some(),
                tets: plan.tets,
                draws: plan.draws.len(),
                extra_draws: plan.draws.len() - plan.tets,
                segments: draw.segments,
                cycle_breaks: plan.cycle_breaks,
                sort_time: plan.sort_time,
                expand_time: plan.expand_time,
                draw_time: draw.gpu_time.unwrap_or(draw.wall_time),
                draw_timed_on_gpu: draw.gpu_time.is_some(),
                wall_time: start.elapsed(),
            },
        })
    }
}
