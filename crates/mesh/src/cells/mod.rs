//! The cell model every reader produces, and the one place that turns it
//! into tetrahedra.
//!
//! A reader (in `tetray-io`) parses its file into a [`CellGrid`]: points in
//! f64, cells with their VTK type (connectivity and offsets), polyhedron
//! faces, point and cell arrays ([`CellArray`]), global ids, the pieces,
//! blocks and ghost cells it met. [`assemble_with`] checks what it can see
//! (point indices, NaN/inf, counts), splits the volume cells into
//! tetrahedra and builds a [`TetMesh`]. It does not orient tetrahedra or
//! build topology: [`crate::finish`] does that afterwards. Nothing here
//! reads a file; the name a grid is given is used in messages only.
//!
//! Conventions:
//! - tetra cells are kept; voxel, hexahedron, wedge and pyramid cells are
//!   split into tetrahedra conformingly (see `split.rs`); quadratic and
//!   order-2 Lagrange tetra, hexahedra, wedges and pyramids are subdivided
//!   through their nodes (`split_quadratic.rs`, in VTK's node order: one
//!   table per cell type; [`Linearize::Corners`] keeps their corners only);
//!   polyhedra and pentagonal/hexagonal prisms are split around a centroid
//!   (`polyhedron.rs`); the points these add come after the file's, their
//!   fields interpolated; 0-, 1- and 2-D cells are skipped with a warning
//!   that counts them; other 3-D cells (Bezier, higher orders, ...) are an
//!   error naming the type and the cell;
//! - a point array with one component becomes a field of its name; one with
//!   several components becomes its Euclidean magnitude `<name>_magnitude`;
//! - a cell array becomes a point field by averaging over the volume cells
//!   using each point (0 at points in none), with a warning naming it;
//! - values are converted to f32; NaN, infinities and values beyond f32's
//!   range are errors;
//! - structured grids become one hexahedron per grid cell, split like any
//!   other (see `structured_grid.rs`);
//! - `vtkGhostType` arrays are not fields: cells flagged duplicate (1) or
//!   hidden (32), and cells touching points flagged hidden (2), are dropped;
//!   pieces and blocks are welded into one mesh (see `pieces.rs`).

mod added_points;
mod assemble;
mod cell_table;
mod cell_types;
mod error;
mod grid;
mod pieces;
mod poly_grid;
mod polyhedron;
mod split;
mod split_centred;
mod split_quadratic;
mod structured_grid;

pub use assemble::{assemble_at, assemble_with, per_tuple, to_f32};
pub use cell_types::{CellKind, classify, type_name};
pub use error::CellError;
pub use grid::{CellArray, CellGrid};
pub use pieces::{drop_ghosts, drop_global_ids, finish_grid, merge_arrays, weld};
pub use poly_grid::{checked_faces, keep_cell_faces, separate_inline_faces, shift_faces};
pub use polyhedron::{
    PieceFaces, PolyhedronFaces, from_face_stream, from_face_tables, parse_face_stream,
};
pub use structured_grid::{
    add_cells, cell_count, extent_dims, image_points, point_count, rectilinear_points,
};

use crate::TetMesh;

/// What assembling a [`CellGrid`] gives: the tetrahedra, and what the
/// file said on the way (what [`assemble_with`] returns; the VTK readers
/// return it as is, the Exodus reader wraps it).
#[derive(Debug, Clone, PartialEq)]
pub struct VtkRead {
    pub mesh: TetMesh,
    /// Things read past or converted (skipped cells, cell data averaged...).
    pub warnings: Vec<String>,
    pub cells: CellCounts,
    /// The VTK dataset type read: "UnstructuredGrid", "StructuredGrid",
    /// "RectilinearGrid", "ImageData" (of every block, or "MultiBlock"
    /// when they differ).
    pub dataset: &'static str,
    pub pieces: PieceCounts,
    /// The points are stored relative to this origin (f64; see
    /// [`crate::centring_origin`]): a point's coordinates as in the file
    /// are `origin + point`.
    pub origin: glam::DVec3,
    /// Per tetrahedron, the index of the file's cell it was split from
    /// (ghost and lower-dimensional cells counted; for pieces and blocks,
    /// each piece's cells numbered on from those of the pieces before it,
    /// in the order the file names them).
    pub tet_cells: Vec<u32>,
}

/// What joining pieces and blocks did (zero for a single serial file
/// without ghost cells).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PieceCounts {
    /// Piece files (or Pieces of one file) read.
    pub pieces: usize,
    /// Multi-block leaves read (0 outside `.vtm`), and those skipped
    /// (polygonal data, surface cells only).
    pub blocks: usize,
    pub blocks_skipped: usize,
    /// Points of one piece merged with the same point of another.
    pub welded_points: usize,
    /// Cells flagged duplicate (`vtkGhostType` bit 1): another piece owns them.
    pub ghost_cells_dropped: usize,
    /// Cells flagged hidden (bit 32) or touching a point flagged hidden
    /// (bit 2): blanked.
    pub hidden_cells_dropped: usize,
}

/// What to do with the mid-edge, face and body nodes of quadratic and
/// Lagrange cells.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Linearize {
    /// Subdivide each cell into linear tetrahedra through all its nodes,
    /// so the field values there are used.
    #[default]
    Subdivide,
    /// Keep the corner nodes only (the linear cell), as VTK's unstructured
    /// volume mappers do; the other nodes stay as unused points.
    Corners,
}

/// Options of the `*_with` readers.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReadOptions {
    pub linearize: Linearize,
}

/// Cells of one VTK type that were subdivided or split around a centroid.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SubdividedCells {
    pub type_id: i64,
    /// VTK's name of the type ("quadratic tetra").
    pub name: &'static str,
    pub cells: usize,
    /// Tetrahedra they gave.
    pub tets: usize,
    /// Points added for them (computed face and body nodes, centroids).
    pub points_added: usize,
}

/// How many cells of each kind were read, and how many tetrahedra the
/// non-tetrahedral ones gave.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct CellCounts {
    pub tetra: usize,
    pub hexahedra: usize,
    pub wedges: usize,
    pub pyramids: usize,
    pub voxels: usize,
    /// Vertices, lines, triangles, quads, polygons...: not part of the
    /// volume, skipped.
    pub skipped_lower_dim: usize,
    /// Tetrahedra made from every cell that is not a linear tetra.
    pub tets_from_split: usize,
    /// Higher-order cells, prisms and polyhedra, per type (by type id).
    pub subdivided: Vec<SubdividedCells>,
    /// Points added after the file's (the sum over `subdivided`).
    pub points_added: usize,
}
