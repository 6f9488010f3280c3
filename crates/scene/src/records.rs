//! The walk's record of each tetrahedron ([`WalkTet`]), built and checked
//! from the mesh and its topology.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use tetray_mesh::{FACE_VERTICES, NO_NEIGHBOR, TetMesh, Topology, first_position};

use crate::SceneError;
use crate::order::Reorder;

/// One tetrahedron as the walk reads it: 20 bytes, the compact record of
/// Aman et al., "Compact tetrahedralization-based acceleration structures
/// for ray tracing". A ray enters a tetrahedron through a face whose three
/// point indices it carries from the previous cell, so the record keeps of
/// the vertices only their XOR (the fourth is the XOR of it and the three),
/// and orders the neighbours by the point index of the vertex opposite the
/// shared face ([`vertex_rank`]): which vertex the exit face leaves out
/// names the neighbour, with no vertex list and no face index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub struct WalkTet {
    /// The XOR of the four point indices.
    pub vert_xor: u32,
    /// Across the face opposite the vertex of rank `r` (the place of its
    /// point index among the four, ascending): the neighbour; on the
    /// boundary [`NO_NEIGHBOR`], or [`FINAL_EXIT`] where no ray leaving
    /// through the face can meet the mesh again.
    pub next: [u32; 4],
}

/// The rank of point index `id` among a tetrahedron's four (`verts`, all
/// different, `id` one of them): how many are smaller. It is the slot of
/// [`WalkTet::next`] across the face opposite `id`. One compare of the
/// four lanes: the walk ranks with it at every step. A scene's point
/// indices are below 2^31 (`SceneError::TooManyPoints`), where the signed
/// compare orders them.
#[inline(always)]
pub fn vertex_rank(verts: [u32; 4], id: u32) -> usize {
    tetray_wide::lanes::count_below(verts, id) as usize
}

/// `WalkTet::next` of a boundary face on the mesh's convex hull: a ray
/// leaving through it is done (`BoundaryBvh::final_exit_faces`).
pub const FINAL_EXIT: u32 = NO_NEIGHBOR - 1;

/// The compact records ([`WalkTet`]), checking that every neighbour shares
/// its face: the walk finds the next tetrahedron's new vertex from the XOR
/// and the three carried ones, so a neighbour sharing fewer points would
/// send it astray.
pub(crate) fn walk_tets(
    mesh: &TetMesh,
    topology: &Topology,
    order: Option<&Reorder>,
) -> Result<Vec<WalkTet>, SceneError> {
    // In parallel, straight into place (an indexed collect: collecting
    // `Result`s would gather pieces and copy them, 0.4 s at 10 M
    // tetrahedra); on a bad mesh the error of the first bad tetrahedron.
    let bad = AtomicBool::new(false);
    let walk = mesh
        .tets
        .par_iter()
        .zip(&topology.neighbors)
        .enumerate()
        .map(|t| {
            walk_record(mesh, t).unwrap_or_else(|_| {
                bad.store(true, Ordering::Relaxed);
                WalkTet {
                    vert_xor: 0,
                    next: [NO_NEIGHBOR; 4],
                }
            })
        })
        .collect();
    if bad.into_inner() {
        return Err(first_bad(mesh, topology, order));
    }
    Ok(walk)
}

/// Every neighbour id names a tetrahedron (what the renumbering needs; the
/// walk records check the rest).
pub(crate) fn check_neighbors_in_range(topology: &Topology) -> Result<(), SceneError> {
    let n = topology.neighbors.len();
    let bad = |row: &[u32; 4]| {
        row.iter()
            .position(|&nb| nb != NO_NEIGHBOR && nb as usize >= n)
    };
    match first_position(&topology.neighbors, |row| bad(row).is_some()) {
        None => Ok(()),
        Some(tet) => {
            let face = bad(&topology.neighbors[tet]).unwrap_or_default();
            Err(SceneError::BadNeighbor {
                tet,
                face,
                neighbor: topology.neighbors[tet][face],
            })
        }
    }
}

/// The error of the bad tetrahedron with the smallest input id, named by
/// its input ids (`order` maps the scene's ids back).
fn first_bad(mesh: &TetMesh, topology: &Topology, order: Option<&Reorder>) -> SceneError {
    let input_tet = |t: usize| order.map_or(t, |o| o.tet_from[t] as usize);
    let bad = mesh
        .tets
        .par_iter()
        .zip(&topology.neighbors)
        .enumerate()
        .filter_map(|t| walk_record(mesh, t).err())
        .map(|e| match e {
            SceneError::BadNeighbor {
                tet,
                face,
                neighbor,
            } => SceneError::BadNeighbor {
                tet: input_tet(tet),
                face,
                neighbor: order
                    .and_then(|o| o.tet_from.get(neighbor as usize).copied())
                    .unwrap_or(neighbor),
            },
            other => other,
        })
        .min_by_key(|e| match e {
            SceneError::BadNeighbor { tet, .. } => *tet,
            _ => usize::MAX,
        });
    // walk_record failed on some tetrahedron, so `bad` holds its error.
    bad.unwrap_or(SceneError::Empty)
}

/// The record of one tetrahedron, checking that each neighbour shares the
/// face.
fn walk_record(
    mesh: &TetMesh,
    (tet, (verts, neighbors)): (usize, (&[u32; 4], &[u32; 4])),
) -> Result<WalkTet, SceneError> {
    let mut next = [NO_NEIGHBOR; 4];
    for (face, &neighbor) in neighbors.iter().enumerate() {
        if neighbor == NO_NEIGHBOR {
            continue;
        }
        let bad = || SceneError::BadNeighbor {
            tet,
            face,
            neighbor,
        };
        let other = mesh.tets.get(neighbor as usize).ok_or_else(bad)?;
        let [a, b, c] = FACE_VERTICES[face].map(|v| verts[v]);
        // Bit `i` set when the neighbour's vertex `i` is off the shared
        // face: exactly one must be (branch-free; which one is random).
        let off = (0..4).fold(0u32, |off, i| {
            let on = other[i] == a || other[i] == b || other[i] == c;
            off | u32::from(!on) << i
        });
        if off.count_ones() != 1 || neighbor as usize == tet {
            return Err(bad());
        }
        next[vertex_rank(*verts, verts[face])] = neighbor;
    }
    Ok(WalkTet {
        vert_xor: verts[0] ^ verts[1] ^ verts[2] ^ verts[3],
        next,
    })
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use tetray_mesh::synthetic::{CellSplit, jittered_box};

    use super::*;

    /// Every record gives, for each face, the vertex opposite it from the
    /// face's three points and the neighbour across it from the vertex's
    /// rank: what the walk asks of it.
    #[test]
    fn a_record_names_the_apex_and_the_neighbour_of_each_face() {
        let mesh =
            jittered_box(Vec3::ZERO, Vec3::ONE, [3, 3, 2], 0.2, 5, CellSplit::Six).expect("a mesh");
        let topology = Topology::build(&mesh).expect("topology");
        let records = walk_tets(&mesh, &topology, None).expect("records");
        let mut shared = 0;
        for (t, (record, verts)) in records.iter().zip(&mesh.tets).enumerate() {
            for (face, &neighbor) in topology.neighbors[t].iter().enumerate() {
                let face_xor = FACE_VERTICES[face].iter().fold(0, |x, &v| x ^ verts[v]);
                assert_eq!(record.vert_xor ^ face_xor, verts[face]);
                let across = record.next[vertex_rank(*verts, verts[face])];
                assert_eq!(across, neighbor, "tet {t} face {face}");
                shared += usize::from(neighbor != NO_NEIGHBOR);
            }
        }
        assert!(shared > records.len(), "the box has inner faces");
    }

    #[test]
    fn ranks_count_the_smaller_indices() {
        let verts = [40, 7, 1_000_000, 8];
        assert_eq!(verts.map(|v| vertex_rank(verts, v)), [2, 0, 3, 1]);
    }
}
