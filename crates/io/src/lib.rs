//! Mesh files: one module per format, each turning bytes into the cell
//! model of `tetray-mesh` ([`tetray_mesh::cells::CellGrid`]: points in f64,
//! cells with their VTK type, fields, pieces and blocks) and through its
//! one assembly step into tetrahedra; and [`load`], which picks the reader
//! by the file's name and finishes the mesh ([`tetray_mesh::finish`]:
//! orient, validate, topology), returning a [`LoadedMesh`]; [`probe`]
//! tells a file's format (by name, else by content) and whether it is image
//! data before anything is read.
//!
//! - [`vtk`]: legacy `.vtk`, serial XML (`.vtu`, `.vts`, `.vtr`, `.vti`,
//!   one DataArray decoder), parallel XML (`.pvt*`) and multi-block `.vtm`;
//!   writers for `.vtu` (whole or streamed) and legacy `.vtk`;
//! - [`exodus`]: Exodus II (netCDF);
//! - [`vtkhdf`]: VTKHDF (VTK's data model in HDF5), temporal and
//!   partitioned;
//! - [`plot3d`]: PLOT3D grids and solutions, read and written;
//! - [`generate`]: large test meshes written as files (refined PLOT3D
//!   grids, a torus shell as `.vtu`).
//!
//! A format module knows nothing of topology; `tetray-mesh` knows nothing
//! of files.

mod error;
mod h5;
mod load;
mod probe;

pub mod cgns;
pub mod ensight;
pub mod exodus;
pub mod generate;
pub mod openfoam;
pub mod plot3d;
pub mod preflight;
pub mod series;
pub mod time;
pub mod vtk;
pub mod vtkhdf;

pub use cgns::{CgnsError, CgnsOptions, CgnsRead, read_cgns};
pub use ensight::{EnSightError, EnSightOptions, EnSightRead, read_ensight};
pub use error::IoError;
pub use exodus::{ExodusError, ExodusOptions, ExodusRead, read_exodus_bytes, read_exodus_file};
pub use load::{
    LoadOptions, load, load_grid, load_image_data, load_image_grid, load_piece_subset,
    load_plot3d_bytes, plot3d_q_sibling, read_file,
};
pub use openfoam::{OpenFoamError, OpenFoamOptions, OpenFoamRead, read_openfoam};
pub use plot3d::{Plot3dRead, read_plot3d_bytes, read_plot3d_files};
pub use probe::{DataKind, Probe, probe};
pub use series::{SeriesError, SeriesStep, read_series};
pub use tetray_mesh::{ElementBlock, LoadReport, LoadedMesh};
pub use vtk::{ImageGrid, VtkError, read_image_grid};
pub use vtkhdf::{VtkHdfError, VtkHdfOptions, VtkHdfRead, read_vtkhdf_bytes, read_vtkhdf_file};
