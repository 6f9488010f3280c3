//! The error type of the mesh crate.

/// Everything that makes a mesh unusable. Each variant names what is at
/// fault: the cell (tetrahedron index), the point, the field; a mesh read
/// from a file has its errors wrapped in [`MeshError::InFile`], naming it.
/// File errors are `tetray-io`'s (`IoError`), which wraps these.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
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
    /// an error that already names its file is left as it is.
    pub fn in_file(self, file: &str) -> MeshError {
        match self {
            MeshError::InFile { .. } => self,
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
