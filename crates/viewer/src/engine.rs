//! The GPU side of the viewer: the ray caster and the display pass on
//! eframe's device, and a progressive frame: a preview at low resolution
//! while the view changes, then the full frame a few rows per display frame,
//! each batch followed by the display pass, so that the image never leaves
//! the GPU and no display frame waits on more ray casting than the budget.

use std::time::{Duration, Instant};

use anyhow::Context;
use tetray_core::WalkCounters;
use tetray_core::{Camera, Image};
use tetray_gpu::{
    FrameJob, GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene, GpuTarget,
    walk_counters,
};
use tetray_scene::Scene;

use crate::gpu_io;
use crate::pacing::Pacer;
use crate::present::{DisplayTexture, PresentParams, Presenter};

/// The ray caster and the mesh on the display's device.
pub struct GpuRenderer {
    pub ctx: GpuContext,
    raycaster: GpuRaycaster,
    presenter: Presenter,
    scene: GpuScene,
}

impl GpuRenderer {
    pub fn new(ctx: GpuContext, scene: &Scene) -> anyhow::Result<GpuRenderer> {
        let raycaster = GpuRaycaster::new(&ctx).context("compiling the ray-casting kernel")?;
        let presenter = Presenter::new(&ctx);
        let scene = GpuScene::new(&ctx, scene).context("uploading the mesh")?;
        Ok(GpuRenderer {
            ctx,
            raycaster,
            presenter,
            scene,
        })
    }

    /// Uploads another scene (a new scalar field).
    pub fn set_scene(&mut self, scene: &Scene) -> anyhow::Result<()> {
        self.scene = GpuScene::new(&self.ctx, scene).context("uploading the mesh")?;
        Ok(())
    }

    /// Writes the points' scalars of `scene`, another time step of the
    /// uploaded mesh, over the upload.
    pub fn write_points(&mut self, scene: &Scene) -> anyhow::Result<()> {
        self.scene
            .write_points(&self.ctx, scene)
            .context("writing the time step's field")
    }

    pub fn tet_count(&self) -> usize {
        self.scene.tet_count()
    }
}

/// Everything a frame is made of: when any of it changes, the frame starts
/// over (with a preview, unless a whole frame fits the budget).
#[derive(Debug, Clone, PartialEq)]
pub struct FrameKey {
    pub camera: Camera,
    pub size: (u32, u32),
    pub early_termination: f32,
    /// Bumped whenever a transfer function, method, field or option changes.
    pub generation: u64,
    /// 1, or 2 when comparing.
    pub views: u32,
}

/// How the frame is shown (changes only re-run the display pass).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    pub display: crate::present::Display,
    /// First column showing B, as a fraction of the width.
    pub divider: f32,
    pub background: glam::Vec3,
    pub diff_scale: f32,
}

/// The statistics of a finished frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameReport {
    pub size: (u32, u32),
    pub views: u32,
    /// Ray casting of the full frame, all batches (submission to
    /// completion), preview excluded.
    pub elapsed: Duration,
    pub batches: u32,
    /// Counters of each view (B zero when not comparing).
    pub stats: [WalkCounters; 2],
    pub renderer: &'static str,
}

impl FrameReport {
    pub fn rays(&self) -> u64 {
        self.stats.iter().map(|s| s.rays).sum()
    }

    pub fn segments(&self) -> u64 {
        self.stats.iter().map(|s| s.segments).sum()
    }
}

/// Where the current frame is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Nothing rendered for the current key.
    Start,
    /// The preview is shown; `rows` rows of the full frame are done.
    Refining { rows: u32 },
    /// The full frame is shown.
    Done,
}

/// One progressive frame of up to two views.
pub struct Progressive {
    pub pacer: Pacer,
    key: Option<FrameKey>,
    phase: Phase,
    full: Vec<GpuTarget>,
    preview: Vec<GpuTarget>,
    elapsed: Duration,
    batches: u32,
    presented: Option<PresentParams>,
    pub report: Option<FrameReport>,
}

impl Progressive {
    pub fn new(budget: Duration) -> Progressive {
        Progressive {
            pacer: Pacer::new(budget),
            key: None,
            phase: Phase::Start,
            full: Vec::new(),
            preview: Vec::new(),
            elapsed: Duration::ZERO,
            batches: 0,
            presented: None,
            report: None,
        }
    }

    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// Size of the last preview.
    pub fn preview_size(&self) -> Option<(u32, u32)> {
        self.preview.first().map(|t| (t.width(), t.height()))
    }

    /// Fraction of the full frame done.
    pub fn progress(&self) -> f32 {
        match (self.phase, &self.key) {
            (Phase::Done, _) => 1.0,
            (Phase::Refining { rows }, Some(key)) => rows as f32 / key.size.1.max(1) as f32,
            _ => 0.0,
        }
    }

    /// Starts over whenever `key` differs from the current frame's.
    fn restart_if_changed(&mut self, gpu: &GpuRenderer, key: &FrameKey) -> anyhow::Result<()> {
        if self.key.as_ref() == Some(key) {
            return Ok(());
        }
        let (w, h) = key.size;
        let resized = self.full.first().map(|t| (t.width(), t.height())) != Some((w, h))
            || self.full.len() != key.views as usize;
        if resized {
            self.full = (0..key.views)
                .map(|_| GpuTarget::new(&gpu.ctx, w, h))
                .collect::<Result<_, _>>()?;
        }
        self.key = Some(key.clone());
        self.phase = Phase::Start;
        self.elapsed = Duration::ZERO;
        self.batches = 0;
        self.presented = None;
        Ok(())
    }

    /// Does one display frame's worth of work for `key` with one
    /// integrator per view, then the display pass into `output` (whose size
    /// must be `key.size`). With `refine` false only previews are made (a
    /// CPU renderer provides the full frame). Returns whether more work is
    /// left.
    pub fn advance(
        &mut self,
        gpu: &GpuRenderer,
        key: &FrameKey,
        integrators: &[&GpuIntegrator],
        look: &Look,
        output: &DisplayTexture,
        refine: bool,
    ) -> anyhow::Result<bool> {
        self.restart_if_changed(gpu, key)?;
        let (w, h) = key.size;
        let views = integrators.len().min(key.views as usize);
        let full_rays = u64::from(w) * u64::from(h) * views as u64;
        let mut encoder = gpu.ctx.device.create_command_encoder(&Default::default());
        let start = Instant::now();
        let mut rays = 0u64;
        let mut refined_rows = None;
        match self.phase {
            Phase::Start if refine && self.pacer.fits(full_rays) => {
                self.encode_full_rows(gpu, key, integrators, 0..h, &mut encoder)?;
                rays = full_rays;
                refined_rows = Some(h);
            }
            Phase::Start => {
                let size = self.pacer.preview_size((w, h), views as u32);
                self.encode_preview(gpu, key, integrators, size, &mut encoder)?;
                rays = u64::from(size.0 * size.1) * views as u64;
                self.phase = Phase::Refining { rows: 0 };
            }
            Phase::Refining { rows } if refine => {
                let count = self.pacer.rows(w, views as u32, h - rows);
                self.encode_full_rows(gpu, key, integrators, rows..rows + count, &mut encoder)?;
                rays = u64::from(w * count) * views as u64;
                refined_rows = Some(rows + count);
            }
            Phase::Refining { .. } | Phase::Done => {}
        }
        if let Some(rows) = refined_rows {
            self.phase = if rows >= h {
                Phase::Done
            } else {
                Phase::Refining { rows }
            };
        }
        let params = self.present_params(key, look);
        let stats_reads: Vec<wgpu::Buffer> = if self.phase == Phase::Done && rays > 0 {
            self.full[..views]
                .iter()
                .map(|t| t.encode_stats_readback(&gpu.ctx, &mut encoder))
                .collect()
        } else {
            Vec::new()
        };
        if rays == 0 && self.presented == Some(params) {
            return Ok(self.more_work(refine));
        }
        self.encode_present(gpu, &params, &mut encoder, output);
        let submission = gpu.ctx.queue.submit([encoder.finish()]);
        // One batch in flight at a time: wait for it, so that the next
        // batch is sized from its time and display frames never queue up
        // behind ray casting.
        gpu.ctx
            .device
            .poll(wgpu::PollType::Wait {
                submission_index: Some(submission),
                timeout: None,
            })
            .map_err(|e| anyhow::anyhow!("waiting for the GPU: {e}"))?;
        let batch = start.elapsed();
        if rays > 0 {
            self.pacer.record(rays, batch);
        }
        if refined_rows.is_some() {
            self.elapsed += batch;
            self.batches += 1;
        }
        if !stats_reads.is_empty() {
            let mut stats = [WalkCounters::default(); 2];
            for (slot, read) in stats.iter_mut().zip(&stats_reads) {
                let bytes = gpu_io::map_read(&gpu.ctx, read)?;
                let counters: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
                *slot = walk_counters(&counters, u64::from(w) * u64::from(h));
            }
            self.report = Some(FrameReport {
                size: (w, h),
                views: views as u32,
                elapsed: self.elapsed,
                batches: self.batches,
                stats,
                renderer: "GPU ray caster",
            });
        }
        self.presented = Some(params);
        Ok(self.more_work(refine))
    }

    fn more_work(&self, refine: bool) -> bool {
        match self.phase {
            Phase::Start => true,
            Phase::Refining { .. } => refine,
            Phase::Done => false,
        }
    }

    /// Shows full frames made elsewhere (the CPU reference) for `key`.
    pub fn show_frames(
        &mut self,
        gpu: &GpuRenderer,
        key: &FrameKey,
        images: &[Image],
        report: FrameReport,
        look: &Look,
        output: &DisplayTexture,
    ) -> anyhow::Result<()> {
        self.restart_if_changed(gpu, key)?;
        for (target, image) in self.full.iter().zip(images) {
            gpu_io::write_image(&gpu.ctx, target, image);
        }
        self.phase = Phase::Done;
        self.report = Some(report);
        let params = self.present_params(key, look);
        let mut encoder = gpu.ctx.device.create_command_encoder(&Default::default());
        self.encode_present(gpu, &params, &mut encoder, output);
        gpu.ctx.queue.submit([encoder.finish()]);
        self.presented = Some(params);
        Ok(())
    }

    /// The refined images of the current frame (screenshots), finishing
    /// the frame first if it is still refining.
    pub fn finished_images(
        &mut self,
        gpu: &GpuRenderer,
        key: &FrameKey,
        integrators: &[&GpuIntegrator],
    ) -> anyhow::Result<Vec<Image>> {
        self.restart_if_changed(gpu, key)?;
        let h = key.size.1;
        let first = match self.phase {
            Phase::Start => 0,
            Phase::Refining { rows } => rows,
            Phase::Done => h,
        };
        if first < h {
            let mut encoder = gpu.ctx.device.create_command_encoder(&Default::default());
            self.encode_full_rows(gpu, key, integrators, first..h, &mut encoder)?;
            gpu.ctx.queue.submit([encoder.finish()]);
            self.phase = Phase::Done;
            // The display pass still shows the old rows: present again.
            self.presented = None;
        }
        let views = integrators.len().min(self.full.len());
        self.full[..views]
            .iter()
            .map(|t| gpu_io::read_image(&gpu.ctx, t))
            .collect()
    }

    fn encode_full_rows(
        &mut self,
        gpu: &GpuRenderer,
        key: &FrameKey,
        integrators: &[&GpuIntegrator],
        rows: std::ops::Range<u32>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> anyhow::Result<()> {
        if rows.start == 0 {
            for target in &self.full {
                target.clear_stats(encoder);
            }
        }
        encode_views(gpu, key, &self.full, integrators, key.size, rows, encoder)
    }

    fn encode_preview(
        &mut self,
        gpu: &GpuRenderer,
        key: &FrameKey,
        integrators: &[&GpuIntegrator],
        (pw, ph): (u32, u32),
        encoder: &mut wgpu::CommandEncoder,
    ) -> anyhow::Result<()> {
        let current = self.preview.first().map(|t| (t.width(), t.height()));
        if current != Some((pw, ph)) || self.preview.len() != integrators.len() {
            self.preview = integrators
                .iter()
                .map(|_| GpuTarget::new(&gpu.ctx, pw, ph))
                .collect::<Result<_, _>>()?;
        }
        encode_views(
            gpu,
            key,
            &self.preview,
            integrators,
            (pw, ph),
            0..ph,
            encoder,
        )
    }

    fn present_params(&self, key: &FrameKey, look: &Look) -> PresentParams {
        let (w, h) = key.size;
        let rows = match self.phase {
            Phase::Done => h,
            Phase::Refining { rows } => rows,
            Phase::Start => 0,
        };
        let preview = self
            .preview
            .first()
            .map_or((w, h), |t| (t.width(), t.height()));
        let divider = (look.divider.clamp(0.0, 1.0) * w as f32).round() as u32;
        PresentParams::new(
            (w, h),
            preview,
            rows,
            if key.views > 1 {
                look.display
            } else {
                crate::present::Display::Single
            },
            divider,
            look.background,
            look.diff_scale,
        )
    }

    fn encode_present(
        &self,
        gpu: &GpuRenderer,
        params: &PresentParams,
        encoder: &mut wgpu::CommandEncoder,
        output: &DisplayTexture,
    ) {
        let full_a = &self.full[0];
        let full_b = self.full.get(1).unwrap_or(full_a);
        // Before any preview (a CPU frame shown first) the full image
        // stands in for it: every row is done then.
        let preview_a = self.preview.first().unwrap_or(full_a);
        let preview_b = self.preview.get(1).unwrap_or(preview_a);
        gpu.presenter.encode(
            &gpu.ctx,
            encoder,
            params,
            [full_a, full_b, preview_a, preview_b],
            output,
        );
    }
}

/// Encodes rows `rows` of each view's target, a `size` frame of `key`.
fn encode_views(
    gpu: &GpuRenderer,
    key: &FrameKey,
    targets: &[GpuTarget],
    integrators: &[&GpuIntegrator],
    size: (u32, u32),
    rows: std::ops::Range<u32>,
    encoder: &mut wgpu::CommandEncoder,
) -> anyhow::Result<()> {
    let opts = render_options(key, size);
    for (target, integrator) in targets.iter().zip(integrators) {
        let job = FrameJob {
            scene: &gpu.scene,
            integrator,
            camera: &key.camera,
            opts: &opts,
        };
        gpu.raycaster
            .encode_rows(&gpu.ctx, &job, target, rows.clone(), encoder, None)?;
    }
    Ok(())
}

fn render_options(key: &FrameKey, (width, height): (u32, u32)) -> GpuRenderOptions {
    GpuRenderOptions {
        width,
        height,
        early_termination: key.early_termination,
        max_steps_per_ray: None,
    }
}
