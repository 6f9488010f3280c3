//! Validation: a mesh that cannot be walked is rejected before rendering,
//! never rendered wrong.
//!
//! Errors (the first one found, naming the cell, point or field): empty
//! mesh, field lengths, dangling or repeated point indices, non-finite
//! coordinates or scalars, negatively oriented or degenerate tetrahedra,
//! faces shared by more than two tetrahedra, tetrahedra overlapping across
//! a shared face. The loader leaves the last three out of the walk first
//! (`exclude.rs`), so only a mesh built by hand meets them here.
//!
//! Warnings for what renders fine: duplicate points, unused points,
//! coincident boundary faces (seams), several components, and tetrahedra
//! not meeting face to face (hanging nodes or T-junctions, a face split
//! differently on its two sides; see `conform.rs`): the unmatched faces are
//! boundary faces, crossed through the boundary BVH like a seam.

use rayon::prelude::*;

use crate::conform::nonconformity;
use crate::seams::{coincident_boundary_faces, duplicate_points};
use crate::{
    BoundaryFace, FACE_VERTICES, MeshError, TetMesh, Topology, first_index, first_position,
    tet_shape,
};

/// What validation found that does not stop rendering.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ValidationReport {
    /// Connected components through shared faces.
    pub components: usize,
    /// Points equal in all three coordinates to an earlier point.
    pub duplicate_points: usize,
    /// Points no tetrahedron uses.
    pub unused_points: usize,
    /// Boundary faces lying exactly on another boundary face (a seam where
    /// two parts of the mesh touch without sharing points).
    pub seam_faces: usize,
    /// Points lying on a face or edge of another tetrahedron without being
    /// its corner (hanging nodes, T-junctions).
    pub hanging_nodes: usize,
    /// Pairs of boundary faces sharing an edge and lying on each other (a
    /// quadrilateral split along different diagonals on its two sides).
    pub folded_face_pairs: usize,
    /// The unmatched faces of those non-conforming contacts, both sides: a
    /// ray leaves through them and re-enters through the other side.
    pub nonconforming_faces: Vec<BoundaryFace>,
    /// The above (when not zero or one) as sentences.
    pub warnings: Vec<String>,
}

/// Checks that `mesh` can be walked face to face; see the module docs.
/// Expects positively oriented tetrahedra ([`TetMesh::orient`] first).
///
/// # Errors
/// The first problem found, as the [`MeshError`] variant naming it.
pub fn validate(mesh: &TetMesh) -> Result<ValidationReport, MeshError> {
    validate_with_topology(mesh).map(|(report, _)| report)
}

/// [`validate`], also returning the topology it built on the way.
pub fn validate_with_topology(mesh: &TetMesh) -> Result<(ValidationReport, Topology), MeshError> {
    check_input(mesh)?;
    let topology = Topology::build(mesh)?;
    let report = check_walkable(mesh, &topology)?;
    Ok((report, topology))
}

/// What must hold before any geometry is looked at: counts, indices in
/// range and not repeated, finite coordinates and scalars.
pub fn check_input(mesh: &TetMesh) -> Result<(), MeshError> {
    check_sizes(mesh)?;
    check_indices(mesh)?;
    check_finite(mesh)
}

/// The checks on shapes and the topology (`check_input` passed), and the
/// findings.
pub(crate) fn check_walkable(
    mesh: &TetMesh,
    topology: &Topology,
) -> Result<ValidationReport, MeshError> {
    check_shapes(mesh)?;
    if let Some(&(tet_a, tet_b, vertices)) = face_side_conflicts(mesh, topology).first() {
        return Err(MeshError::Overlapping {
            tet_a,
            tet_b,
            vertices,
        });
    }
    Ok(walkable_report(mesh, topology))
}

/// The findings of [`check_walkable`] without its error checks, for a mesh
/// that [`crate::exclude`] made walkable: it left out the flat
/// tetrahedra, the cells overlapping across a face and the non-manifold
/// ones, and oriented the rest (an exact negation of the volume), so the
/// checks would find nothing at the cost of a second pass over every
/// tetrahedron.
pub(crate) fn walkable_report(mesh: &TetMesh, topology: &Topology) -> ValidationReport {
    let canonical = duplicate_points(&mesh.points);
    findings(mesh, topology, &canonical)
}

fn check_sizes(mesh: &TetMesh) -> Result<(), MeshError> {
    if mesh.tets.is_empty() {
        return Err(MeshError::Empty);
    }
    let max = u32::MAX as usize;
    if mesh.points.len() > max {
        return Err(MeshError::TooLarge {
            what: "points",
            count: mesh.points.len(),
            max,
        });
    }
    for field in &mesh.fields {
        if field.values.len() != mesh.points.len() {
            return Err(MeshError::FieldLength {
                field: field.name.clone(),
                expected: mesh.points.len(),
                found: field.values.len(),
            });
        }
    }
    Ok(())
}

fn check_indices(mesh: &TetMesh) -> Result<(), MeshError> {
    let npoints = mesh.points.len();
    let bad = first_position(&mesh.tets, |tet| {
        tet.iter().any(|&i| i as usize >= npoints) || has_repeat(tet)
    });
    let Some(t) = bad else { return Ok(()) };
    let tet = &mesh.tets[t];
    if let Some(corner) = tet.iter().position(|&i| i as usize >= npoints) {
        return Err(MeshError::DanglingIndex {
            tet: t,
            corner,
            index: tet[corner],
            npoints,
        });
    }
    let point = (0..4)
        .flat_map(|a| (a + 1..4).map(move |b| (a, b)))
        .find(|&(a, b)| tet[a] == tet[b])
        .map_or(tet[0], |(a, _)| tet[a]);
    Err(MeshError::RepeatedVertex {
        tet: t,
        point,
        vertices: *tet,
    })
}

fn has_repeat(tet: &[u32; 4]) -> bool {
    tet[0] == tet[1]
        || tet[0] == tet[2]
        || tet[0] == tet[3]
        || tet[1] == tet[2]
        || tet[1] == tet[3]
        || tet[2] == tet[3]
}

fn check_finite(mesh: &TetMesh) -> Result<(), MeshError> {
    let bad = first_position(&mesh.points, |p| !p.is_finite());
    if let Some(point) = bad {
        let p = mesh.points[point];
        let axis = (0..3).find(|&a| !p[a].is_finite()).unwrap_or(0);
        return Err(MeshError::NonFiniteCoordinate {
            point,
            axis: ['x', 'y', 'z'][axis],
            value: p[axis],
        });
    }
    for field in &mesh.fields {
        if let Some(point) = first_position(&field.values, |v| !v.is_finite()) {
            return Err(MeshError::NonFiniteScalar {
                field: field.name.clone(),
                point,
                value: field.values[point],
            });
        }
    }
    Ok(())
}

/// Degenerate before inverted: a flat tetrahedron's sign means nothing.
fn check_shapes(mesh: &TetMesh) -> Result<(), MeshError> {
    let bad = first_index(mesh.tets.len(), |t| {
        let shape = tet_shape(mesh.tet_points(t));
        shape.is_degenerate() || shape.volume6 < 0.0
    });
    let Some(t) = bad else { return Ok(()) };
    let vertices = mesh.tets[t];
    let shape = tet_shape(mesh.tet_points(t));
    if shape.is_degenerate() {
        return Err(MeshError::DegenerateTet {
            tet: t,
            vertices,
            volume6: shape.volume6,
            min_height: shape.min_height(),
            threshold: shape.height_threshold(),
        });
    }
    Err(MeshError::Inverted { tet: t, vertices })
}

/// Parity of the permutation sorting `v` (true when odd).
fn odd_sort_parity(v: [u32; 3]) -> bool {
    let inversions = u32::from(v[0] > v[1]) + u32::from(v[0] > v[2]) + u32::from(v[1] > v[2]);
    inversions % 2 == 1
}

/// Two positively oriented tetrahedra on opposite sides of their shared
/// face see it with opposite vertex orders (each counter-clockwise from its
/// own outside). The same order means both lie on one side: they overlap,
/// and a ray leaving one through that face would walk into the other.
/// Every such pair `(t, neighbour, face of t)` with `t < neighbour`.
pub(crate) fn face_side_conflicts(
    mesh: &TetMesh,
    topology: &Topology,
) -> Vec<(u32, u32, [u32; 3])> {
    topology
        .neighbors
        .par_iter()
        .enumerate()
        .flat_map_iter(|(t, nbs)| {
            nbs.iter().enumerate().filter_map(move |(f, &nb)| {
                if nb == crate::NO_NEIGHBOR || (nb as usize) < t {
                    return None;
                }
                let g = topology.shared_face(t as u32, nb)?;
                let mine = FACE_VERTICES[f].map(|v| mesh.tets[t][v]);
                let theirs = FACE_VERTICES[g].map(|v| mesh.tets[nb as usize][v]);
                (odd_sort_parity(mine) == odd_sort_parity(theirs)).then_some((t as u32, nb, mine))
            })
        })
        .collect()
}

fn findings(mesh: &TetMesh, topology: &Topology, canonical: &[u32]) -> ValidationReport {
    let (components, _) = topology.components();
    let mut used = vec![false; mesh.points.len()];
    for tet in &mesh.tets {
        for &i in tet {
            used[i as usize] = true;
        }
    }
    let unused_points = used.iter().filter(|&&u| !u).count();
    let duplicate_points = canonical
        .iter()
        .enumerate()
        .filter(|&(i, &c)| c as usize != i)
        .count();
    let seam_faces = coincident_boundary_faces(topology, canonical);
    let nonconforming = nonconformity(mesh, topology, canonical);

    let mut warnings = Vec::new();
    if duplicate_points > 0 {
        warnings.push(format!(
            "{duplicate_points} points repeat the coordinates of another point \
             (parts of the mesh touch without sharing points)"
        ));
    }
    if seam_faces > 0 {
        warnings.push(format!(
            "{seam_faces} boundary faces lie exactly on another boundary face (seams); \
             rays cross them by leaving and re-entering the mesh"
        ));
    }
    if !nonconforming.faces.is_empty() {
        warnings.push(format!(
            "{} faces do not meet face to face ({} hanging nodes, {} pairs of faces split \
             differently on their two sides); they are boundary faces, crossed by leaving \
             and re-entering the mesh",
            nonconforming.faces.len(),
            nonconforming.hanging_nodes,
            nonconforming.folded_pairs
        ));
    }
    if unused_points > 0 {
        warnings.push(format!("{unused_points} points are used by no tetrahedron"));
    }
    if components > 1 {
        warnings.push(format!(
            "the mesh has {components} separate pieces (connected through faces)"
        ));
    }
    ValidationReport {
        components,
        duplicate_points,
        unused_points,
        seam_faces,
        hanging_nodes: nonconforming.hanging_nodes,
        folded_face_pairs: nonconforming.folded_pairs,
        nonconforming_faces: nonconforming.faces,
        warnings,
    }
}
