//! VTK readers and writers: legacy `.vtk` UNSTRUCTURED_GRID and XML `.vtu`.
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
//!   range are errors.

mod assemble;
mod cells;
mod error;
mod legacy_lex;
mod legacy_read;
mod legacy_write;
mod numeric;
mod split;
mod vtu_data;
mod vtu_read;
mod vtu_stream;
mod vtu_write;
mod vtu_xml;

use std::path::Path;

pub use error::VtkError;
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
    /// The points are stored relative to this origin (f64; see
    /// [`crate::centring_origin`]): a point's coordinates as in the file
    /// are `origin + point`.
    pub origin: glam::DVec3,
    /// Per tetrahedron, the index of the file's cell it was split from.
    pub tet_cells: Vec<u32>,
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

/// Reads a legacy `.vtk` file (UNSTRUCTURED_GRID, ASCII or BINARY).
pub fn read_legacy_file(path: &Path) -> Result<VtkRead, VtkError> {
    read_legacy_bytes(&read_path(path)?, &path.display().to_string())
}

/// Reads a legacy VTK file held in memory; `name` is used in messages.
pub fn read_legacy_bytes(bytes: &[u8], name: &str) -> Result<VtkRead, VtkError> {
    legacy_read::read(bytes, name)
}

/// Reads an XML `.vtu` file (UnstructuredGrid; ascii, base64 or appended
/// data, optionally zlib-compressed).
pub fn read_vtu_file(path: &Path) -> Result<VtkRead, VtkError> {
    read_vtu_bytes(&read_path(path)?, &path.display().to_string())
}

/// Reads a `.vtu` file held in memory; `name` is used in messages.
pub fn read_vtu_bytes(bytes: &[u8], name: &str) -> Result<VtkRead, VtkError> {
    vtu_read::read(bytes, name)
}
