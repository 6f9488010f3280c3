//! Timing frames of one renderer: a warm-up frame, then `frames` frames
//! orbiting the camera once about its view-up (as the dissertation
//! averages over a rotation), averaged.

use tetray_core::Camera;
use tetray_gpu::{GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene};
use tetray_integrate::ScalarIntegrator;
use tetray_raycast::{RenderOptions, render_scalar};

use crate::StudyError;

/// What one renderer did over the timed frames.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    pub ms_per_frame: f64,
    pub segments_per_frame: f64,
    pub rays_hit_per_frame: f64,
    /// How frame times were measured.
    pub clock: &'static str,
}

impl Timing {
    pub fn fps(&self) -> f64 {
        1e3 / self.ms_per_frame.max(1e-9)
    }

    pub fn segments_per_s(&self) -> f64 {
        self.segments_per_frame * self.fps()
    }
}

/// Per-frame numbers of either renderer.
pub(crate) struct Frame {
    pub(crate) seconds: f64,
    pub(crate) segments: u64,
    pub(crate) rays_hit: u64,
}

/// Averages `frames` frames of `render` after a warm-up one, turning the
/// camera `360 / frames` degrees between frames.
pub(crate) fn orbit(
    camera: &Camera,
    frames: u32,
    mut render: impl FnMut(&Camera) -> Result<Frame, StudyError>,
) -> Result<(f64, f64, f64), StudyError> {
    let mut camera = *camera;
    render(&camera)?;
    let (mut seconds, mut segments, mut hits) = (0.0, 0.0, 0.0);
    for _ in 0..frames {
        let frame = render(&camera)?;
        seconds += frame.seconds;
        segments += frame.segments as f64;
        hits += frame.rays_hit as f64;
        camera.azimuth(360.0 / frames as f32)?;
        camera.orthogonalize_view_up()?;
    }
    let n = f64::from(frames.max(1));
    Ok((seconds / n, segments / n, hits / n))
}

/// The CPU ray caster (rayon's pool), by wall clock.
pub fn time_cpu(
    scene: &tetray_scene::Scene,
    camera: &Camera,
    integrator: &ScalarIntegrator,
    (width, height): (u32, u32),
    frames: u32,
) -> Result<Timing, StudyError> {
    let options = RenderOptions {
        width,
        height,
        ..RenderOptions::default()
    };
    let (s, segments, hits) = orbit(camera, frames, |camera| {
        let out = render_scalar(scene, camera, integrator, &options)?;
        Ok(Frame {
            seconds: out.stats.elapsed.as_secs_f64(),
            segments: out.stats.counters.segments,
            rays_hit: out.stats.counters.rays_hit,
        })
    })?;
    Ok(Timing {
        ms_per_frame: s * 1e3,
        segments_per_frame: segments,
        rays_hit_per_frame: hits,
        clock: "wall clock",
    })
}

/// The adapter and the compiled ray-casting kernel.
pub struct GpuRig {
    pub ctx: GpuContext,
    pub raycaster: GpuRaycaster,
}

impl GpuRig {
    pub fn new() -> Result<GpuRig, StudyError> {
        let ctx = GpuContext::new()?;
        let raycaster = GpuRaycaster::new(&ctx)?;
        Ok(GpuRig { ctx, raycaster })
    }

    /// The GPU ray caster, by wall clock from submission to completion (the
    /// image's read-back excluded), as the cell projection is timed: one
    /// clock for both GPU renderers. Not by timestamp queries: on lavapipe,
    /// once a render pass (the projection's) has run on the device, the
    /// compute pass's timestamps read about 0.05 ms for passes that take
    /// 50 ms (measured in this study: Blunt Fin at 32 x 32 read 53 ms
    /// before the first projection frame and 0.04 ms after).
    pub fn time(
        &self,
        scene: &GpuScene,
        integrator: &GpuIntegrator,
        camera: &Camera,
        (width, height): (u32, u32),
        frames: u32,
    ) -> Result<Timing, StudyError> {
        let options = GpuRenderOptions {
            width,
            height,
            ..GpuRenderOptions::default()
        };
        let (s, segments, hits) = orbit(camera, frames, |camera| {
            let out = self
                .raycaster
                .render(&self.ctx, scene, integrator, camera, &options)?;
            Ok(Frame {
                seconds: out.stats.wall_time.as_secs_f64(),
                segments: out.stats.counters.segments,
                rays_hit: out.stats.counters.rays_hit,
            })
        })?;
        Ok(Timing {
            ms_per_frame: s * 1e3,
            segments_per_frame: segments,
            rays_hit_per_frame: hits,
            clock: "wall clock (submission to completion)",
        })
    }
}

/// The cell projection (tetray_project: balanced projected tetrahedra with
/// adaptive transfer-function sampling and the MPVONC sort), by wall clock
/// over the whole frame (the CPU sort and the GPU draw).
pub fn time_projection(
    rig: &GpuRig,
    projection: &tetray_project::Projection,
    integrator: &GpuIntegrator,
    camera: &Camera,
    (width, height): (u32, u32),
    frames: u32,
) -> Result<Timing, StudyError> {
    let options = tetray_project::ProjectOptions {
        width,
        height,
        ..tetray_project::ProjectOptions::default()
    };
    let (s, segments, hits) = orbit(camera, frames, |camera| {
        let out = projection.render(&rig.ctx, integrator, camera, &options)?;
        Ok(Frame {
            seconds: out.stats.wall_time.as_secs_f64(),
            segments: out.stats.segments,
            rays_hit: 0,
        })
    })?;
    Ok(Timing {
        ms_per_frame: s * 1e3,
        segments_per_frame: segments,
        rays_hit_per_frame: hits,
        clock: "wall clock (sort and draw)",
    })
}
