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
use tetray_core::watertight::{Projector, RayPoint, crossing_barycentric, edge_sign};
use tetray_integrate::fastmath::{clamp_f32, max_f32, min_f32};
use tetray_wide::lanes;

/// One vertex in the frame of a ray: its position across the ray (`x`,
/// `y`, in f64 so that edge functions are exact), its distance along the
/// ray, its scalar and its point index.
#[derive(Clone, Copy)]
pub(crate) struct Vertex {
    pub x: f64,
    pub y: f64,
    pub z: f32,
    pub s: f32,
    pub id: u32,
}

impl Vertex {
    /// Point `id` (position and scalar) projected into a ray's frame.
    #[inline(always)]
    pub fn load(points: &[[f32; 4]], ray: &Projector, id: u32) -> Vertex {
        let (p, s) = ray.project_keep_w(Vec4::from_array(points[id as usize]));
        let [x, y] = lanes::widen_pair(p.to_array());
        Vertex {
            x,
            y,
            z: p.z,
            s,
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
pub(crate) const NONE: u8 = 3;

/// For the signs of `E(d, v_i)` (bit `i` set when positive), the slot `k`
/// of the entry face that the exit face leaves out: the exit is
/// `(v_{k+1}, v_{k+2}, d)`, whose edges are all positive exactly when
/// `E(d, v_{k+1}) > 0` and `E(d, v_{k+2}) < 0` (its third edge is the entry
/// face's, positive already); 3 where all signs agree. The GPU kernel
/// holds the same table.
pub const LEFT_OUT_SLOT: [u8; 8] = [NONE, 2, 0, 0, 1, 2, 1, NONE];
/// The slots following and preceding slot `k` in the face's cyclic order.
pub(crate) const FOLLOWING: [usize; 4] = [1, 2, 0, 0];
pub(crate) const PRECEDING: [usize; 4] = [2, 0, 1, 0];

/// The face a ray entered its current tetrahedron through: three vertices
/// in the cyclic order in which the ray sees every edge positive, and
/// `edge[i] = E(v_i, v_{i+1})`, each quantity in an array of its own (so
/// that the three new edge functions of an exit are one vector operation).
/// Slot 3 is unused (slots are masked to two bits, so indexing needs no
/// bounds check).
#[derive(Clone, Copy)]
pub(crate) struct Face {
    pub x: [f64; 4],
    pub y: [f64; 4],
    pub z: [f32; 4],
    pub s: [f32; 4],
    pub id: [u32; 4],
    pub edge: [f64; 4],
}

impl Face {
    pub const EMPTY: Face = Face {
        x: [0.0; 4],
        y: [0.0; 4],
        z: [0.0; 4],
        s: [0.0; 4],
        id: [0; 4],
        edge: [0.0; 4],
    };

    /// The vertex in slot `i`.
    #[inline(always)]
    fn vertex(&self, i: usize) -> Vertex {
        Vertex {
            x: self.x[i],
            y: self.y[i],
            z: self.z[i],
            s: self.s[i],
            id: self.id[i],
        }
    }

    /// Puts `v` in slot `i`.
    #[inline(always)]
    fn set(&mut self, i: usize, v: Vertex) {
        self.x[i] = v.x;
        self.y[i] = v.y;
        self.z[i] = v.z;
        self.s[i] = v.s;
        self.id[i] = v.id;
    }

    /// Enters a tetrahedron through its face with point indices `face`
    /// (in the tetrahedron's order, [`tetray_mesh::FACE_VERTICES`], in
    /// which all of its edges are negative, as for every face a ray enters
    /// through): the face, and the scalar at the crossing.
    #[inline]
    pub fn enter(points: &[[f32; 4]], ray: &Projector, face: [u32; 3]) -> (Face, f32) {
        let [a, b, c] = face.map(|id| Vertex::load(points, ray, id));
        let (_, w) = crossing_barycentric(a.point(), b.point(), c.point());
        let value = w[0] * f64::from(a.s) + w[1] * f64::from(b.s) + w[2] * f64::from(c.s);
        // Reversed, the face's edges are positive.
        let mut face = Face::EMPTY;
        for (i, v) in [a, c, b].into_iter().enumerate() {
            face.set(i, v);
        }
        face.edge = [a.edge(&c), c.edge(&b), b.edge(&a), 0.0];
        (face, value as f32)
    }

    /// The rank of point index `id` among those of the tetrahedron made of
    /// this face and `d` (how many of the four are smaller; `id` is one of
    /// them): the slot of the neighbour across the face opposite `id`.
    #[inline(always)]
    fn rank(&self, d: u32, id: u32) -> usize {
        let mut ids = self.id;
        ids[3] = d;
        tetray_scene::vertex_rank(ids, id)
    }

    /// Leaves the tetrahedron whose vertex opposite this face is `d`:
    /// `(rank of the entry face's vertex not on the exit face among the
    /// tetrahedron's four, distance, scalar)` at the exit face, or `None`
    /// for a degenerate cell: the rank names the neighbour across the exit
    /// face. The exit face becomes this face: the next cell's entry face.
    ///
    /// The distance and scalar are barycentric in the exit face's edge
    /// functions, with `d`, then the vertices following and preceding it.
    #[inline(always)]
    pub fn exit(&mut self, d: Vertex) -> Option<(usize, f32, f32)> {
        // E(d, v_i) of the three slots (and of the unused fourth) at once,
        // with `Vertex::edge`'s operations.
        let e: [f64; 4] = std::array::from_fn(|i| d.x * self.y[i] - d.y * self.x[i]);
        // Which face the ray leaves through is as good as random, so the
        // signs are combined without branches (a branch per sign costs
        // about one misprediction per step); an exact zero, rare, takes
        // the symbolic perturbation's side.
        // Slot 3 is left out. The edge functions are finite (products of
        // finite f32 values), so their product is zero when one is; one
        // that underflows to zero only sends the signs the longer way, to
        // the same answer.
        let code = if e[0] * e[1] * e[2] == 0.0 {
            let mut code = 0;
            for (i, &edge) in e[..3].iter().enumerate() {
                code |= usize::from(d.positive(&self.vertex(i), edge)) << i;
            }
            code
        } else {
            (lanes::positive_mask(e) & 7) as usize
        };
        let k = LEFT_OUT_SLOT[code];
        if k == NONE {
            return None;
        }
        let k = usize::from(k & 3);
        let (next, prev) = (FOLLOWING[k], PRECEDING[k]);
        // Weights of (d, next, prev): each the edge function of the
        // opposite edge, with E(prev, d) = -E(d, prev) exactly.
        let w = [self.edge[next], -e[prev], e[next]];
        let z = [d.z, self.z[next], self.z[prev]];
        let s = [d.s, self.s[next], self.s[prev]];
        let lo = min_f32(min_f32(z[0], z[1]), z[2]);
        let hi = max_f32(max_f32(z[0], z[1]), z[2]);
        let sum = w[0] + w[1] + w[2];
        let (t, value) = if sum == 0.0 {
            // The ray in the face's plane: any point of the face is the
            // crossing; take the nearest vertex, as crossing_distance does.
            let value = if lo == z[0] {
                s[0]
            } else if lo == z[1] {
                s[1]
            } else {
                s[2]
            };
            (lo, value)
        } else {
            let inv = 1.0 / sum;
            let t =
                (w[0] * f64::from(z[0]) + w[1] * f64::from(z[1]) + w[2] * f64::from(z[2])) * inv;
            let value =
                (w[0] * f64::from(s[0]) + w[1] * f64::from(s[1]) + w[2] * f64::from(s[2])) * inv;
            (clamp_f32(t as f32, lo, hi), value as f32)
        };
        // Ranked before the face changes, from the indices at hand.
        let rank = self.rank(d.id, self.id[k]);
        // The exit face in cyclic order (d, next, prev): d takes slot k.
        self.set(k, d);
        self.edge[k] = e[next];
        self.edge[prev] = -e[prev];
        Some((rank, t, value))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use glam::Vec3;
    use tetray_core::watertight::{RayFrame, cross_triangle};
    use tetray_mesh::FACE_VERTICES;

    use super::*;

    struct Rng(u32);

    impl Rng {
        fn unit(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 17;
            self.0 ^= self.0 << 5;
            self.0 as f32 / u32::MAX as f32
        }
    }

    /// A random tetrahedron entered through a random face by a ray aimed
    /// at a random interior point, where the shared predicate finds one
    /// exit face.
    #[derive(Clone, Copy)]
    pub(crate) struct Entered {
        p: [Vec3; 4],
        /// The entry face and the exit face (the face opposite vertex g
        /// is face g).
        entry: usize,
        exit: usize,
        ray: RayFrame,
        pub face: Face,
        pub apex: Vertex,
    }

    fn random_entered(rng: &mut Rng) -> Option<Entered> {
        let mut p: [Vec3; 4] =
            std::array::from_fn(|_| Vec3::new(rng.unit(), rng.unit(), rng.unit()) * 2.0 - 1.0);
        let f = ((rng.unit() * 4.0) as usize).min(3);
        let [i, j, k] = FACE_VERTICES[f];
        let weights = [rng.unit(), rng.unit(), rng.unit()];
        let sum = weights[0] + weights[1] + weights[2];
        let on_face = (p[i] * weights[0] + p[j] * weights[1] + p[k] * weights[2]) / sum;
        let inside = (p[0] + p[1] + p[2] + p[3]) * 0.25;
        let ray = RayFrame::new(on_face - (inside - on_face) * 3.0, inside - on_face);
        let crossing = |p: &[Vec3; 4], g: usize| {
            let [a, b, c] = FACE_VERTICES[g].map(|v| ray.project(p[v]));
            cross_triangle(a, b, c)
        };
        if !crossing(&p, f).is_some_and(|c| c.entering) {
            // Negatively oriented: swapping two of face f's vertices
            // keeps the face and turns the tetrahedron over.
            p.swap(i, j);
            if !crossing(&p, f).is_some_and(|c| c.entering) {
                return None;
            }
        }
        let leaving: Vec<usize> = (0..4)
            .filter(|&g| g != f && crossing(&p, g).is_some_and(|c| !c.entering))
            .collect();
        let [exit] = leaving[..] else {
            return None;
        };
        let points: Vec<[f32; 4]> = p.iter().map(|v| [v.x, v.y, v.z, v.x]).collect();
        let projector = Projector::new(&ray);
        let entry = FACE_VERTICES[f].map(|v| v as u32);
        let (face, _) = Face::enter(&points, &projector, entry);
        let apex = Vertex::load(&points, &projector, f as u32);
        Some(Entered {
            p,
            entry: f,
            exit,
            ray,
            face,
            apex,
        })
    }

    /// Up to `tries` random entered tetrahedra ([`random_entered`]).
    pub(crate) fn random_entries(tries: usize) -> Vec<Entered> {
        let mut rng = Rng(0x2545_f491);
        (0..tries)
            .filter_map(|_| random_entered(&mut rng))
            .collect()
    }

    /// Random tetrahedra, each entered through a random face by a ray aimed
    /// at a random interior point: the face the carried-face exit leaves
    /// through is the one face the shared predicate says the ray leaves
    /// through, and the new entry face's edges are those of that face.
    #[test]
    fn the_exit_is_the_face_the_ray_leaves_through() {
        let entries = random_entries(20_000);
        for entered in &entries {
            let Entered {
                p,
                entry: f,
                exit,
                ray,
                mut face,
                apex,
            } = *entered;
            let Some((rank, t, _)) = face.exit(apex) else {
                panic!("no exit from {p:?} entered through {f}");
            };
            // Point indices 0 to 3: a vertex's rank is its index.
            assert_eq!(rank, exit, "{p:?} entered through {f}");
            let z = FACE_VERTICES[exit].map(|v| ray.project(p[v]).z);
            assert!(t >= z[0].min(z[1]).min(z[2]) && t <= z[0].max(z[1]).max(z[2]));
            // The carried face is the exit face, every edge positive.
            for s in 0..3 {
                let (a, b) = (face.vertex(s), face.vertex((s + 1) % 3));
                assert_eq!(face.edge[s].to_bits(), a.edge(&b).to_bits());
                assert!(a.positive(&b, face.edge[s]), "{p:?} entered through {f}");
            }
        }
        assert!(
            entries.len() > 15_000,
            "only {} tetrahedra checked",
            entries.len()
        );
    }

    /// The carried face and the XOR give the fourth vertex, and the rank
    /// of each vertex the exit may leave out is the scene's.
    #[test]
    fn the_record_names_the_apex_and_the_neighbour() {
        let verts = [7, 3, 11, 5];
        let xor = verts.iter().fold(0, |x, &v| x ^ v);
        for skip in 0..4 {
            let mut face = Face::EMPTY;
            let others = (0..4).filter(|&i| i != skip).map(|i| verts[i]);
            for (slot, id) in others.enumerate() {
                face.id[slot] = id;
            }
            let mut lanes = crate::exits::Lanes::<1>::new();
            lanes.set_face(0, &face);
            let apex = lanes.opposite(0, xor);
            assert_eq!(apex, verts[skip]);
            for &id in &face.id[..3] {
                assert_eq!(face.rank(apex, id), tetray_scene::vertex_rank(verts, id));
            }
        }
    }
}
