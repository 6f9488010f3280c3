//! The cell-projection renderer (crates/project) in the viewer: whole
//! frames only (a render pass cannot be cut into rows), read back and shown
//! through the display pass as the CPU reference's frames are. The mesh is
//! prepared once per scalar field, when the renderer is first picked.

use std::time::{Duration, Instant};

use anyhow::Context;
use tetray_core::Image;
use tetray_core::WalkCounters;
use tetray_gpu::{GpuContext, GpuIntegrator};
use tetray_project::layout::knot_scalars;
use tetray_project::{
    GpuProjectScene, GpuProjector, ProjectScene, SortKind, TetIntervals, View, plan,
};
use tetray_scene::Scene;

use crate::engine::{FrameKey, FrameReport};

/// A mesh ready to project on the display's device.
pub struct ProjectRenderer {
    scene: ProjectScene,
    gpu_scene: GpuProjectScene,
    projector: GpuProjector,
    /// Each view's cells split at its transfer function's knots, for the
    /// frame generation they were made for.
    intervals: Option<(u64, Vec<Option<TetIntervals>>)>,
    /// The whole last frame (sort, draws, read-back), to decide whether
    /// frames may follow the camera or wait until it stops.
    pub last_frame: Option<Duration>,
}

impl ProjectRenderer {
    pub fn new(ctx: &GpuContext, scene: &Scene) -> anyhow::Result<ProjectRenderer> {
        let scene = ProjectScene::new(scene).context("preparing the mesh for cell projection")?;
        Ok(ProjectRenderer {
            gpu_scene: GpuProjectScene::upload(ctx, &scene)
                .context("uploading the projection's mesh")?,
            projector: GpuProjector::new(ctx).context("compiling the projection pipeline")?,
            scene,
            intervals: None,
            last_frame: None,
        })
    }

    /// One frame of `key` per integrator with the `sort` visibility order
    /// and adaptive transfer-function sampling (where the method gains).
    pub fn render(
        &mut self,
        ctx: &GpuContext,
        key: &FrameKey,
        sort: SortKind,
        integrators: &[&GpuIntegrator],
    ) -> anyhow::Result<(Vec<Image>, FrameReport)> {
        let start = Instant::now();
        if self.intervals.as_ref().map(|(g, _)| *g) != Some(key.generation) {
            let intervals = integrators
                .iter()
                .map(|i| {
                    tetray_project::samples_adaptively(i.data())
                        .then(|| TetIntervals::new(&self.scene, &knot_scalars(i.data())))
                })
                .collect();
            self.intervals = Some((key.generation, intervals));
        }
        let intervals = self
            .intervals
            .as_ref()
            .map(|(_, v)| v.as_slice())
            .unwrap_or(&[]);
        let (width, height) = key.size;
        let view = View::new(&key.camera, width, height)?;
        let mut images = Vec::new();
        let mut stats = [WalkCounters::default(); 2];
        for (k, integrator) in integrators.iter().enumerate() {
            let pieces = intervals.get(k).and_then(Option::as_ref);
            let plan = plan(&self.scene, pieces, &view, sort);
            let (image, draw) = self
                .projector
                .draw(ctx, &self.gpu_scene, integrator, &view, &plan.draws)
                .with_context(|| format!("projecting view {}", k + 1))?;
            if let Some(slot) = stats.get_mut(k) {
                *slot = WalkCounters {
                    rays: u64::from(width) * u64::from(height),
                    segments: draw.segments,
                    ..WalkCounters::default()
                };
            }
            images.push(image);
        }
        let elapsed = start.elapsed();
        self.last_frame = Some(elapsed);
        let report = FrameReport {
            size: key.size,
            views: images.len() as u32,
            elapsed,
            batches: 1,
            stats,
            renderer: "cell projection",
        };
        Ok((images, report))
    }
}
