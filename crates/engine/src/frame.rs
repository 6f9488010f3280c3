//! What a renderer gives back: the image and what the walk counted.

use std::time::Duration;

use tetray_core::{Image, WalkCounters};
use tetray_project::ProjectStats;

/// What either renderer reports of a frame.
#[derive(Debug, Clone, Copy, Default)]
pub struct FrameStats {
    /// What the walk counted (for the projection: rays are pixels, lit
    /// pixels the rays that hit, draws the steps; for shear-warp: slabs
    /// composited the segments).
    pub counters: WalkCounters,
    /// The CPU ray caster took its rays' boundary entries from per-pixel
    /// lists, not BVH queries.
    pub entry_lists: bool,
    /// Render time: the GPU pass by timestamp queries where the adapter has
    /// them, else the wall time of the frame; for the projection, its sort
    /// and draw list (CPU) plus its render pass.
    pub elapsed: Duration,
    /// The projection's own counters and stage times.
    pub project: Option<ProjectStats>,
}

/// One rendered frame.
pub struct Frame {
    pub image: Image,
    pub stats: FrameStats,
}
