//! The cells left out of the walk (tangled, overlapping a neighbour; see
//! `tetray_mesh`'s exclusion), composited where the walk leaves a hole.
//!
//! A left-out cell leaves a hole in the walked mesh, bounded by its faces.
//! Its tetrahedra are kept with the signs of their volumes against the
//! mesh's orientation (a tangled cell's folded-back ones, or an inverted
//! cell's, negative). Along a ray, each tetrahedron crossed gives an interval with
//! its sign and the scalar linear over it. Between two boundary crossings
//! of the walk (a gap, where the walk's mesh has nothing), the ray is cut
//! at every interval end; on each piece the signs of the intervals
//! covering it sum to the winding number of the left-out cells' faces
//! around it, which is 1 inside a hole. Pieces with a positive sum are
//! integrated once, with the scalar the signed mean of the covering
//! intervals' (each linear, so the mean is linear over the piece). A
//! constant field therefore gives the hole's exact Beer-Lambert light, and
//! a linear field over an unfolded cell its exact integral; where a folded
//! cell's pieces overlap, their scalars are blended by sign.
//!
//! The CPU ray caster and the GPU kernel (`shaders/overlaps.wgsl`) do the
//! same operations: [`line_meets_box`] against the bounds of the left-out
//! points, [`collect_crossings`] once per ray (at most
//! [`MAX_OVERLAP_CROSSINGS`] kept; a ray that meets more counts an
//! overflow), then [`window_segments`] per gap.

use glam::Vec3;
use tetray_mesh::FACE_VERTICES;

/// The most left-out tetrahedra one ray keeps; the rest are dropped and
/// the ray counted (`WalkCounters::overlap_overflows`).
pub const MAX_OVERLAP_CROSSINGS: usize = 32;

/// The tetrahedra of the left-out cells, over the scene's points.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overlaps {
    /// Point indices (the scene's numbering), oriented as kept: a
    /// tetrahedron's signed volume is its sign.
    pub tets: Vec<[u32; 4]>,
    /// Bounds of their points (`lo > hi` when there are none).
    pub bounds: (Vec3, Vec3),
}

impl Overlaps {
    /// The overlaps `tets` over `points` (position and scalar per point).
    pub fn new(tets: Vec<[u32; 4]>, points: &[[f32; 4]]) -> Overlaps {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for t in &tets {
            for &v in t {
                let p = Vec3::from_slice(&points[v as usize][..3]);
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        Overlaps {
            tets,
            bounds: (lo, hi),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.tets.is_empty()
    }

    /// Whether the line `origin + t dir` may meet a left-out tetrahedron
    /// (slab test against [`Overlaps::bounds`]; any `t`, behind the origin
    /// too, since a walk may start behind it).
    pub fn line_meets_bounds(&self, origin: Vec3, dir: Vec3) -> bool {
        let (lo, hi) = self.bounds;
        !self.tets.is_empty() && line_meets_box(lo, hi, origin, dir)
    }
}

/// Whether the line `origin + t dir` (any `t`) meets the box `[lo, hi]`:
/// the slab test the kernel's `find_holes` makes.
pub fn line_meets_box(lo: Vec3, hi: Vec3, origin: Vec3, dir: Vec3) -> bool {
    let mut near = f32::NEG_INFINITY;
    let mut far = f32::INFINITY;
    for axis in 0..3 {
        let (o, d) = (origin[axis], dir[axis]);
        if d == 0.0 {
            if o < lo[axis] || o > hi[axis] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[axis] - o) / d, (hi[axis] - o) / d);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    near <= far
}

/// Appends to `out` the crossings of the tetrahedra `tets` (in order) by a
/// ray, each tetrahedron's vertices given by `vertex` (projected into the
/// ray's frame, the scalar in the fourth lane), until `out` holds
/// [`MAX_OVERLAP_CROSSINGS`]; returns whether a crossing was left out.
pub fn collect_crossings(
    tets: &[[u32; 4]],
    vertex: impl Fn(u32) -> [f32; 4],
    out: &mut Vec<OverlapCrossing>,
) -> bool {
    for tet in tets {
        if let Some(c) = OverlapCrossing::of_tet(tet.map(&vertex)) {
            if out.len() == MAX_OVERLAP_CROSSINGS {
                return true;
            }
            out.push(c);
        }
    }
    false
}

/// Where a ray crosses one left-out tetrahedron.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OverlapCrossing {
    pub t_in: f32,
    pub t_out: f32,
    pub s_in: f32,
    pub s_out: f32,
    /// +1 for a positively oriented tetrahedron, -1 for an inverted one.
    pub sign: f32,
}

impl OverlapCrossing {
    /// The crossing of a tetrahedron whose vertices, in its own order, are
    /// `v` projected into the ray's frame (x and y across the ray, z along
    /// it, w the scalar), or `None` when the ray misses it. A face the ray
    /// passes through has edge functions of one sign; the entry face's
    /// (the nearer one) are negative when the tetrahedron is positive.
    pub fn of_tet(v: [[f32; 4]; 4]) -> Option<OverlapCrossing> {
        let mut first: Option<(f32, f32, f32)> = None;
        let mut last: Option<(f32, f32)> = None;
        for face in FACE_VERTICES {
            let [a, b, c] = face.map(|i| v[i]);
            let edge = |p: [f32; 4], q: [f32; 4]| p[0] * q[1] - p[1] * q[0];
            let (wa, wb, wc) = (edge(b, c), edge(c, a), edge(a, b));
            let inside =
                (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) || (wa <= 0.0 && wb <= 0.0 && wc <= 0.0);
            let sum = wa + wb + wc;
            if !inside || sum == 0.0 {
                continue;
            }
            let t = (wa * a[2] + wb * b[2] + wc * c[2]) / sum;
            let s = (wa * a[3] + wb * b[3] + wc * c[3]) / sum;
            if first.is_none_or(|f| t < f.0) {
                first = Some((t, s, sum));
            }
            if last.is_none_or(|l| t > l.0) {
                last = Some((t, s));
            }
        }
        let ((t_in, s_in, entry_sum), (t_out, s_out)) = (first?, last?);
        (t_out > t_in).then_some(OverlapCrossing {
            t_in,
            t_out,
            s_in,
            s_out,
            sign: if entry_sum < 0.0 { 1.0 } else { -1.0 },
        })
    }

    /// The scalar at distance `t` (linear over the crossing).
    fn scalar_at(&self, t: f32) -> f32 {
        self.s_in + (self.s_out - self.s_in) * ((t - self.t_in) / (self.t_out - self.t_in))
    }
}

/// The pieces of the gap `a..b` of a ray (`a` at least 0: nothing behind
/// the eye is integrated) that the left-out cells `crossings` fill, front
/// to back: `emit(start, front scalar, back scalar, length)` for each
/// piece whose covering signs sum to 1 or more (see the module docs).
pub fn window_segments(
    crossings: &[OverlapCrossing],
    a: f32,
    b: f32,
    mut emit: impl FnMut(f32, f32, f32, f32),
) {
    let mut e = a;
    // Each piece ends at a crossing's end: at most two per crossing.
    for _ in 0..=2 * crossings.len() {
        if e >= b {
            return;
        }
        let mut n = b;
        for c in crossings {
            if c.t_in > e && c.t_in < n {
                n = c.t_in;
            }
            if c.t_out > e && c.t_out < n {
                n = c.t_out;
            }
        }
        let mid = 0.5 * (e + n);
        let (mut w, mut front, mut back) = (0.0f32, 0.0f32, 0.0f32);
        for c in crossings {
            if c.t_in < mid && mid < c.t_out {
                w += c.sign;
                front += c.sign * c.scalar_at(e);
                back += c.sign * c.scalar_at(n);
            }
        }
        if w >= 1.0 {
            emit(e, front / w, back / w, n - e);
        }
        e = n;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crossing(t_in: f32, t_out: f32, s_in: f32, s_out: f32, sign: f32) -> OverlapCrossing {
        OverlapCrossing {
            t_in,
            t_out,
            s_in,
            s_out,
            sign,
        }
    }

    fn pieces(crossings: &[OverlapCrossing], a: f32, b: f32) -> Vec<[f32; 4]> {
        let mut out = Vec::new();
        window_segments(crossings, a, b, |t, f, k, l| out.push([t, f, k, l]));
        out
    }

    #[test]
    fn a_unit_tetrahedron_is_crossed_where_its_faces_are() {
        // The ray is the z axis (x = y = 0); the tetrahedron spans z 1..3
        // around it, positive, scalar = z.
        let v = [
            [-1.0, -1.0, 1.0, 1.0],
            [3.0, -1.0, 1.0, 1.0],
            [-1.0, 3.0, 1.0, 1.0],
            [0.0, 0.0, 3.0, 3.0],
        ];
        // Orient it positively in these coordinates.
        let d = |p: [f32; 4], q: [f32; 4]| Vec3::new(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
        let volume = |v: [[f32; 4]; 4]| d(v[0], v[1]).dot(d(v[0], v[2]).cross(d(v[0], v[3])));
        let positive = if volume(v) > 0.0 {
            v
        } else {
            [v[0], v[2], v[1], v[3]]
        };
        let c = OverlapCrossing::of_tet(positive).expect("crossed");
        assert_eq!(
            (c.t_in, c.t_out, c.s_in, c.s_out, c.sign),
            (1.0, 3.0, 1.0, 3.0, 1.0)
        );
        let inverted = [positive[0], positive[2], positive[1], positive[3]];
        assert_eq!(
            OverlapCrossing::of_tet(inverted).map(|c| c.sign),
            Some(-1.0)
        );
        let missed = positive.map(|p| [p[0] + 10.0, p[1], p[2], p[3]]);
        assert_eq!(OverlapCrossing::of_tet(missed), None);
    }

    #[test]
    fn signs_cancel_where_an_inverted_piece_overlaps() {
        // +[0, 4] and -[1, 2]: the hole is 0..1 and 2..4.
        let c = [
            crossing(0.0, 4.0, 0.0, 4.0, 1.0),
            crossing(1.0, 2.0, 9.0, 9.0, -1.0),
        ];
        assert_eq!(
            pieces(&c, 0.0, f32::INFINITY),
            vec![[0.0, 0.0, 1.0, 1.0], [2.0, 2.0, 4.0, 2.0]]
        );
        // Clipped to the gap 0.5..3.
        assert_eq!(
            pieces(&c, 0.5, 3.0),
            vec![[0.5, 0.5, 1.0, 0.5], [2.0, 2.0, 3.0, 1.0]]
        );
    }

    #[test]
    fn two_positive_pieces_over_one_negative_are_their_signed_mean() {
        let c = [
            crossing(0.0, 2.0, 2.0, 2.0, 1.0),
            crossing(0.0, 2.0, 4.0, 4.0, 1.0),
            crossing(0.0, 2.0, 3.0, 3.0, -1.0),
        ];
        // w = 1, scalar (2 + 4 - 3) / 1 = 3.
        assert_eq!(pieces(&c, 0.0, 5.0), vec![[0.0, 3.0, 3.0, 2.0]]);
        assert!(pieces(&[], 0.0, 5.0).is_empty());
    }

    #[test]
    fn the_bounds_test_takes_lines_through_and_beside_the_box() {
        let tets = vec![[0, 1, 2, 3]];
        let points = [
            [0.0, 0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ];
        let o = Overlaps::new(tets, &points);
        assert!(o.line_meets_bounds(Vec3::new(0.5, 0.5, -5.0), Vec3::Z));
        assert!(
            o.line_meets_bounds(Vec3::new(0.5, 0.5, 5.0), Vec3::Z),
            "behind the origin"
        );
        assert!(!o.line_meets_bounds(Vec3::new(1.5, 0.5, -5.0), Vec3::Z));
        assert!(!Overlaps::default().line_meets_bounds(Vec3::ZERO, Vec3::Z));
    }
}
