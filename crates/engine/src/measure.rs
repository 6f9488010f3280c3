//! Timed frames: the one measurement behind `bench`, `compare` and the
//! Python package's `compare`, so they time frames the same way.

use std::time::Duration;

use tetray_core::{Camera, WalkCounters};

use crate::error::{Context, EngineError};
use crate::frame::{Frame, FrameStats};
use crate::options::WalkOptions;
use crate::renderer::Engine;
use crate::setup::Setup;

/// How frames are timed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Frames timed (at least 1).
    pub frames: u32,
    /// Degrees the camera turns about its view-up after each frame (0: the
    /// same view every frame).
    pub orbit_step: f32,
    /// Render one frame first, untimed: shader compilation, page faults and
    /// caches stay out of the times.
    pub warm_up: bool,
}

/// What [`measure`] found.
pub struct Measured {
    /// The frame of median time (the later of the two middle ones for an
    /// even count).
    pub median: Frame,
    /// Every timed frame's statistics, in order.
    pub frames: Vec<FrameStats>,
    /// The counters of every timed frame, summed.
    pub total: WalkCounters,
}

impl Measured {
    /// The frames' times in milliseconds, in order.
    pub fn times_ms(&self) -> Vec<f64> {
        self.frames
            .iter()
            .map(|f| f.elapsed.as_secs_f64() * 1e3)
            .collect()
    }

    /// The median frame's time in seconds (never 0).
    pub fn median_seconds(&self) -> f64 {
        self.median
            .stats
            .elapsed
            .max(Duration::from_nanos(1))
            .as_secs_f64()
    }
}

/// Renders `timing.frames` frames of `setup` from `camera` (orbiting by
/// `timing.orbit_step`) and keeps the median one.
pub fn measure(
    engine: &Engine,
    setup: &Setup,
    camera: &Camera,
    walk: WalkOptions,
    size: (u32, u32),
    timing: Timing,
) -> Result<Measured, EngineError> {
    if timing.warm_up {
        engine
            .render(setup, camera, walk, size, None)
            .context("warm-up frame")?;
    }
    let mut camera = *camera;
    let mut frames: Vec<Frame> = Vec::with_capacity(timing.frames as usize);
    for k in 0..timing.frames.max(1) {
        let frame = engine
            .render(setup, &camera, walk, size, None)
            .with_context(|| format!("frame {k}"))?;
        frames.push(frame);
        if timing.orbit_step != 0.0 {
            camera
                .azimuth(timing.orbit_step)
                .and_then(|()| camera.orthogonalize_view_up())
                .context("orbiting the camera")?;
        }
    }
    let stats: Vec<FrameStats> = frames.iter().map(|f| f.stats).collect();
    let total = stats
        .iter()
        .fold(WalkCounters::default(), |t, s| t.merge(s.counters));
    let mut order: Vec<usize> = (0..frames.len()).collect();
    order.sort_by_key(|&k| frames[k].stats.elapsed);
    let median = frames.swap_remove(order[order.len() / 2]);
    Ok(Measured {
        median,
        frames: stats,
        total,
    })
}

/// The median of `values` (0 for none).
pub fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    match sorted.len() {
        0 => 0.0,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians() {
        assert_eq!(median(&[]), 0.0);
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
    }
}
