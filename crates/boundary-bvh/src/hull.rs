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
        for (slot, &face) in self.prim_faces.iter().enumerate() {
            let first = &mut first_slot[face as usize];
            *first = (*first).min(slot);
        }
        first_slot
            .par_iter()
            .map_init(Vec::new, |stack, &slot| {
                let [a, b, c] = self.prim_tris[slot].map(|p| p.as_dvec3());
                let normal = (b - a).cross(c - a);
                normal.length() > 0.0 && self.all_behind(a, normal, stack)
            })
            .collect()
    }

    /// Whether every boundary point `q` has `(q - point) . normal <= 0`
    /// (up to [`COPLANAR_REL`]), pruning subtrees whose boxes lie behind
    /// (`stack`: the traversal's, reused between calls).
    fn all_behind(&self, point: DVec3, normal: DVec3, stack: &mut Vec<u32>) -> bool {
        let nodes = &self.bvh.nodes;
        let abs_normal = normal.abs();
        let normal_length = normal.length();
        stack.clear();
        stack.push(0);
        while let Some(index) = stack.pop() {
            let node = &nodes[index as usize];
            let aabb = node.aabb();
            let (lo, hi) = (aabb.min.as_dvec3(), aabb.max.as_dvec3());
            let centre = 0.5 * (lo + hi);
            let half = 0.5 * (hi - lo);
            // The box's farthest corner in front of the plane.
            let reach = (centre - point).dot(normal) + half.dot(abs_normal);
            // The slack is never negative: a box wholly behind needs no
            // square root.
            if reach <= 0.0
                || reach
                    <= COPLANAR_REL * normal_length * ((centre - point).length() + half.length())
            {
                continue;
            }
            if node.is_leaf() {
                let first = node.first_index as usize;
                for tri in &self.prim_tris[first..first + node.prim_count as usize] {
                    for q in tri.map(|q| q.as_dvec3()) {
                        let d = q - point;
                        let ahead = d.dot(normal);
                        if ahead > 0.0 && ahead > COPLANAR_REL * normal_length * d.length() {
                            return false;
                        }
                    }
                }
            } else {
                stack.push(node.first_index);
                stack.push(node.first_index + 1);
            }
        }
        true
    }
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
