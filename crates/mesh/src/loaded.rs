//! From a reader's output ([`MeshRead`], points relative to an origin near
//! the mesh, see [`crate::centring_origin`]) to a mesh ready to render:
//! leave out the cells that cannot be walked (`exclude.rs`), orient,
//! validate, build the topology ([`finish`]). What was changed is in the
//! [`LoadReport`]. The readers that produce a [`MeshRead`] are in
//! `tetray-io`.

use glam::DVec3;

use crate::cells::{PieceCounts, SubdividedCells};
use crate::exclude::{ExcludedCells, KnownTopology, exclude_bad_cells};
use crate::validate::{check_input, walkable_report};
use crate::{MeshError, TetMesh, Topology, ValidationReport};

/// What happened on the way from the file to the mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LoadReport {
    /// The reader used: "VTK legacy", "VTK legacy STRUCTURED_GRID" (and
    /// RECTILINEAR_GRID, STRUCTURED_POINTS), "VTK XML" (`.vtu`), "VTK XML
    /// StructuredGrid" (and RectilinearGrid, ImageData), "VTK parallel
    /// XML", "VTK multi-block", "Exodus II", "PLOT3D" or "memory".
    pub format: &'static str,
    /// Reader and validation warnings, as sentences.
    pub warnings: Vec<String>,
    /// Negatively oriented tetrahedra that were reoriented (for PLOT3D,
    /// those the split made inverted: all of them for a left-handed grid).
    pub inverted_fixed: usize,
    /// Flat tetrahedra made by splitting collapsed cells, dropped by the
    /// reader (PLOT3D; the VTK readers report theirs in `warnings`).
    pub degenerate_dropped: usize,
    /// Non-tetrahedral cells (hexahedra, wedges...) split into tetrahedra.
    pub cells_split: usize,
    /// Tetrahedra made by those splits.
    pub tets_from_split: usize,
    /// Pieces joined, points welded, ghost and blanked cells dropped, blocks
    /// read and skipped (parallel and multi-block files; ghost and blanked
    /// cells of any VTK file).
    pub pieces: PieceCounts,
    /// Points the splits added (face and cell centres of higher-order
    /// cells, polyhedra and prisms), their fields interpolated.
    pub points_added: usize,
    /// Higher-order cells, polyhedra and prisms per VTK type: cells, the
    /// tetrahedra they gave, the points added for them.
    pub subdivided: Vec<SubdividedCells>,
    /// Validation findings (components, duplicate points, seams,
    /// non-conforming faces...).
    pub validation: ValidationReport,
    /// The times the file stores, one per time step (Exodus II; empty for
    /// the other formats).
    pub times: Vec<f64>,
    /// The time step read (0-based), when the file stores any.
    pub time_step: Option<usize>,
    /// The file's element blocks, kept or skipped (Exodus II).
    pub blocks: Vec<ElementBlock>,
    /// The points are stored relative to this origin: a point's coordinates
    /// in the file are `origin + point` (zero unless the mesh lies far from
    /// zero; see [`crate::centring_origin`]). Cameras given in the file's
    /// coordinates subtract it.
    pub origin: DVec3,
    /// Cells left out of the walk (tangled, overlapping) and flat
    /// tetrahedra dropped.
    pub excluded: ExcludedCells,
}

impl LoadReport {
    /// One line saying what loading changed in the mesh (non-conforming
    /// faces made boundary, cells left out with their volume share, the
    /// origin shift), or `None` when it changed nothing of the geometry.
    pub fn changes(&self) -> Option<String> {
        let mut parts = Vec::new();
        let v = &self.validation;
        if !v.nonconforming_faces.is_empty() {
            parts.push(format!(
                "{} non-conforming faces made boundary ({} hanging nodes, {} pairs of faces split \
                 differently)",
                v.nonconforming_faces.len(),
                v.hanging_nodes,
                v.folded_face_pairs
            ));
        }
        let x = &self.excluded;
        if !x.cells.is_empty() {
            parts.push(format!(
                "{} cells left out ({} tangled, {} overlapping, {} non-manifold; {:.4}% of the \
                 volume), composited by the ray casters in the holes they leave",
                x.cells.len(),
                x.tangled,
                x.overlapping,
                x.non_manifold,
                100.0 * x.volume_share
            ));
        }
        if x.flat_tets > 0 {
            parts.push(format!("{} flat tetrahedra dropped", x.flat_tets));
        }
        if self.origin != DVec3::ZERO {
            let o = self.origin;
            parts.push(format!(
                "points stored relative to the origin ({}, {}, {})",
                o.x, o.y, o.z
            ));
        }
        (!parts.is_empty()).then(|| format!("mesh changed on load: {}", parts.join("; ")))
    }
}

/// A mesh ready to render: positively oriented, validated, with its
/// face-neighbour topology.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedMesh {
    pub mesh: TetMesh,
    pub topology: Topology,
    pub report: LoadReport,
    /// The tetrahedra of the cells left out of the walk (tangled,
    /// overlapping, non-manifold; not the flat ones), over `mesh.points`,
    /// signed against the mesh's orientation (positive where the cells are
    /// not inverted; see `exclude.rs`): the ray casters
    /// composite them where the walk leaves a hole
    /// (`tetray_scene::Overlaps`).
    pub overlaps: Vec<[u32; 4]>,
}

impl LoadedMesh {
    /// Where the stored points are relative to the file's coordinates
    /// (see [`LoadReport::origin`]).
    pub fn origin(&self) -> DVec3 {
        self.report.origin
    }
}

/// Orients, validates and builds the topology of a mesh made in memory.
///
/// # Errors
/// The first validation error (see [`crate::validate`]).
pub fn prepare(mesh: TetMesh) -> Result<LoadedMesh, MeshError> {
    finish(MeshRead {
        mesh,
        format: "memory",
        ..MeshRead::default()
    })
}

/// A reader's output in common form: the tetrahedra and what the file
/// said (blocks, pieces, time steps, skipped and split cells), before
/// [`finish`] orients, validates and builds the topology.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshRead {
    pub mesh: TetMesh,
    /// The reader used (see [`LoadReport::format`]).
    pub format: &'static str,
    pub warnings: Vec<String>,
    pub degenerate_dropped: usize,
    pub inverted_fixed: usize,
    pub cells_split: usize,
    pub tets_from_split: usize,
    pub times: Vec<f64>,
    pub time_step: Option<usize>,
    pub blocks: Vec<ElementBlock>,
    pub pieces: PieceCounts,
    pub points_added: usize,
    pub subdivided: Vec<SubdividedCells>,
    pub origin: DVec3,
    /// Per tetrahedron, the cell it came from (empty: each its own).
    pub tet_cells: Vec<u32>,
}

/// An element block as the file describes it (Exodus II).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ElementBlock {
    /// The block id (`eb_prop1`).
    pub id: i64,
    /// The block name (`eb_names`), empty when the file gives none.
    pub name: String,
    /// The `elem_type` attribute of its connectivity ("HEX8", "SHELL4"...).
    pub elem_type: String,
    pub nodes_per_element: usize,
    /// Elements in the block.
    pub cells: usize,
    /// Whether its elements are part of the mesh (volume blocks).
    pub kept: bool,
}

/// Leaves out the cells that cannot be walked, orients, validates and
/// builds the topology of what a reader produced.
///
/// # Errors
/// The first validation error (see [`crate::validate`]); wrap it with
/// [`MeshError::in_file`] to name the file.
pub fn finish(read: MeshRead) -> Result<LoadedMesh, MeshError> {
    finish_reusing(read, None)
}

/// [`finish`] for another time step of a mesh whose finished tetrahedra
/// and topology are `previous`: when this step's tetrahedra come out the
/// same (kept and oriented alike; its points may move), the topology is
/// taken, not built. The result is [`finish`]'s.
///
/// # Errors
/// As [`finish`].
pub fn finish_reusing(
    mut read: MeshRead,
    previous: Option<&KnownTopology>,
) -> Result<LoadedMesh, MeshError> {
    check_input(&read.mesh)?;
    let exclusion = exclude_bad_cells(&mut read.mesh, &read.tet_cells, previous)?;
    let (topology, excluded) = (exclusion.topology, exclusion.excluded);
    read.inverted_fixed += exclusion.reoriented;
    // Exclusion left only walkable tetrahedra: the findings, no re-check.
    let validation = walkable_report(&read.mesh, &topology);
    let mut warnings = read.warnings;
    warnings.extend(excluded.warnings());
    warnings.extend(validation.warnings.iter().cloned());
    Ok(LoadedMesh {
        mesh: read.mesh,
        topology,
        report: LoadReport {
            format: read.format,
            warnings,
            inverted_fixed: read.inverted_fixed,
            degenerate_dropped: read.degenerate_dropped,
            cells_split: read.cells_split,
            tets_from_split: read.tets_from_split,
            pieces: read.pieces,
            points_added: read.points_added,
            subdivided: read.subdivided,
            validation,
            times: read.times,
            time_step: read.time_step,
            blocks: read.blocks,
            origin: read.origin,
            excluded,
        },
        overlaps: exclusion.overlaps,
    })
}
