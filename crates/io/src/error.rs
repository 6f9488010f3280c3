//! The error of the readers and writers: the file at fault, and what is
//! wrong with it. Errors of the mesh a file holds (validation) are
//! [`MeshError`]s, wrapped so their message names the file.

use tetray_mesh::MeshError;

use crate::exodus::ExodusError;
use crate::preflight::MemoryError;
use crate::vtk::VtkError;
use crate::vtkhdf::VtkHdfError;

/// Everything that can go wrong loading a mesh from a file. Each variant
/// names the file.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
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

    /// The VTKHDF reader failed.
    #[error(transparent)]
    VtkHdf(#[from] VtkHdfError),

    /// The CGNS reader failed.
    #[error(transparent)]
    Cgns(#[from] crate::cgns::CgnsError),

    /// The EnSight Gold reader failed.
    #[error(transparent)]
    EnSight(#[from] crate::ensight::EnSightError),

    /// The OpenFOAM reader failed.
    #[error(transparent)]
    OpenFoam(#[from] crate::openfoam::OpenFoamError),

    /// A series file (`.series`, `.pvd`) that cannot be read, or one of
    /// its steps.
    #[error(transparent)]
    Series(#[from] crate::series::SeriesError),

    /// A time step or time asked of a file that stores none.
    #[error("{file}: {message}")]
    Time { file: String, message: String },

    /// The file's declared sizes need more memory than is available.
    #[error(transparent)]
    Memory(#[from] MemoryError),

    /// Neither the file's name nor its content says which reader to use.
    #[error(
        "{file}: unknown mesh format ({seen}): expected .vtk, .vtu, .vts, .vtr, .vti, \
         .pvtu, .pvts, .pvtr, .pvti, .vtm, an Exodus II file (.e, .exo, .ex2, .exii, .g, \
         .gen, .e-s*), VTKHDF (.vtkhdf, .hdf, .h5), an OpenFOAM case (its folder, \
         system/controlDict or a .foam file), EnSight Gold (.case), CGNS (.cgns), a PLOT3D grid (name ending in \
         xyz.bin, .xyz or .x) or a file series (.series, .pvd)"
    )]
    UnknownFormat {
        file: String,
        /// What the file starts with.
        seen: String,
    },

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

    /// The mesh read is unusable (validation); wrapped in
    /// [`MeshError::InFile`] when it came from a file.
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

impl IoError {
    /// The mesh error at the root of this one (without the file wrapper of
    /// [`MeshError::InFile`]), when it is one.
    pub fn mesh_root(&self) -> Option<&MeshError> {
        match self {
            IoError::Mesh(e) => Some(e.root()),
            _ => None,
        }
    }
}
