//! What a frame's walk counts: one struct for the CPU ray caster, the GPU
//! kernel (read back from its counter buffer), the projection and
//! shear-warp, so that every front end reports the same numbers the same
//! way.

/// Counters of one frame (or of one ray, summed with [`WalkCounters::merge`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WalkCounters {
    /// Rays cast (one per pixel).
    pub rays: u64,
    /// Rays that entered the volume at least once.
    pub rays_hit: u64,
    /// Segments integrated (for shear-warp: slabs composited).
    pub segments: u64,
    /// Cells visited (for the projection: draws).
    pub steps: u64,
    /// Boundary entries found (entries and re-entries).
    pub entries: u64,
    /// Rays stopped by the step bound (a correct mesh never hits it).
    pub steps_bound_hits: u64,
    /// Rays stopped in a cell with no exit face (a degenerate cell).
    pub walk_failures: u64,
    /// Segments integrated in the cells left out of the walk, where they
    /// fill its holes (not counted in `segments`).
    pub overlap_segments: u64,
    /// Rays that met more left-out tetrahedra than a ray keeps (the rest
    /// were not composited).
    pub overlap_overflows: u64,
}

impl WalkCounters {
    /// The counters of a renderer that casts no rays of its own (the
    /// projection, shear-warp): every pixel of `image` a ray, the lit ones
    /// (alpha above 0) the rays that hit, with the segments and steps it
    /// counted (slabs composited, cells drawn).
    pub fn of_image(image: &crate::Image, segments: u64, steps: u64) -> WalkCounters {
        WalkCounters {
            rays: u64::from(image.width) * u64::from(image.height),
            rays_hit: image.rgba.iter().filter(|p| p[3] > 0.0).count() as u64,
            segments,
            steps,
            ..WalkCounters::default()
        }
    }

    /// The sum of two frames' (or two tiles') counters.
    #[must_use]
    pub fn merge(self, other: WalkCounters) -> WalkCounters {
        WalkCounters {
            rays: self.rays + other.rays,
            rays_hit: self.rays_hit + other.rays_hit,
            segments: self.segments + other.segments,
            steps: self.steps + other.steps,
            entries: self.entries + other.entries,
            steps_bound_hits: self.steps_bound_hits + other.steps_bound_hits,
            walk_failures: self.walk_failures + other.walk_failures,
            overlap_segments: self.overlap_segments + other.overlap_segments,
            overlap_overflows: self.overlap_overflows + other.overlap_overflows,
        }
    }

    /// Integrated segments per second over `seconds`.
    pub fn segments_per_second(&self, seconds: f64) -> f64 {
        self.segments as f64 / seconds.max(1e-12)
    }

    /// Rays whose walk did not finish: cut by the step bound or stopped in
    /// a degenerate cell.
    pub fn unfinished(&self) -> u64 {
        self.steps_bound_hits + self.walk_failures
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merging_adds_every_counter() {
        let a = WalkCounters {
            rays: 1,
            rays_hit: 2,
            segments: 3,
            steps: 4,
            entries: 5,
            steps_bound_hits: 6,
            walk_failures: 7,
            overlap_segments: 8,
            overlap_overflows: 9,
        };
        let b = a.merge(a);
        assert_eq!(
            b,
            WalkCounters {
                rays: 2,
                rays_hit: 4,
                segments: 6,
                steps: 8,
                entries: 10,
                steps_bound_hits: 12,
                walk_failures: 14,
                overlap_segments: 16,
                overlap_overflows: 18,
            }
        );
        assert_eq!(b.unfinished(), 26);
        assert_eq!(WalkCounters::default().merge(a), a);
    }
}
