//! VTK readers and writers: legacy `.vtk` (UNSTRUCTURED_GRID,
//! STRUCTURED_GRID, RECTILINEAR_GRID, STRUCTURED_POINTS), serial XML
//! (`.vtu`, `.vts`, `.vtr`, `.vti`), parallel XML (`.pvtu`, `.pvts`,
//! `.pvtr`, `.pvti`) and multi-block `.vtm`.
//!
//! Each reader parses its file into a [`tetray_mesh::cells::CellGrid`]
//! (points in f64, cells with their VTK type, point and cell arrays,
//! pieces and ghost cells); [`tetray_mesh::cells::assemble_with`] turns it
//! into tetrahedra (see there for the conventions). A point or cell array
//! with several components (SCALARS with numComp > 1, VECTORS,
//! multi-component FIELD or DataArray) becomes its magnitude there. The
//! modules, one per format: `legacy` (`.vtk`: tokenizer, unstructured and
//! structured datasets, writer), `xml` (serial XML:
//! the XML tree, the one DataArray decoder, `.vtu` and `.vts`/`.vtr`/`.vti`
//! grids, writers), `collection` (parallel `.pvt*` and multi-block `.vtm`).
//! [`read_image_grid`] (`image_grid.rs`) reads a `.vti` or STRUCTURED_POINTS
//! file as the regular grid it is (for shear-warp): the same parsing,
//! stopped before the cells are assembled.

mod collection;
mod error;
mod image_grid;
mod legacy;
mod numeric;
mod piece_subset;
mod xml;

use std::path::Path;

pub(crate) use collection::read_parts;
pub use error::VtkError;
pub(crate) use image_grid::image_grid_of;
pub use image_grid::{ImageGrid, read_image_data_with, read_image_grid};
pub use legacy::write::write_legacy;
pub use piece_subset::{PieceSubset, parallel_piece_count, read_piece_subset};
pub use xml::stream::{TetChunks, VtuIndex, VtuStreamOptions, write_vtu_streamed};
pub use xml::write::{VtuOptions, write_vtu, write_vtu_with};

pub use tetray_mesh::cells::{
    CellCounts, Linearize, PieceCounts, ReadOptions, SubdividedCells, VtkRead,
};

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

/// Where the points of an image lie: point `(i, j, k)` (from 0) at
/// `origin + direction * ((i, j, k) * spacing)`, `direction` row-major.
/// The readers report it beside their [`CellGrid`] for a single-piece
/// ImageData / STRUCTURED_POINTS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ImageGeometry {
    pub dims: [usize; 3],
    pub origin: [f64; 3],
    pub spacing: [f64; 3],
    pub direction: [f64; 9],
}

/// The one step from a file's raw cells to tetrahedra, for every reader
/// of this module: ghost cells and global ids handled, a structured grid
/// without volume cells refused, cells split.
pub(crate) fn assemble(
    grid: tetray_mesh::cells::CellGrid,
    name: &str,
    opts: &ReadOptions,
) -> Result<VtkRead, VtkError> {
    let grid = tetray_mesh::cells::finish_grid(grid, name)?;
    if grid.dataset != "UnstructuredGrid" {
        collection::require_volume(&grid, name, "")?;
    }
    Ok(tetray_mesh::cells::assemble_with(grid, name, opts)?)
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
    read_legacy_file_with(path, &ReadOptions::default())
}

/// [`read_legacy_file`] with options.
pub fn read_legacy_file_with(path: &Path, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
    read_legacy_bytes_with(&read_path(path)?, &path.display().to_string(), opts)
}

/// Reads a legacy VTK file held in memory; `name` is used in messages.
pub fn read_legacy_bytes(bytes: &[u8], name: &str) -> Result<VtkRead, VtkError> {
    read_legacy_bytes_with(bytes, name, &ReadOptions::default())
}

/// [`read_legacy_bytes`] with options.
pub fn read_legacy_bytes_with(
    bytes: &[u8],
    name: &str,
    opts: &ReadOptions,
) -> Result<VtkRead, VtkError> {
    legacy::read::read_with(bytes, name, opts)
}

/// Reads a serial XML file: `.vtu` (UnstructuredGrid), `.vts`
/// (StructuredGrid), `.vtr` (RectilinearGrid) or `.vti` (ImageData), chosen
/// by its `<VTKFile type>`; ascii, base64 or appended data, optionally
/// zlib-compressed.
pub fn read_vtu_file(path: &Path) -> Result<VtkRead, VtkError> {
    read_vtu_file_with(path, &ReadOptions::default())
}

/// [`read_vtu_file`] with options.
pub fn read_vtu_file_with(path: &Path, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
    let name = path.display().to_string();
    // The file's bytes are freed before the cells become tetrahedra: not
    // both in memory at the peak.
    let grid = xml::read_raw(&read_path(path)?, &name)?;
    assemble(grid, &name, opts)
}

/// Reads a serial XML file held in memory; `name` is used in messages.
pub fn read_vtu_bytes(bytes: &[u8], name: &str) -> Result<VtkRead, VtkError> {
    read_vtu_bytes_with(bytes, name, &ReadOptions::default())
}

/// [`read_vtu_bytes`] with options.
pub fn read_vtu_bytes_with(
    bytes: &[u8],
    name: &str,
    opts: &ReadOptions,
) -> Result<VtkRead, VtkError> {
    xml::read_with(bytes, name, opts)
}

/// Assembles a raw grid held in memory as [`read_vtu_bytes_with`] does the
/// grid it parses (the one path from raw arrays to tetrahedra).
pub fn assemble_grid(
    grid: tetray_mesh::cells::CellGrid,
    name: &str,
    opts: &ReadOptions,
) -> Result<VtkRead, VtkError> {
    assemble(grid, name, opts)
}

/// The grids of one dataset (CGNS zones, EnSight parts, OpenFOAM
/// processors) as one: a single grid as it is, several welded at their
/// shared points and counted as pieces.
pub(crate) fn join_grids(
    mut grids: Vec<tetray_mesh::cells::CellGrid>,
    name: &str,
) -> Result<tetray_mesh::cells::CellGrid, VtkError> {
    let count = grids.len();
    if count == 1 {
        return Ok(grids.pop().expect("one grid"));
    }
    let mut grid = tetray_mesh::cells::weld(grids, name)?;
    grid.pieces.pieces = count;
    Ok(grid)
}

/// Reads a parallel XML file (`.pvtu`, `.pvts`, `.pvtr`, `.pvti`): every
/// piece it names, relative to its folder, read in parallel, ghost cells
/// dropped, shared points welded into one mesh.
pub fn read_parallel_file(path: &Path) -> Result<VtkRead, VtkError> {
    read_parallel_file_with(path, &ReadOptions::default())
}

/// [`read_parallel_file`] with options (applied to every piece).
pub fn read_parallel_file_with(path: &Path, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
    collection::read_parallel(path, opts)
}

/// Reads a multi-block `.vtm` file: its volume blocks (any of the XML
/// formats above, nested blocks included) welded into one mesh; polygonal
/// and surface-only blocks are skipped with a note. `block` keeps only the
/// blocks of that name or path (`outer/inner`).
pub fn read_multiblock_file(path: &Path, block: Option<&str>) -> Result<VtkRead, VtkError> {
    read_multiblock_file_with(path, block, &ReadOptions::default())
}

/// [`read_multiblock_file`] with options (applied to every block).
pub fn read_multiblock_file_with(
    path: &Path,
    block: Option<&str>,
    opts: &ReadOptions,
) -> Result<VtkRead, VtkError> {
    collection::read_multiblock(path, block, opts)
}
