//! The error type of the VTK readers.

use tetray_mesh::cells::CellError;

/// Everything that can go wrong reading a VTK file. Every variant names the
/// file (the `name` given to the `*_bytes` readers, or the path) and the
/// section, array, line or cell at fault.
#[derive(Debug, thiserror::Error)]
pub enum VtkError {
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

    /// Two counts that must agree do not (a header against the data, an
    /// array against the number of points or cells).
    #[error("{file}: {section}: {what}: expected {expected}, found {found}")]
    CountMismatch {
        file: String,
        section: String,
        what: String,
        expected: usize,
        found: usize,
    },

    /// A cell references a point that does not exist.
    #[error(
        "{file}: cell {cell}: point index {index} is out of range (the mesh has {npoints} points)"
    )]
    BadIndex {
        file: String,
        cell: usize,
        index: i64,
        npoints: usize,
    },

    /// A coordinate or scalar is NaN or infinite (also after conversion to
    /// f32, so values beyond f32's range land here).
    #[error("{file}: {section}: value {index} is {value}, not a finite number")]
    NonFinite {
        file: String,
        section: String,
        index: usize,
        value: f64,
    },

    /// A 3-D cell type that cannot be split into tetrahedra, or an unknown
    /// type id.
    #[error(
        "{file}: cell {cell}: VTK cell type {type_id} ({type_name}) is not supported; \
         volume cells must be linear (10-16), quadratic (24-27, 29, 32), Lagrange of order 2 \
         (71-73) or polyhedra (42)"
    )]
    UnsupportedCell {
        file: String,
        cell: usize,
        type_id: i64,
        type_name: &'static str,
    },

    /// A cell whose number of points does not fit its type.
    #[error(
        "{file}: cell {cell}: a {type_name} (type {type_id}) has {expected} points, found {found}"
    )]
    CellSize {
        file: String,
        cell: usize,
        type_id: i64,
        type_name: &'static str,
        expected: usize,
        found: usize,
    },

    /// A polyhedron whose faces are missing, malformed, out of range or do
    /// not close a volume.
    #[error("{file}: cell {cell}: polyhedron: {message}")]
    BadPolyhedron {
        file: String,
        cell: usize,
        message: String,
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

    /// A known feature this reader does not implement: an encoding, a
    /// compressor, a data type, a byte order, a format.
    #[error("{file}: {section}: unsupported {what} \"{value}\"")]
    Unsupported {
        file: String,
        section: String,
        what: &'static str,
        value: String,
    },

    /// Structurally invalid content not covered above (missing arrays,
    /// decreasing offsets, wrong number of components...).
    #[error("{file}: {section}: {message}")]
    Invalid {
        file: String,
        section: String,
        message: String,
    },
}

impl From<CellError> for VtkError {
    /// The model's errors read as the reader's own, with the same message
    /// (the cell model names the file as the reader does).
    fn from(e: CellError) -> Self {
        match e {
            CellError::CountMismatch {
                file,
                section,
                what,
                expected,
                found,
            } => VtkError::CountMismatch {
                file,
                section,
                what,
                expected,
                found,
            },
            CellError::BadIndex {
                file,
                cell,
                index,
                npoints,
            } => VtkError::BadIndex {
                file,
                cell,
                index,
                npoints,
            },
            CellError::NonFinite {
                file,
                section,
                index,
                value,
            } => VtkError::NonFinite {
                file,
                section,
                index,
                value,
            },
            CellError::UnsupportedCell {
                file,
                cell,
                type_id,
                type_name,
            } => VtkError::UnsupportedCell {
                file,
                cell,
                type_id,
                type_name,
            },
            CellError::CellSize {
                file,
                cell,
                type_id,
                type_name,
                expected,
                found,
            } => VtkError::CellSize {
                file,
                cell,
                type_id,
                type_name,
                expected,
                found,
            },
            CellError::BadPolyhedron {
                file,
                cell,
                message,
            } => VtkError::BadPolyhedron {
                file,
                cell,
                message,
            },
            CellError::Unsupported {
                file,
                section,
                what,
                value,
            } => VtkError::Unsupported {
                file,
                section,
                what,
                value,
            },
            CellError::Invalid {
                file,
                section,
                message,
            } => VtkError::Invalid {
                file,
                section,
                message,
            },
        }
    }
}
