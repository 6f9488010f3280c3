//! The error type of the VTK readers.

use tetray_mesh::cells::CellError;

/// Everything that can go wrong reading a VTK file. Every variant names the
/// file (the `name` given to the `*_bytes` readers, or the path) and the
/// section, array, line or cell at fault.
#[derive(Debug, thiserror::Error)]
pub enum VtkError {
    /// What the cell model found wrong assembling the file's cells (counts,
    /// indices, values, cell types and sizes, polyhedra, invalid arrays),
    /// with its message: the file, then the section or cell.
    #[error(transparent)]
    Cell(#[from] CellError),

    /// A grid whose size, from its header alone, needs more memory than
    /// there is (an image's points and cells are made, not read).
    #[error(transparent)]
    Memory(#[from] crate::preflight::MemoryError),

    /// The file could not be opened or read.
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },

    /// Text that is not what the format requires at that place.
    #[error("{file}: line {line}: {message}")]
    Syntax {
        file: String,
        line: usize,
        message: String,
    },

    /// The file ends (or the array's bytes end) before a section is complete.
    #[error("{file}: {section}: data ends early: expected {expected} {unit}, found {found}")]
    Truncated {
        file: String,
        section: String,
        expected: usize,
        found: usize,
        /// "values", "bytes", ...
        unit: &'static str,
    },

    /// A dataset type the readers do not read (polygonal data...).
    #[error(
        "{file}: dataset \"{found}\" is not supported: the readers take unstructured grids, structured grids, rectilinear grids and images (legacy UNSTRUCTURED_GRID, STRUCTURED_GRID, RECTILINEAR_GRID, STRUCTURED_POINTS; XML .vtu, .vts, .vtr, .vti, their parallel forms and .vtm)"
    )]
    UnsupportedDataset { file: String, found: String },

    /// A piece of a parallel file, or a block of a multi-block file, that
    /// names a file which does not exist.
    #[error("{file}: {what} \"{source_name}\" is missing: no file {path}")]
    MissingFile {
        file: String,
        /// "piece" or "block \"name\"".
        what: String,
        /// As written in the file.
        source_name: String,
        /// Where it was looked for.
        path: String,
    },

    /// Nothing to render: no volume cell in the file (or the blocks kept).
    #[error("{file} holds {found}: nothing to volume-render")]
    NoVolumeCells {
        file: String,
        /// "only surface cells (16 quadrilaterals in 2 blocks)", "no cells"...
        found: String,
    },

    /// `--block` names no block of a multi-block file.
    #[error("{file}: no block named \"{block}\"; the blocks are: {blocks}")]
    NoSuchBlock {
        file: String,
        block: String,
        blocks: String,
    },

    /// XML that does not parse or lacks the structure of a .vtu file.
    #[error("{file}: line {line}: malformed XML: {message}")]
    Xml {
        file: String,
        line: usize,
        message: String,
    },

    /// A character that is not base64, or misplaced padding.
    #[error("{file}: {section}: bad base64 at character {position}: {message}")]
    Base64 {
        file: String,
        section: String,
        position: usize,
        message: String,
    },

    /// A zlib block that does not inflate, or inflates to the wrong size.
    #[error("{file}: {section}: zlib block {block} of {blocks}: {message}")]
    Zlib {
        file: String,
        section: String,
        block: usize,
        blocks: usize,
        message: String,
    },
}
