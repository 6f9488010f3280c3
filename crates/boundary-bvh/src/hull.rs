//! Faces through which a ray leaves the mesh for good: those whose plane has
//! the whole boundary (hence the whole mesh) behind it. A ray leaving
//! through such a face moves into the open half-space in front of it and
//! never meets the mesh again, so the walk needs no re-entry query there.

use glam::DVec3;
use rayon::prelude::*;

use crate::build::BoundaryBvh;

/// Points within this fraction of their distance in front of a face's plane
/// count as behind it (coplanar neighbours on flat walls, and f64 rounding
/// of the plane). A ray could only re-enter through such a sliver along a
/// chord of that relative thickness.
const COPLANAR_REL: f64 = 1e-9;

impl BoundaryBvh {
    /// Per boundary face: whether every boundary point lies behind (or on)
    /// its plane, so that a ray leaving through it cannot re-enter.
    pub fn final_exit_faces(&self) -> Vec<bool> {
        let mut first_slot = vec![usize::MAX; self.face_count()];
        for &slot in &self.face_slots {
            first_slot[self.prim_faces[slot as usize] as usize] = slot as usize;
        }
        let extremes = self.extreme_points();
        first_slot
            .par_iter()
            .map_init(Vec::new, |stack, &slot| {
                let [a, b, c] = self.prim_tris[slot].map(|p| p.as_dvec3());
                let normal = (b - a).cross(c - a);
                let normal_length = normal.length();
                normal_length > 0.0
                    && !extremes
                        .iter()
                        .any(|&q| in_front(q, a, normal, normal_length))
                    && self.all_behind(a, normal, normal_length, stack)
            })
            .collect()
    }

    /// The boundary points farthest along each of the 26 directions of
    /// `{-1, 0, 1}^3 \ 0`: most faces off the convex hull have one of them
    /// in front, which settles them without a traversal (the answer is the
    /// traversal's: the same test on a point it would reach).
    fn extreme_points(&self) -> Vec<DVec3> {
        let directions: Vec<DVec3> = (0..27)
            .filter(|&i| i != 13)
            .map(|i| {
                DVec3::new(
                    (i % 3) as f64 - 1.0,
                    (i / 3 % 3) as f64 - 1.0,
                    (i / 9) as f64 - 1.0,
                )
            })
            .collect();
        let none = || vec![(f64::NEG_INFINITY, DVec3::ZERO); directions.len()];
        let best = self
            .prim_tris
            .par_chunks(4096)
            .fold(none, |mut best, tris| {
                for q in tris.iter().flatten().map(|q| q.as_dvec3()) {
                    for (slot, d) in best.iter_mut().zip(&directions) {
                        let along = q.dot(*d);
                        if along > slot.0 {
                            *slot = (along, q);
                        }
                    }
                }
                best
            })
            .reduce(none, |a, b| {
                a.into_iter()
                    .zip(b)
                    .map(|(a, b)| if b.0 > a.0 { b } else { a })
                    .collect()
            });
        best.into_iter()
            .filter(|(along, _)| along.is_finite())
            .map(|(_, q)| q)
            .collect()
    }

    /// Whether every boundary point `q` has `(q - point) . normal <= 0`
    /// (up to [`COPLANAR_REL`]; `normal_length`: the normal's length), pruning subtrees whose boxes lie behind and
    /// descending first into the child reaching farthest in front, where a
    /// point in front is likeliest (`stack`: the traversal's, reused
    /// between calls).
    fn all_behind(
        &self,
        point: DVec3,
        normal: DVec3,
        normal_length: f64,
        stack: &mut Vec<u32>,
    ) -> bool {
        let nodes = &self.bvh.nodes;
        let abs_normal = normal.abs();
        // How far the box of node `index` reaches in front of the plane, or
        // `None` when it lies wholly behind.
        let reach = |index: u32| {
            let aabb = nodes[index as usize].aabb();
            let (lo, hi) = (aabb.min.as_dvec3(), aabb.max.as_dvec3());
            let centre = 0.5 * (lo + hi);
            let half = 0.5 * (hi - lo);
            // The box's farthest corner in front of the plane.
            let reach = (centre - point).dot(normal) + half.dot(abs_normal);
            // The slack is never negative: a box wholly behind needs no
            // square root.
            let behind = reach <= 0.0
                || reach
                    <= COPLANAR_REL * normal_length * ((centre - point).length() + half.length());
            (!behind).then_some(reach)
        };
        stack.clear();
        if reach(0).is_some() {
            stack.push(0);
        }
        while let Some(index) = stack.pop() {
            let node = &nodes[index as usize];
            if node.is_leaf() {
                let first = node.first_index as usize;
                for tri in &self.prim_tris[first..first + node.prim_count as usize] {
                    if tri
                        .iter()
                        .any(|q| in_front(q.as_dvec3(), point, normal, normal_length))
                    {
                        return false;
                    }
                }
            } else {
                let (left, right) = (node.first_index, node.first_index + 1);
                match (reach(left), reach(right)) {
                    (Some(l), Some(r)) => {
                        // The farther-reaching child is popped first.
                        let (near, far) = if l > r { (right, left) } else { (left, right) };
                        stack.push(near);
                        stack.push(far);
                    }
                    (Some(_), None) => stack.push(left),
                    (None, Some(_)) => stack.push(right),
                    (None, None) => {}
                }
            }
        }
        true
    }
}

/// Whether `q` lies in front of the plane through `point` with `normal`
/// (of length `normal_length`) by more than [`COPLANAR_REL`] of its
/// distance.
#[inline]
fn in_front(q: DVec3, point: DVec3, normal: DVec3, normal_length: f64) -> bool {
    let d = q - point;
    let ahead = d.dot(normal);
    ahead > 0.0 && ahead > COPLANAR_REL * normal_length * d.length()
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use tetray_mesh::{TetMesh, Topology};

    use crate::{BoundaryBvh, BuildPreset};

    /// Two unit cubes of 5 tets each, side by side along x with a gap.
    fn two_cubes() -> TetMesh {
        let cube = |x0: f32| {
            let p = |x: f32, y: f32, z: f32| Vec3::new(x0 + x, y, z);
            vec![
                p(0.0, 0.0, 0.0),
                p(1.0, 0.0, 0.0),
                p(0.0, 1.0, 0.0),
                p(1.0, 1.0, 0.0),
                p(0.0, 0.0, 1.0),
                p(1.0, 0.0, 1.0),
                p(0.0, 1.0, 1.0),
                p(1.0, 1.0, 1.0),
            ]
        };
        let five = [
            [0, 1, 2, 4],
            [1, 3, 2, 7],
            [1, 5, 4, 7],
            [2, 6, 4, 7],
            [1, 2, 4, 7],
        ];
        let mut points = cube(0.0);
        points.extend(cube(2.0));
        let mut tets = Vec::new();
        for offset in [0u32, 8] {
            for t in five {
                tets.push(t.map(|v| v + offset));
            }
        }
        let mut mesh = TetMesh {
            points,
            tets,
            fields: Vec::new(),
        };
        mesh.orient();
        mesh
    }

    #[test]
    fn only_faces_facing_away_from_the_other_cube_are_final() {
        let mesh = two_cubes();
        let topology = Topology::build(&mesh).unwrap();
        let bvh = BoundaryBvh::build(&mesh, &topology, BuildPreset::default()).unwrap();
        let finals = bvh.final_exit_faces();
        assert_eq!(finals.len(), topology.boundary_faces.len());
        for (face, &is_final) in topology.boundary_faces.iter().zip(&finals) {
            let [a, b, c] = face.vertices.map(|v| mesh.points[v as usize]);
            let n = (b - a).cross(c - a).normalize();
            // Faces towards the other cube (+x of the first, -x of the
            // second) can be re-entered from; all others are on the hull.
            let inner = (n.x > 0.5 && a.x < 1.5) || (n.x < -0.5 && a.x > 1.5);
            assert_eq!(is_final, !inner, "face {:?} normal {n:?}", face.vertices);
        }
    }
}
