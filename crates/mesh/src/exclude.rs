//! Cells that cannot be walked are left out of the mesh instead of
//! rejecting it: a few bad cells never stop a render.
//!
//! - A flat tetrahedron (see [`crate::DEGENERATE_HEIGHT_ULPS`]) is dropped
//!   on its own: it has no volume to speak of.
//! - A cell split into tetrahedra of both orientations is tangled (a
//!   hexahedron deformed until its faces fold, as a crushed can's): no
//!   orientation of its pieces is right, and they overlap each other. The
//!   whole cell is left out.
//! - Two tetrahedra sharing a face but lying on the same side of it overlap
//!   (an inverted cell next to a good one): both cells are left out, since
//!   the face alone cannot tell which is wrong.
//! - Tetrahedra on a face shared by more than two are left out.
//!
//! What remains is a valid mesh with holes. The faces around a hole are
//! boundary faces: a ray leaves there and re-enters beyond the hole through
//! the boundary BVH, as at a seam or a non-conforming interface.
//!
//! The tetrahedra of the cells left out are kept apart as overlaps
//! ([`orient_overlaps`]), signed against the mesh's orientation so that their
//! signed volumes sum to the volume their faces enclose: the ray casters
//! fill the holes with them (`tetray_scene::Overlaps`).

use rayon::prelude::*;

use crate::topology::check_tet_count;
use crate::validate::face_side_conflicts;
use crate::{MeshError, TetMesh, Topology, tet_shape};

/// What was left out of the walk, and how much of the mesh that is.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ExcludedCells {
    /// The cells left out, ascending: their index among the file's cells
    /// (VTK; for parallel and multi-block files a piece's cells are
    /// numbered on from all the cells of the pieces before it, ghost cells
    /// included; Exodus: the 0-based element number across all blocks), or
    /// the tetrahedron's index as given (PLOT3D, memory).
    pub cells: Vec<u32>,
    /// Of those: cells split into tetrahedra of both orientations.
    pub tangled: usize,
    /// Cells with a tetrahedron overlapping a neighbour across a shared
    /// face.
    pub overlapping: usize,
    /// Cells with a tetrahedron on a face shared by more than two.
    pub non_manifold: usize,
    /// Tetrahedra removed with those cells.
    pub tets: usize,
    /// Their volume (sum of the tetrahedra's absolute volumes).
    pub volume: f64,
    /// That volume over the absolute volume of every tetrahedron read.
    pub volume_share: f64,
    /// Flat tetrahedra dropped one by one (not counted in `cells`).
    pub flat_tets: usize,
}

impl ExcludedCells {
    /// Whether anything was left out.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty() && self.flat_tets == 0
    }

    /// The findings as sentences (none when nothing was left out).
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        if !self.cells.is_empty() {
            let shown: Vec<String> = self.cells.iter().take(10).map(u32::to_string).collect();
            let more = if self.cells.len() > 10 { ", ..." } else { "" };
            warnings.push(format!(
                "left out {} cells that cannot be walked ({} tangled, {} overlapping a \
                 neighbour, {} on a face of more than two tetrahedra): {} tetrahedra, {:.4}% of \
                 the mesh volume; the ray casters composite them in the holes they leave \
                 (cells {}{more})",
                self.cells.len(),
                self.tangled,
                self.overlapping,
                self.non_manifold,
                self.tets,
                100.0 * self.volume_share,
                shown.join(", ")
            ));
        }
        if self.flat_tets > 0 {
            warnings.push(format!(
                "dropped {} flat tetrahedra (height within f32 rounding of their coordinates)",
                self.flat_tets
            ));
        }
        warnings
    }
}

/// Why a cell was left out.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Reason {
    Tangled,
    Overlapping,
    NonManifold,
}

/// The tetrahedra a mesh was left with (after what could not be walked
/// was left out, oriented) and their topology: another time step with the
/// same tetrahedra (moved points) takes the topology instead of building
/// it (see [`crate::finish_reusing`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KnownTopology {
    pub tets: Vec<[u32; 4]>,
    pub topology: Topology,
}

/// What [`exclude_bad_cells`] made of a mesh.
pub(crate) struct Exclusion {
    pub topology: Topology,
    pub excluded: ExcludedCells,
    /// Tetrahedra reoriented.
    pub reoriented: usize,
    /// The tetrahedra of the cells left out (see [`orient_overlaps`]).
    pub overlaps: Vec<[u32; 4]>,
}

/// Leaves out of `mesh` what cannot be walked (see the module docs),
/// orients the rest and builds its topology. `tet_cells` gives each
/// tetrahedron's cell; empty when each tetrahedron is its own cell.
/// Expects [`crate::validate::check_input`] to have passed.
///
/// # Errors
/// [`MeshError::NothingLeft`] when nothing is left; [`MeshError::TooLarge`].
pub(crate) fn exclude_bad_cells(
    mesh: &mut TetMesh,
    tet_cells: &[u32],
    previous: Option<&KnownTopology>,
) -> Result<Exclusion, MeshError> {
    let n = mesh.tets.len();
    // Kept tetrahedra are listed by u32 index below.
    check_tet_count(n)?;
    let cell_of = |t: usize| {
        if tet_cells.len() == n {
            tet_cells[t]
        } else {
            t as u32
        }
    };
    let shapes: Vec<(f64, bool)> = (0..n)
        .into_par_iter()
        .map(|t| {
            let shape = tet_shape(mesh.tet_points(t));
            (shape.volume6 / 6.0, shape.is_degenerate())
        })
        .collect();
    let total: f64 = shapes.iter().map(|(v, _)| v.abs()).sum();
    let ncells = (0..n).map(|t| cell_of(t) as usize + 1).max().unwrap_or(0);
    let mut reason: Vec<Option<Reason>> = vec![None; ncells];

    // Orientation per cell: +1 seen positive, +2 seen negative.
    let mut signs = vec![0u8; ncells];
    for (t, &(volume, flat)) in shapes.iter().enumerate() {
        if !flat {
            signs[cell_of(t) as usize] |= if volume > 0.0 { 1 } else { 2 };
        }
    }
    for (c, &s) in signs.iter().enumerate() {
        if s == 3 {
            reason[c] = Some(Reason::Tangled);
        }
    }

    let given = std::mem::take(&mut mesh.tets);
    let flat_tets = shapes.iter().filter(|(_, flat)| *flat).count();
    let keep =
        |t: usize, reason: &[Option<Reason>]| !shapes[t].1 && reason[cell_of(t) as usize].is_none();
    let mut reoriented;
    let topology = loop {
        // Current tetrahedron -> its index as given.
        let original: Vec<u32> = (0..n)
            .into_par_iter()
            .filter(|&t| keep(t, &reason))
            .map(|t| t as u32)
            .collect();
        if original.is_empty() {
            return Err(MeshError::NothingLeft {
                tets: n,
                flat: flat_tets,
                cells: reason.iter().filter(|r| r.is_some()).count(),
            });
        }
        mesh.tets = original.par_iter().map(|&t| given[t as usize]).collect();
        reoriented = mesh.orient();
        // The topology is of the indices alone: tetrahedra kept and
        // oriented as another time step's have its topology.
        let built = match previous {
            Some(known) if known.tets == mesh.tets => Ok(known.topology.clone()),
            _ => Topology::build(mesh),
        };
        let topology = match built {
            Ok(topology) => topology,
            Err(MeshError::NonManifoldFace { tets, .. }) => {
                for t in tets {
                    reason[cell_of(original[t as usize] as usize) as usize] =
                        Some(Reason::NonManifold);
                }
                continue;
            }
            Err(e) => return Err(e),
        };
        let conflicts = face_side_conflicts(mesh, &topology);
        if conflicts.is_empty() {
            break topology;
        }
        for (a, b, _) in conflicts {
            for t in [a, b] {
                reason[cell_of(original[t as usize] as usize) as usize] = Some(Reason::Overlapping);
            }
        }
    };

    let mut excluded = ExcludedCells {
        flat_tets,
        ..ExcludedCells::default()
    };
    // The left-out tetrahedra as given, and the signed volume of all
    // tetrahedra (the mesh's orientation, see `orient_overlaps`).
    let mut overlaps = Vec::new();
    let mut signed_volume = 0.0;
    for (t, &(volume, flat)) in shapes.iter().enumerate() {
        if flat {
            continue;
        }
        signed_volume += volume;
        if reason[cell_of(t) as usize].is_some() {
            excluded.volume += volume.abs();
            overlaps.push(given[t]);
        }
    }
    excluded.tets = overlaps.len();
    for (c, r) in reason.iter().enumerate() {
        let Some(r) = r else { continue };
        excluded.cells.push(c as u32);
        match r {
            Reason::Tangled => excluded.tangled += 1,
            Reason::Overlapping => excluded.overlapping += 1,
            Reason::NonManifold => excluded.non_manifold += 1,
        }
    }
    excluded.volume_share = if total > 0.0 {
        excluded.volume / total
    } else {
        0.0
    };
    orient_overlaps(&mut overlaps, signed_volume);
    Ok(Exclusion {
        topology,
        excluded,
        reoriented,
        overlaps,
    })
}

/// Turns the left-out tetrahedra `tets` (two vertices swapped) when the
/// mesh's tetrahedra are mostly negative (`signed_volume`: the sum of all
/// their signed volumes). Measured against the mesh's own orientation, a
/// left-out tetrahedron's sign is what it adds to the winding number of
/// the cells' faces: a tangled cell's folded-back tetrahedra, or an
/// inverted cell, count negative and cancel where they overlap the others,
/// so that a constant field over all of them integrates to the volume the
/// left-out cells' faces enclose (the hole they leave).
fn orient_overlaps(tets: &mut [[u32; 4]], signed_volume: f64) {
    if signed_volume < 0.0 {
        for tet in tets {
            tet.swap(2, 3);
        }
    }
}
