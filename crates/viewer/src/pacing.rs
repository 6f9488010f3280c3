//! How much ray casting fits in one display frame: a running estimate of
//! the time per ray, the size of the preview shown while the view changes,
//! and how many rows of the full frame to add per display frame while it
//! refines. Pure arithmetic, so that it is tested without a GPU.

use std::time::Duration;

/// Long side of the first preview, before any frame has been timed.
pub const FIRST_PREVIEW_SIDE: u32 = 48;
/// The preview's long side is never smaller than this.
pub const MIN_PREVIEW_SIDE: u32 = 16;
/// Rows of the first refinement batch, before any frame has been timed.
const FIRST_ROWS: u32 = 8;

/// Running estimate of the renderer's time per ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pacer {
    /// GPU (or CPU) time one display frame may spend ray casting.
    pub budget: Duration,
    ns_per_ray: Option<f64>,
}

impl Pacer {
    pub fn new(budget: Duration) -> Pacer {
        Pacer {
            budget,
            ns_per_ray: None,
        }
    }

    /// Folds in a batch of `rays` that took `elapsed` (half weight to the
    /// newest batch: the cost per ray changes with the view).
    pub fn record(&mut self, rays: u64, elapsed: Duration) {
        if rays == 0 {
            return;
        }
        let sample = elapsed.as_secs_f64() * 1e9 / rays as f64;
        self.ns_per_ray = Some(match self.ns_per_ray {
            Some(old) => 0.5 * (old + sample),
            None => sample,
        });
    }

    /// Expected time of `rays` rays, once something has been timed.
    pub fn estimate(&self, rays: u64) -> Option<Duration> {
        self.ns_per_ray
            .map(|ns| Duration::from_secs_f64(ns * rays as f64 * 1e-9))
    }

    /// Rays that fit the budget (none known: `None`).
    fn budget_rays(&self) -> Option<f64> {
        self.ns_per_ray
            .map(|ns| self.budget.as_secs_f64() * 1e9 / ns.max(1e-3))
    }

    /// Whether `rays` rays fit one display frame: then the full frame is
    /// rendered at once, with no preview.
    pub fn fits(&self, rays: u64) -> bool {
        self.estimate(rays).is_some_and(|t| t <= self.budget)
    }

    /// The preview of a `width x height` frame with `views` views: the
    /// frame scaled down (same aspect) to about the budget's rays, long
    /// side between [`MIN_PREVIEW_SIDE`] and the frame's.
    pub fn preview_size(&self, (width, height): (u32, u32), views: u32) -> (u32, u32) {
        let long = width.max(height).max(1) as f64;
        let side = match self.budget_rays() {
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
        let rows = match self.budget_rays() {
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

    #[test]
    fn before_any_timing_the_preview_is_small_and_batches_short() {
        let pacer = Pacer::new(40 * MS);
        assert_eq!(pacer.estimate(1000), None);
        assert!(!pacer.fits(1));
        assert_eq!(pacer.preview_size((480, 240), 1), (48, 24));
        assert_eq!(pacer.rows(480, 1, 100), 8);
        assert_eq!(pacer.rows(480, 1, 3), 3);
    }

    #[test]
    fn a_fast_renderer_gets_whole_frames() {
        let mut pacer = Pacer::new(40 * MS);
        // 1 ns per ray: 40 million rays per budget.
        pacer.record(1_000_000, MS);
        assert!(pacer.fits(512 * 512));
        assert_eq!(pacer.preview_size((512, 512), 2), (512, 512));
        assert_eq!(pacer.rows(512, 2, 512), 512);
    }

    #[test]
    fn a_slow_renderer_gets_a_preview_within_the_budget() {
        let mut pacer = Pacer::new(40 * MS);
        // 25 us per ray: 1600 rays per budget (lavapipe on a loaded CPU).
        pacer.record(4000, 100 * MS);
        assert!(!pacer.fits(400 * 300));
        let (w, h) = pacer.preview_size((400, 300), 1);
        assert_eq!((w, h), (46, 35));
        assert!(u64::from(w * h) <= 1700);
        // Two views share the budget.
        let (w2, _) = pacer.preview_size((400, 300), 2);
        assert!(w2 < w);
        assert_eq!(pacer.rows(400, 1, 300), 4);
        assert_eq!(pacer.rows(4000, 1, 300), 1, "at least one row");
    }

    #[test]
    fn the_estimate_follows_the_newest_batches() {
        let mut pacer = Pacer::new(40 * MS);
        pacer.record(1000, 10 * MS);
        pacer.record(1000, 30 * MS);
        assert_eq!(pacer.estimate(1000), Some(20 * MS));
        pacer.record(0, 100 * MS);
        assert_eq!(
            pacer.estimate(1000),
            Some(20 * MS),
            "empty batches are ignored"
        );
    }
}
