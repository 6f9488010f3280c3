//! Timing frames of one renderer: a warm-up frame, then `frames` frames
//! orbiting the camera once about its view-up (as the dissertation
//! averages over a rotation), averaged.

use tetray_gpu::{GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene};
use tetray_integrate::ScalarIntegrator;
use tetray_raycast::{render_scalar, Camera, RenderOptions};

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
struct Frame {
    seconds: f64,
    segments: u64,
    rays_hit: u64,
}

/// Averages `frames` frames of `render` after a warm-up one, turning the
/// camera `360 / frames` degrees between frames.
fn orbit(
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
    scene: &tetray_raycast::Scene,
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
            segments: out.stats.segments,
            rays_hit: out.stats.rays_hit,
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

    /// The GPU ray caster: the pass by timestamp queries where the adapter
    /// has them, else submission to completion.
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
                seconds: out.stats.frame_time().as_secs_f64(),
                segments: out.stats.segments,
                rays_hit: out.stats.rays_hit,
            })
        })?;
        Ok(Timing {
            ms_per_frame: s * 1e3,
            segments_per_frame: segments,
            rays_hit_per_frame: hits,
            clock: if self.ctx.timestamps {
                "gpu timestamp queries"
            } else {
                "wall clock"
            },
        })
    }
}
