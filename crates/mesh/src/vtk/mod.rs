//! VTK readers and writers: legacy `.vtk` (UNSTRUCTURED_GRID,
//! STRUCTURED_GRID, RECTILINEAR_GRID, STRUCTURED_POINTS), serial XML
//! (`.vtu`, `.vts`, `.vtr`, `.vti`), parallel XML (`.pvtu`, `.pvts`,
//! `.pvtr`, `.pvti`) and multi-block `.vtm`.
//!
//! Both readers parse the file into the same raw arrays, then check what they
//! can see (point indices, NaN/inf, counts), split the volume cells into
//! tetrahedra and build a [`TetMesh`]. They do not orient tetrahedra or
//! build topology: the mesh loader does that afterwards.
//!
//! Conventions of the readers:
//! - tetra, voxel, hexahedron, wedge and pyramid cells are kept; the others
//!   are split into tetrahedra conformingly (see `split.rs`); 0-, 1- and
//!   2-D cells are skipped with a warning that counts them; other 3-D cells
//!   (quadratic, higher order, polyhedra, prisms with 5 or 6 sides) are an
//!   error naming the type and the cell;
//! - a point array with one component becomes a field of its name; one with
//!   several components (SCALARS with numComp > 1, VECTORS, multi-component
//!   FIELD or DataArray) becomes its Euclidean magnitude `<name>_magnitude`;
//! - a cell array becomes a point field by averaging over the volume cells
//!   using each point (0 at points in none), with a warning naming it;
//! - values are converted to f32; NaN, infinities and values beyond f32's
//!   range are errors;
//! - structured grids become one hexahedron per grid cell, split like any
//!   other (see `structured_grid.rs`);
//! - `vtkGhostType` arrays are not fields: cells flagged duplicate (1) or
//!   hidden (32), and cells touching points flagged hidden (2), are dropped;
//!   pieces and blocks are welded into one mesh (see `pieces.rs`).

mod assemble;
mod cells;
mod collection;
mod error;
mod image_grid;
mod legacy_lex;
mod legacy_read;
mod legacy_structured;
mod legacy_write;
mod numeric;
mod pieces;
mod split;
mod structured_grid;
mod vtu_data;
mod vtu_read;
mod vtu_stream;
mod vtu_write;
mod vtu_xml;
mod xml_structured;

use std::path::Path;

pub(crate) use assemble::{assemble, RawArray, RawGrid};

pub use error::VtkError;
pub use image_grid::{read_image_grid, ImageGrid};
pub use legacy_write::write_legacy;
pub use vtu_stream::{write_vtu_streamed, TetChunks, VtuIndex, VtuStreamOptions};
pub use vtu_write::{write_vtu, write_vtu_with, VtuOptions};

use crate::TetMesh;

/// What a reader returns.
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

/// How many cells of each kind were read, and how many tetrahedra the
/// non-tetrahedral ones gave.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CellCounts {
    pub tetra: usize,
    pub hexahedra: usize,
    pub wedges: usize,
    pub pyramids: usize,
    pub voxels: usize,
    /// Vertices, lines, triangles, quads, polygons...: not part of the
    /// volume, skipped.
    pub skipped_lower_dim: usize,
    /// Tetrahedra made from hexahedra, wedges, pyramids and voxels.
    pub tets_from_split: usize,
}

/// How [`write_vtu`] stores its arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VtuEncoding {
    /// Decimal text inside each DataArray (never compressed).
    Ascii,
    /// Base64 inside each DataArray (`format="binary"`).
    Base64,
    /// Raw bytes in an `<AppendedData encoding="raw">` section.
    AppendedRaw,
    /// Base64 in an `<AppendedData encoding="base64">` section.
    AppendedBase64,
}

fn read_path(path: &Path) -> Result<Vec<u8>, VtkError> {
    std::fs::read(path).map_err(|source| VtkError::Io {
        file: path.display().to_string(),
        source,
    })
}

/// Reads a legacy `.vtk` file (UNSTRUCTURED_GRID, STRUCTURED_GRID,
/// RECTILINEAR_GRID or STRUCTURED_POINTS; ASCII or BINARY).
pub fn read_legacy_file(path: &Path) -> Result<VtkRead, VtkError> {
    read_legacy_bytes(&read_path(path)?, &path.display().to_string())
}

/// Reads a legacy VTK file held in memory; `name` is used in messages.
pub fn read_legacy_bytes(bytes: &[u8], name: &str) -> Result<VtkRead, VtkError> {
    legacy_read::read(bytes, name)
}

/// Reads a serial XML file: `.vtu` (UnstructuredGrid), `.vts`
/// (StructuredGrid), `.vtr` (RectilinearGrid) or `.vti` (ImageData), chosen
/// by its `<VTKFile type>`; ascii, base64 or appended data, optionally
/// zlib-compressed.
pub fn read_vtu_file(path: &Path) -> Result<VtkRead, VtkError> {
    read_vtu_bytes(&read_path(path)?, &path.display().to_string())
}

/// Reads a serial XML file held in memory; `name` is used in messages.
pub fn read_vtu_bytes(bytes: &[u8], name: &str) -> Result<VtkRead, VtkError> {
    vtu_read::read(bytes, name)
}

/// Reads a parallel XML file (`.pvtu`, `.pvts`, `.pvtr`, `.pvti`): every
/// piece it names, relative to its folder, read in parallel, ghost cells
/// dropped, shared points welded into one mesh.
pub fn read_parallel_file(path: &Path) -> Result<VtkRead, VtkError> {
    collection::read_parallel(path)
}

/// Reads a multi-block `.vtm` file: its volume blocks (any of the XML
/// formats above, nested blocks included) welded into one mesh; polygonal
/// and surface-only blocks are skipped with a note. `block` keeps only the
/// blocks of that name or path (`outer/inner`).
pub fn read_multiblock_file(path: &Path, block: Option<&str>) -> Result<VtkRead, VtkError> {
    collection::read_multiblock(path, block)
}
