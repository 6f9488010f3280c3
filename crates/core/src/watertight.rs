//! The watertight ray / triangle predicate shared by the BVH (entry faces) and
//! the ray caster (exit faces), so both agree on which face a ray crosses.
//!
//! Every point is projected once per ray into a frame whose third axis is the
//! ray direction: `x, y` across the ray, `z` the distance along it. Edge
//! functions are evaluated in f64 on the f32 projections, which is exact: the
//! sign of a 2x2 determinant of f32 values never rounds wrong in f64. When an
//! edge function is exactly zero (the ray passes through an edge or a vertex)
//! the tie is broken by simulation of simplicity: the ray origin is moved by
//! `(eps, eps^2)` in the projected plane, which depends only on the edge, so
//! two faces sharing an edge always disagree and a fan of faces around a
//! vertex claims the ray exactly once. Rays therefore never leak between
//! faces, never cross two at once and never loop.

use glam::{Vec3, Vec4};

/// A point in the frame of one ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayPoint {
    pub x: f32,
    pub y: f32,
    /// Signed distance along the (unit) ray direction from its origin.
    pub z: f32,
}

/// A ray with an orthonormal frame around its direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayFrame {
    pub origin: Vec3,
    /// Unit direction.
    pub dir: Vec3,
    u: Vec3,
    v: Vec3,
}

impl RayFrame {
    /// `dir` need not be normalised; it must be finite and non-zero.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        let dir = dir.normalize();
        // Duff et al. 2017 branchless basis: exact for axis-aligned directions.
        let sign = 1.0f32.copysign(dir.z);
        let a = -1.0 / (sign + dir.z);
        let b = dir.x * dir.y * a;
        let u = Vec3::new(1.0 + sign * dir.x * dir.x * a, sign * b, -sign * dir.x);
        let v = Vec3::new(b, sign + dir.y * dir.y * a, -dir.y);
        Self { origin, dir, u, v }
    }

    /// Projects a point into this ray's frame. The same point always projects
    /// to the same bits, which is what makes shared edges agree.
    #[inline(always)]
    pub fn project(&self, p: Vec3) -> RayPoint {
        let d = p - self.origin;
        RayPoint {
            x: d.dot(self.u),
            y: d.dot(self.v),
            z: d.dot(self.dir),
        }
    }

    /// The world position at distance `t` along the ray.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Side of the ray relative to the directed edge `a -> b`: `+1` or `-1`, with
/// ties broken symbolically; `0` only when the edge is parallel to the ray
/// (its projection is a single point), which no perturbation can resolve.
/// Antisymmetric: `edge_sign(a, b) == -edge_sign(b, a)` always.
#[inline(always)]
pub fn edge_sign(a: RayPoint, b: RayPoint) -> i8 {
    let e = f64::from(a.x) * f64::from(b.y) - f64::from(a.y) * f64::from(b.x);
    if e != 0.0 {
        return if e > 0.0 { 1 } else { -1 };
    }
    // Origin moved by (eps, eps^2): e' = e - eps * ey + eps^2 * ex.
    let ey = f64::from(b.y) - f64::from(a.y);
    if ey != 0.0 {
        return if ey < 0.0 { 1 } else { -1 };
    }
    let ex = f64::from(b.x) - f64::from(a.x);
    if ex > 0.0 {
        1
    } else if ex < 0.0 {
        -1
    } else {
        0
    }
}

/// How a ray crosses a triangle given counter-clockwise seen from outside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// True when the ray goes from outside to inside (against the normal).
    pub entering: bool,
    /// Distance along the ray to the crossing point.
    pub t: f32,
}

/// Where the ray crosses triangle `(a, b, c)`, if it does. All three edge
/// signs negative: entering; all positive: leaving.
#[inline(always)]
pub fn cross_triangle(a: RayPoint, b: RayPoint, c: RayPoint) -> Option<Crossing> {
    let sab = edge_sign(a, b);
    let sbc = edge_sign(b, c);
    let sca = edge_sign(c, a);
    if sab == 0 || sab != sbc || sbc != sca {
        return None;
    }
    Some(Crossing {
        entering: sab < 0,
        t: crossing_distance(a, b, c),
    })
}

/// Where the ray enters through triangle `(a, b, c)` (counter-clockwise
/// seen from outside), if it does: [`cross_triangle`]'s distance when its
/// crossing is entering, found by stopping at the first edge sign that rules
/// an entry out (the same answer, with fewer steps for faces it misses).
#[inline(always)]
pub fn entry_distance(a: RayPoint, b: RayPoint, c: RayPoint) -> Option<f32> {
    if edge_sign(a, b) >= 0 || edge_sign(b, c) >= 0 || edge_sign(c, a) >= 0 {
        return None;
    }
    Some(crossing_distance(a, b, c))
}

/// Distance along the ray to the plane of `(a, b, c)` where the ray crosses
/// it, from barycentric weights of the projected triangle. Clamped into the
/// range of the vertex distances so rounding cannot move it off the face.
#[inline(always)]
pub fn crossing_distance(a: RayPoint, b: RayPoint, c: RayPoint) -> f32 {
    let wa = edge_function(b, c);
    let wb = edge_function(c, a);
    let wc = edge_function(a, b);
    let sum = wa + wb + wc;
    let lo = a.z.min(b.z).min(c.z);
    let hi = a.z.max(b.z).max(c.z);
    if sum == 0.0 {
        // The ray lies in the plane of the face (only reached through a tie):
        // any distance on the face is the crossing; take the nearest.
        return lo;
    }
    let t = (wa * f64::from(a.z) + wb * f64::from(b.z) + wc * f64::from(c.z)) / sum;
    (t as f32).clamp(lo, hi)
}

/// The 2-D edge function of `a -> b` about the ray (twice the signed area of
/// the triangle origin, a, b in the projected plane).
#[inline(always)]
pub fn edge_function(a: RayPoint, b: RayPoint) -> f64 {
    f64::from(a.x) * f64::from(b.y) - f64::from(a.y) * f64::from(b.x)
}

/// Where the ray crosses the plane of `(a, b, c)`: the distance, bit for bit
/// that of [`crossing_distance`], and the barycentric weights of the
/// crossing point (summing to 1), to interpolate vertex data (scalars) at
/// it. Weights are the normalised edge functions, as in
/// [`crossing_distance`]; for a ray lying in the face's plane the nearest
/// vertex, whose distance is returned, gets all the weight.
#[inline(always)]
pub fn crossing_barycentric(a: RayPoint, b: RayPoint, c: RayPoint) -> (f32, [f64; 3]) {
    let wa = edge_function(b, c);
    let wb = edge_function(c, a);
    let wc = edge_function(a, b);
    let sum = wa + wb + wc;
    let lo = a.z.min(b.z).min(c.z);
    let hi = a.z.max(b.z).max(c.z);
    if sum == 0.0 {
        let weights = if lo == a.z {
            [1.0, 0.0, 0.0]
        } else if lo == b.z {
            [0.0, 1.0, 0.0]
        } else {
            [0.0, 0.0, 1.0]
        };
        return (lo, weights);
    }
    let t = (wa * f64::from(a.z) + wb * f64::from(b.z) + wc * f64::from(c.z)) / sum;
    let inv = 1.0 / sum;
    ((t as f32).clamp(lo, hi), [wa * inv, wb * inv, wc * inv])
}

/// [`RayFrame::project`] for one point at a time in SIMD lanes: lane `i`
/// of `columns[j]` is coordinate `j` of basis vector `i` (`u`, `v`, `dir`),
/// so `columns[0] dx + columns[1] dy + columns[2] dz` makes, in lane `i`,
/// the operations of `project`'s dot product in the same order: the same
/// bits.
#[derive(Debug, Clone, Copy)]
pub struct Projector {
    origin: Vec4,
    columns: [Vec4; 3],
}

impl Projector {
    pub fn new(ray: &RayFrame) -> Self {
        let (u, v, w) = (ray.u, ray.v, ray.dir);
        Self {
            origin: ray.origin.extend(0.0),
            columns: [
                Vec4::new(u.x, v.x, w.x, 0.0),
                Vec4::new(u.y, v.y, w.y, 0.0),
                Vec4::new(u.z, v.z, w.z, 0.0),
            ],
        }
    }

    /// The projection `(x, y, z)` of the point `(p.x, p.y, p.z)` in lanes
    /// 0 to 2 (lane 3 is not used).
    #[inline(always)]
    pub fn project(&self, p: Vec4) -> Vec4 {
        self.project_keep_w(p).0
    }

    /// [`Projector::project`], and `p.w` unchanged (the origin's lane 3
    /// is zero): a point and its scalar from one load of all four lanes.
    #[inline(always)]
    pub fn project_keep_w(&self, p: Vec4) -> (Vec4, f32) {
        let d = p - self.origin;
        let projected = self.columns[0] * Vec4::splat(d.x)
            + self.columns[1] * Vec4::splat(d.y)
            + self.columns[2] * Vec4::splat(d.z);
        (projected, d.w)
    }
}
