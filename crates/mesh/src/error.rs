//! The error type of the mesh crate.

use crate::exodus::ExodusError;
use crate::vtk::VtkError;

/// Everything that makes a mesh unusable. Each variant names what is at
/// fault: the file, the cell (tetrahedron index), the point, the field.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// A file could not be opened or read.
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },

    /// The VTK legacy or XML reader failed.
    #[error(transparent)]
    Vtk(#[from] VtkError),

    /// The Exodus II reader failed.
    #[error(transparent)]
    Exodus(#[from] ExodusError),

    /// The file name does not say which reader to use.
    #[error(
        "{file}: unknown mesh format: expected .vtk, .vtu, .vts, .vtr, .vti, .pvtu, \
         .pvts, .pvtr, .pvti, .vtm, an Exodus II file (.e, .exo, .ex2, .g, .gen) or a \
         PLOT3D grid (name ending in xyz.bin, .xyz or .x)"
    )]
    UnknownFormat { file: String },

    /// A PLOT3D header that fits no layout this reader knows.
    #[error("{file}: PLOT3D {what} file: {message}")]
    Plot3dHeader {
        file: String,
        /// "grid" or "solution".
        what: &'static str,
        message: String,
    },

    /// A PLOT3D file shorter than its header says it must be.
    #[error(
        "{file}: PLOT3D {what} file is too short: a {ni} x {nj} x {nk} grid needs \
         {expected} bytes ({layout}), the file has {found}"
    )]
    Plot3dTruncated {
        file: String,
        what: &'static str,
        ni: usize,
        nj: usize,
        nk: usize,
        layout: String,
        expected: usize,
        found: usize,
    },

    /// The solution (q) file is for another grid.
    #[error(
        "{q_file}: PLOT3D solution is {q_dims:?} points, but the grid {xyz_file} is {xyz_dims:?}"
    )]
    Plot3dDimsMismatch {
        xyz_file: String,
        q_file: String,
        xyz_dims: [usize; 3],
        q_dims: [usize; 3],
    },

    /// No tetrahedra at all.
    #[error("the mesh has no tetrahedra")]
    Empty,

    /// More points or tetrahedra than 32-bit indices can address.
    #[error("the mesh has {count} {what}; at most {max} are supported")]
    TooLarge {
        what: &'static str,
        count: usize,
        max: usize,
    },

    /// A scalar field whose length is not the number of points.
    #[error("field \"{field}\" has {found} values but the mesh has {expected} points")]
    FieldLength {
        field: String,
        expected: usize,
        found: usize,
    },

    /// A tetrahedron references a point that does not exist.
    #[error(
        "tetrahedron {tet}: vertex {corner} is point {index}, but the mesh has {npoints} points"
    )]
    DanglingIndex {
        tet: usize,
        corner: usize,
        index: u32,
        npoints: usize,
    },

    /// A tetrahedron uses the same point twice.
    #[error("tetrahedron {tet} uses point {point} twice (vertices {vertices:?})")]
    RepeatedVertex {
        tet: usize,
        point: u32,
        vertices: [u32; 4],
    },

    /// A point coordinate is NaN or infinite.
    #[error("point {point}: coordinate {axis} is {value}, not a finite number")]
    NonFiniteCoordinate {
        point: usize,
        axis: char,
        value: f32,
    },

    /// A scalar value is NaN or infinite.
    #[error("field \"{field}\": the value at point {point} is {value}, not a finite number")]
    NonFiniteScalar {
        field: String,
        point: usize,
        value: f32,
    },

    /// A tetrahedron too flat for its orientation to be trusted (see
    /// [`crate::DEGENERATE_HEIGHT_ULPS`]).
    #[error(
        "tetrahedron {tet} (points {vertices:?}) is degenerate: its smallest height \
         {min_height:e} is within {threshold:e} of f32 rounding at its coordinates \
         (6 V = {volume6:e})"
    )]
    DegenerateTet {
        tet: usize,
        vertices: [u32; 4],
        volume6: f64,
        min_height: f64,
        threshold: f64,
    },

    /// A negatively oriented tetrahedron where positive orientation is
    /// required (call [`crate::TetMesh::orient`] first).
    #[error("tetrahedron {tet} (points {vertices:?}) is negatively oriented")]
    Inverted { tet: usize, vertices: [u32; 4] },

    /// A face shared by more than two tetrahedra.
    #[error("the face with points {vertices:?} is shared by {} tetrahedra: {tets:?}", tets.len())]
    NonManifoldFace { vertices: [u32; 3], tets: Vec<u32> },

    /// Two tetrahedra share a face but lie on the same side of it.
    #[error(
        "tetrahedra {tet_a} and {tet_b} share the face {vertices:?} but lie on the same \
         side of it (they overlap)"
    )]
    Overlapping {
        tet_a: u32,
        tet_b: u32,
        vertices: [u32; 3],
    },

    /// Every tetrahedron was left out of the walk (see `exclude.rs`).
    #[error(
        "nothing left to render: all {tets} tetrahedra were left out ({flat} flat, the others \
         in {cells} cells that are tangled, overlap a neighbour or share a face with two others)"
    )]
    NothingLeft {
        tets: usize,
        flat: usize,
        cells: usize,
    },

    /// A mesh read from a file failed validation: the file and the reason.
    #[error("{file}: {source}")]
    InFile {
        file: String,
        #[source]
        source: Box<MeshError>,
    },
}

impl MeshError {
    /// Wraps an error found after reading `file`, so the message names it;
    /// errors that already name their file are left as they are.
    pub(crate) fn in_file(self, file: &str) -> MeshError {
        match self {
            MeshError::Io { .. }
            | MeshError::Vtk(_)
            | MeshError::Exodus(_)
            | MeshError::UnknownFormat { .. }
            | MeshError::Plot3dHeader { .. }
            | MeshError::Plot3dTruncated { .. }
            | MeshError::Plot3dDimsMismatch { .. }
            | MeshError::InFile { .. } => self,
            other => MeshError::InFile {
                file: file.to_string(),
                source: Box::new(other),
            },
        }
    }

    /// The error without the file wrapper of [`MeshError::InFile`].
    pub fn root(&self) -> &MeshError {
        match self {
            MeshError::InFile { source, .. } => source.root(),
            other => other,
        }
    }
}
