//! The linear-scan reference for [`crate::BoundaryBvh::first_entry`].

use tetray_mesh::{TetMesh, Topology};

use crate::{EntryHit, is_better, query_is_valid};
use tetray_core::watertight::{RayFrame, cross_triangle};

/// Same contract as [`crate::BoundaryBvh::first_entry`], by testing every
/// boundary face. Faces naming a point the mesh does not have are ignored
/// (the BVH refuses to build over them). A non-finite ray or a NaN range
/// crosses nothing.
pub fn brute_force_first_entry(
    mesh: &TetMesh,
    topology: &Topology,
    ray: &RayFrame,
    t_min: f32,
    t_max: f32,
    skip: &[u32],
) -> Option<EntryHit> {
    if !query_is_valid(ray, t_min, t_max) {
        return None;
    }
    let mut best = None;
    for (face, boundary_face) in (0u32..).zip(&topology.boundary_faces) {
        let [a, b, c] = boundary_face.vertices.map(|v| mesh.points.get(v as usize));
        let (Some(&a), Some(&b), Some(&c)) = (a, b, c) else {
            continue;
        };
        let Some(crossing) = cross_triangle(ray.project(a), ray.project(b), ray.project(c)) else {
            continue;
        };
        let t = crossing.t;
        if crossing.entering
            && t >= t_min
            && t <= t_max
            && is_better(t, face, best)
            && !skip.contains(&face)
        {
            best = Some(EntryHit { face, t });
        }
    }
    best
}
