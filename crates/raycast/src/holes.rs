//! The cells left out of the walk, composited in the gaps they leave
//! (`tetray_scene::overlaps` for the rule): a ray finds the left-out
//! tetrahedra it crosses once, at its first entry query, and fills each
//! gap between an exit and the next entry with their pieces.

use glam::{Vec3A, Vec4};
use tetray_core::watertight::{Projector, RayFrame};
use tetray_scene::{OverlapCrossing, Scene, collect_crossings, window_segments};

/// The left-out tetrahedra one ray crosses.
#[derive(Debug, Clone, Default)]
pub(crate) struct Holes {
    /// Whether [`Holes::find`] ran for the ray.
    pub found: bool,
    crossings: Vec<OverlapCrossing>,
}

/// What [`Holes::fill`] composited in one gap.
pub(crate) struct Filled {
    pub segments: u64,
    /// Where the first piece starts.
    pub depth: f32,
    /// Whether the ray reached its early-termination opacity.
    pub opaque: bool,
}

impl Holes {
    pub fn clear(&mut self) {
        self.found = false;
        self.crossings.clear();
    }

    pub fn is_empty(&self) -> bool {
        self.crossings.is_empty()
    }

    /// Whether a crossing reaches beyond distance `t`.
    pub fn beyond(&self, t: f32) -> bool {
        self.crossings.iter().any(|c| c.t_out > t)
    }

    /// Finds the left-out tetrahedra of `scene` that `ray` crosses, the
    /// first [`MAX_OVERLAP_CROSSINGS`](tetray_scene::MAX_OVERLAP_CROSSINGS)
    /// in the scene's order; returns whether it crosses more (the ray's
    /// overflow).
    pub fn find(&mut self, scene: &Scene, ray: &RayFrame, projector: &Projector) -> bool {
        self.found = true;
        let overlaps = scene.overlaps();
        if !overlaps.line_meets_bounds(ray.origin, ray.dir) {
            return false;
        }
        let points = scene.point_records();
        let vertex = |i: u32| {
            let p = points[i as usize];
            let q = projector.project(Vec4::from_array(p));
            [q.x, q.y, q.z, p[3]]
        };
        collect_crossings(&overlaps.tets, vertex, &mut self.crossings)
    }

    /// Composites into `color` and `transmittance` the pieces of the
    /// left-out cells in the gap from `start` (clipped at the eye) to
    /// `end`, each integrated by `segment(front scalar, back scalar,
    /// length)`, until the transmittance channels sum to `stop_below_sum`
    /// or less.
    pub fn fill(
        &self,
        start: f32,
        end: f32,
        stop_below_sum: f32,
        color: &mut Vec3A,
        transmittance: &mut Vec3A,
        segment: impl Fn(f32, f32, f32) -> (Vec3A, Vec3A),
    ) -> Filled {
        let mut filled = Filled {
            segments: 0,
            depth: 0.0,
            opaque: false,
        };
        window_segments(
            &self.crossings,
            start.max(0.0),
            end,
            |t, front, back, length| {
                if filled.opaque {
                    return;
                }
                let (emitted, passed) = segment(front, back, length);
                *color += *transmittance * emitted;
                *transmittance *= passed;
                if filled.segments == 0 {
                    filled.depth = t;
                }
                filled.segments += 1;
                filled.opaque = transmittance.element_sum() <= stop_below_sum;
            },
        );
        filled
    }
}
