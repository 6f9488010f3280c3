//! How much ray casting fits in one display frame: the number of rays a
//! batch may have, the size of the preview shown while the view changes,
//! and how many rows of the full frame to add per display frame while it
//! refines. Pure arithmetic, so that it is tested without a GPU.
//!
//! A batch costs a fixed part (submission, the display pass, the wait:
//! about 30 ms on lavapipe, whatever the batch's size) plus a part per
//! ray. Dividing a batch's time by its rays charges the fixed part to the
//! rays, and when that part is close to the budget the batches shrink to
//! one row and stay there (a 235 x 200 frame then took 200 display frames
//! and 8 to 12 s on lavapipe). So the pacer does not model the cost: it
//! scales the next batch by budget / time of the last one (at most 2x up
//! or down per batch), which settles where a batch takes the budget,
//! whatever the fixed part (when it is below the budget).

use std::time::Duration;

/// Long side of the first preview, before any frame has been timed.
pub const FIRST_PREVIEW_SIDE: u32 = 48;
/// The preview's long side is never smaller than this.
pub const MIN_PREVIEW_SIDE: u32 = 16;
/// Rows of the first refinement batch, before any frame has been timed.
const FIRST_ROWS: u32 = 8;
/// The most a batch grows or shrinks from one to the next.
const MAX_STEP: f64 = 2.0;
/// Batches are never planned below this many rays.
const MIN_RAYS: f64 = 64.0;

/// The rays a batch may have to take about the budget.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pacer {
    /// GPU (or CPU) time one display frame may spend ray casting.
    pub budget: Duration,
    /// Rays that fit the budget; `None` before any batch was timed.
    capacity: Option<f64>,
}

impl Pacer {
    pub fn new(budget: Duration) -> Pacer {
        Pacer {
            budget,
            capacity: None,
        }
    }

    /// Folds in a batch of `rays` that took `elapsed`: the next batch is
    /// `rays * budget / elapsed`, within `MAX_STEP` of this one.
    pub fn record(&mut self, rays: u64, elapsed: Duration) {
        if rays == 0 {
            return;
        }
        let ratio = self.budget.as_secs_f64() / elapsed.as_secs_f64().max(1e-9);
        let next = rays as f64 * ratio.clamp(1.0 / MAX_STEP, MAX_STEP);
        self.capacity = Some(next.max(MIN_RAYS));
    }

    /// Rays that fit the budget, once something has been timed.
    pub fn capacity(&self) -> Option<u64> {
        self.capacity.map(|c| c as u64)
    }

    /// Whether `rays` rays fit one display frame: then the full frame is
    /// rendered at once, with no preview.
    pub fn fits(&self, rays: u64) -> bool {
        self.capacity.is_some_and(|c| rays as f64 <= c)
    }

    /// The preview of a `width x height` frame with `views` views: the
    /// frame scaled down (same aspect) to about the budget's rays, long
    /// side between [`MIN_PREVIEW_SIDE`] and the frame's.
    pub fn preview_size(&self, (width, height): (u32, u32), views: u32) -> (u32, u32) {
        let long = width.max(height).max(1) as f64;
        let side = match self.capacity {
            Some(rays) => {
                let per_view = rays / f64::from(views.max(1));
                let scale = (per_view / (f64::from(width) * f64::from(height))).sqrt();
                long * scale
            }
            None => f64::from(FIRST_PREVIEW_SIDE),
        };
        let side = side.clamp(f64::from(MIN_PREVIEW_SIDE), long);
        let scale = side / long;
        let scaled = |v: u32| ((f64::from(v) * scale).round() as u32).clamp(1, v.max(1));
        (scaled(width), scaled(height))
    }

    /// Rows of a frame `width` wide with `views` views to render in the
    /// next batch: as many as fit the budget, at least one, at most
    /// `rows_left`.
    pub fn rows(&self, width: u32, views: u32, rows_left: u32) -> u32 {
        let rows = match self.capacity {
            Some(rays) => (rays / f64::from(width.max(1) * views.max(1))) as u32,
            None => FIRST_ROWS,
        };
        rows.clamp(1, rows_left.max(1)).min(rows_left)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    /// A batch of `rays` on a renderer with a fixed cost per batch.
    fn cost(fixed_ms: f64, us_per_ray: f64, rays: u64) -> Duration {
        Duration::from_secs_f64((fixed_ms + us_per_ray * 1e-3 * rays as f64) * 1e-3)
    }

    #[test]
    fn before_any_timing_the_preview_is_small_and_batches_short() {
        let pacer = Pacer::new(40 * MS);
        assert_eq!(pacer.capacity(), None);
        assert!(!pacer.fits(1));
        assert_eq!(pacer.preview_size((480, 240), 1), (48, 24));
        assert_eq!(pacer.rows(480, 1, 100), 8);
        assert_eq!(pacer.rows(480, 1, 3), 3);
    }

    #[test]
    fn a_fast_renderer_gets_whole_frames() {
        let mut pacer = Pacer::new(40 * MS);
        pacer.record(1_000_000, MS);
        assert_eq!(pacer.capacity(), Some(2_000_000), "at most 2x per batch");
        assert!(pacer.fits(512 * 512));
        assert_eq!(pacer.preview_size((512, 512), 2), (512, 512));
        assert_eq!(pacer.rows(512, 2, 512), 512);
    }

    #[test]
    fn a_slow_renderer_gets_a_preview_within_the_budget() {
        let mut pacer = Pacer::new(40 * MS);
        // 4000 rays in 100 ms: the next batch is half as large (the step
        // limit), 2000 rays.
        pacer.record(4000, 100 * MS);
        assert_eq!(pacer.capacity(), Some(2000));
        assert!(!pacer.fits(400 * 300));
        let (w, h) = pacer.preview_size((400, 300), 1);
        assert_eq!((w, h), (52, 39));
        // Two views share the budget.
        let (w2, _) = pacer.preview_size((400, 300), 2);
        assert!(w2 < w);
        assert_eq!(pacer.rows(400, 1, 300), 5);
        assert_eq!(pacer.rows(4000, 1, 300), 1, "at least one row");
    }

    /// lavapipe in the viewer: about 30 ms per batch whatever its size.
    /// Charging that to the rays (time / rays) made one-row batches that
    /// stayed one row; scaling by budget / time finds the batch that
    /// takes the budget: (40 - 30) ms / 1 us = 10,000 rays.
    #[test]
    fn batches_grow_past_a_fixed_cost_below_the_budget() {
        let mut pacer = Pacer::new(40 * MS);
        let mut rays = 235;
        for _ in 0..30 {
            pacer.record(rays, cost(30.0, 1.0, rays));
            rays = pacer.capacity().expect("timed");
        }
        assert!((9_000..=11_000).contains(&rays), "{rays}");
        let t = cost(30.0, 1.0, rays);
        assert!(t <= 42 * MS, "{t:?}");
        assert_eq!(pacer.rows(235, 1, 200), 200.min(rays as u32 / 235));
    }

    #[test]
    fn a_fixed_cost_above_the_budget_leaves_the_smallest_batches() {
        let mut pacer = Pacer::new(40 * MS);
        let mut rays = 10_000;
        for _ in 0..30 {
            pacer.record(rays, cost(50.0, 1.0, rays));
            rays = pacer.capacity().expect("timed");
        }
        assert_eq!(rays, MIN_RAYS as u64);
        assert_eq!(pacer.rows(235, 1, 200), 1);
        assert_eq!(pacer.preview_size((235, 200), 1).0, MIN_PREVIEW_SIDE);
    }

    #[test]
    fn empty_batches_change_nothing() {
        let mut pacer = Pacer::new(40 * MS);
        pacer.record(1000, 40 * MS);
        pacer.record(0, 100 * MS);
        assert_eq!(pacer.capacity(), Some(1000));
    }
}
