//! The error of the cell model: what assembling a grid can find wrong.

/// A grid that cannot become tetrahedra. Every variant names the file (the
/// name the grid was given) and the section, array or cell at fault; the
/// readers in `tetray-io` report these as their own errors, message
/// unchanged.
#[derive(Debug, thiserror::Error)]
pub enum CellError {
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
