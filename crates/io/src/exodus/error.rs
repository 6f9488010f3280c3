//! The error type of the Exodus II reader.

use tetray_mesh::cells::CellError;

use crate::vtk::VtkError;

/// Everything that can go wrong reading an Exodus II file. Every variant
/// names the file (the `name` given to [`super::read_exodus_bytes`], or the
/// path) and the dimension, variable, block or element at fault.
#[derive(Debug, thiserror::Error)]
pub enum ExodusError {
    /// The file could not be opened or read.
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },

    /// The netCDF container does not parse, or a variable's data cannot be
    /// read from it (a truncated or garbled file).
    #[error("{file}: not a readable Exodus II (netCDF) file: {what}: {message}")]
    NetCdf {
        file: String,
        /// What was being read ("header", "variable \"connect1\"", ...).
        what: String,
        message: String,
    },

    /// The file's sizes need more memory than the machine has.
    #[error(transparent)]
    Memory(#[from] crate::preflight::MemoryError),

    /// A dimension or variable the Exodus II format requires is absent.
    #[error("{file}: Exodus II file has no {what}")]
    Missing { file: String, what: String },

    /// A variable whose shape or length disagrees with the dimensions.
    #[error("{file}: variable \"{variable}\": expected {expected} values ({what}), found {found}")]
    WrongLength {
        file: String,
        variable: String,
        what: String,
        expected: usize,
        found: usize,
    },

    /// A block's connectivity names a node that does not exist (Exodus
    /// node ids are 1-based: 1..=num_nodes).
    #[error(
        "{file}: element block {block}: element {element} uses node id {node_id}, \
         but node ids run from 1 to {num_nodes}"
    )]
    BadNodeId {
        file: String,
        block: String,
        /// 1-based within the block.
        element: usize,
        node_id: i64,
        num_nodes: usize,
    },

    /// A volume element type with a node count this reader does not map,
    /// or an element type it does not know.
    #[error(
        "{file}: element block {block}: unsupported element type \"{elem_type}\" with {nodes} nodes per element ({why})"
    )]
    UnsupportedElement {
        file: String,
        block: String,
        elem_type: String,
        nodes: usize,
        why: &'static str,
    },

    /// Nothing to render: every block is a surface, shell, beam... or empty.
    #[error("{file}: Exodus II file has no volume element block (blocks: {blocks})")]
    NoVolumeBlock { file: String, blocks: String },

    /// The requested time step is not stored.
    #[error("{file}: time step {requested} is out of range: the file stores {count} time step(s){}", if *count > 0 { format!(" (0..={})", count - 1) } else { String::new() })]
    TimeStepOutOfRange {
        file: String,
        requested: usize,
        count: usize,
    },

    /// A time was asked for but the file stores none, the time is not a
    /// finite number, or a step and a time were both given.
    #[error("{file}: {message}")]
    Time { file: String, message: String },

    /// Structurally invalid content not covered above.
    #[error("{file}: {what}: {message}")]
    Invalid {
        file: String,
        what: String,
        message: String,
    },

    /// The cells read could not be split into tetrahedra, or a value is
    /// not finite (the shared VTK assembly step).
    #[error(transparent)]
    Assemble(#[from] VtkError),
}

impl From<CellError> for ExodusError {
    /// The shared assembly step's errors, as the VTK readers report them.
    fn from(e: CellError) -> Self {
        ExodusError::Assemble(e.into())
    }
}
