//! What a walk carries from one tetrahedron to the next: the face the ray
//! entered through, in the ray's frame. The next cell shares that face, so
//! of each new cell only the vertex opposite it is loaded and projected;
//! the three shared vertices and their edge functions come along.
//!
//! Edge functions `E(p, q) = x_p y_q - y_p x_q` of the projections are
//! exact in f64 (products of two f32 values) and exactly antisymmetric, so
//! an edge function carried over has the bits it would have if computed
//! anew: the walk is the one that projects every vertex of every cell.

use glam::Vec4;
use tetray_boundary_bvh::watertight::{crossing_barycentric, edge_sign, Projector, RayPoint};
use tetray_integrate::fastmath::{clamp_f32, max_f32, min_f32};
use tetray_mesh::FACE_VERTICES;

/// One vertex in the frame of a ray: its position across the ray (`x`,
/// `y`, in f64 so that edge functions are exact), its distance along the
/// ray, its scalar and its point index.
#[derive(Clone, Copy)]
pub(crate) struct Vertex {
    x: f64,
    y: f64,
    z: f32,
    s: f32,
    id: u32,
}

impl Vertex {
    const EMPTY: Vertex = Vertex {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        s: 0.0,
        id: 0,
    };

    /// Point `id` (position and scalar) projected into a ray's frame.
    #[inline(always)]
    pub fn load(points: &[[f32; 4]], ray: &Projector, id: u32) -> Vertex {
        let q = Vec4::from_array(points[id as usize]);
        let p = ray.project(q);
        Vertex {
            x: f64::from(p.x),
            y: f64::from(p.y),
            z: p.z,
            s: q.w,
            id,
        }
    }

    #[inline]
    fn point(&self) -> RayPoint {
        RayPoint {
            x: self.x as f32,
            y: self.y as f32,
            z: self.z,
        }
    }

    /// Edge function of the directed edge `self -> other` (exact).
    #[inline(always)]
    fn edge(&self, other: &Vertex) -> f64 {
        self.x * other.y - self.y * other.x
    }

    /// Whether the edge `self -> other` is positive, an exact zero (the ray
    /// through the edge) taking the symbolic perturbation's side.
    #[inline(always)]
    fn positive(&self, other: &Vertex, edge: f64) -> bool {
        if edge != 0.0 {
            edge > 0.0
        } else {
            edge_sign(self.point(), other.point()) > 0
        }
    }
}

/// No exit face (the sign patterns of a degenerate tetrahedron).
const NONE: u8 = 3;

/// For the signs of `E(d, v_i)` (bit `i` set when positive), the slot `k`
/// of the entry face that the exit face leaves out: the exit is
/// `(v_{k+1}, v_{k+2}, d)`, whose edges are all positive exactly when
/// `E(d, v_{k+1}) > 0` and `E(d, v_{k+2}) < 0` (its third edge is the entry
/// face's, positive already).
const EXCLUDED: [u8; 8] = [NONE, 2, 0, 0, 1, 2, 1, NONE];
/// The slots following and preceding slot `k` in the face's cyclic order.
const FOLLOWING: [usize; 4] = [1, 2, 0, 0];
const PRECEDING: [usize; 4] = [2, 0, 1, 0];

/// The face a ray entered its current tetrahedron through: three vertices
/// in the cyclic order in which the ray sees every edge positive, and
/// `edge[i] = E(v_i, v_{i+1})`. Slot 3 is unused (slots are masked to two
/// bits, so indexing needs no bounds check).
#[derive(Clone, Copy)]
pub(crate) struct Face {
    v: [Vertex; 4],
    edge: [f64; 4],
}

impl Face {
    pub const EMPTY: Face = Face {
        v: [Vertex::EMPTY; 4],
        edge: [0.0; 4],
    };

    /// Enters the tetrahedron with point indices `verts` through its local
    /// face `f` (all of whose edges are negative in the tetrahedron's own
    /// order, as for every face a ray enters through): the face, and the
    /// scalar at the crossing.
    #[inline]
    pub fn enter(points: &[[f32; 4]], ray: &Projector, verts: [u32; 4], f: usize) -> (Face, f32) {
        let [a, b, c] = FACE_VERTICES[f].map(|i| Vertex::load(points, ray, verts[i]));
        let (_, w) = crossing_barycentric(a.point(), b.point(), c.point());
        let value = w[0] * f64::from(a.s) + w[1] * f64::from(b.s) + w[2] * f64::from(c.s);
        // Reversed, the face's edges are positive.
        let face = Face {
            v: [a, c, b, Vertex::EMPTY],
            edge: [a.edge(&c), c.edge(&b), b.edge(&a), 0.0],
        };
        (face, value as f32)
    }

    /// Leaves the tetrahedron whose vertex opposite this face is `d`:
    /// `(point index of the entry face's vertex not on the exit face,
    /// distance, scalar)` at the exit face, or `None` for a degenerate
    /// cell. The exit face becomes this face: the next cell's entry face.
    ///
    /// The distance and scalar are barycentric in the exit face's edge
    /// functions, with `d`, then the vertices following and preceding it.
    #[inline(always)]
    pub fn exit(&mut self, d: Vertex) -> Option<(u32, f32, f32)> {
        let e = [d.edge(&self.v[0]), d.edge(&self.v[1]), d.edge(&self.v[2])];
        let mut code = 0;
        for (i, &edge) in e.iter().enumerate() {
            code |= usize::from(d.positive(&self.v[i], edge)) << i;
        }
        let k = EXCLUDED[code];
        if k == NONE {
            return None;
        }
        let k = usize::from(k & 3);
        let (next, prev) = (FOLLOWING[k], PRECEDING[k]);
        let (vn, vp) = (self.v[next], self.v[prev]);
        // Weights of (d, next, prev): each the edge function of the
        // opposite edge, with E(prev, d) = -E(d, prev) exactly.
        let w = [self.edge[next], -e[prev], e[next]];
        let z = [d.z, vn.z, vp.z];
        let s = [d.s, vn.s, vp.s];
        let lo = min_f32(min_f32(z[0], z[1]), z[2]);
        let hi = max_f32(max_f32(z[0], z[1]), z[2]);
        let sum = w[0] + w[1] + w[2];
        let (t, value) = if sum == 0.0 {
            // The ray in the face's plane: any point of the face is the
            // crossing; take the nearest vertex, as crossing_distance does.
            let i = if lo == z[0] {
                0
            } else if lo == z[1] {
                1
            } else {
                2
            };
            (lo, s[i])
        } else {
            let inv = 1.0 / sum;
            let t =
                (w[0] * f64::from(z[0]) + w[1] * f64::from(z[1]) + w[2] * f64::from(z[2])) * inv;
            let value =
                (w[0] * f64::from(s[0]) + w[1] * f64::from(s[1]) + w[2] * f64::from(s[2])) * inv;
            (clamp_f32(t as f32, lo, hi), value as f32)
        };
        let left_out = self.v[k].id;
        // The exit face in cyclic order (d, next, prev): d takes slot k.
        self.v[k] = d;
        self.edge[k] = e[next];
        self.edge[prev] = -e[prev];
        Some((left_out, t, value))
    }
}

/// The local index in `verts` of point `id` (one of them).
#[inline(always)]
pub(crate) fn local_index(verts: [u32; 4], id: u32) -> usize {
    usize::from(verts[1] == id)
        | (usize::from(verts[2] == id) << 1)
        | (usize::from(verts[3] == id) * 3)
}
