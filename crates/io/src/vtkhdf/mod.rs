//! VTKHDF (`.vtkhdf`, `.hdf`, `.hdf5`, `.h5`): VTK's data model stored in
//! HDF5 under a `/VTKHDF` group (VTK's "VTKHDF format specification",
//! versions 1.x and 2.x).
//!
//! - `UnstructuredGrid`: `Points`, `Types`, `Offsets` and `Connectivity`
//!   concatenated over the partitions (`NumberOfPoints`, `NumberOfCells`,
//!   `NumberOfConnectivityIds` give each one's share; each partition's
//!   offsets start at 0 and its connectivity indexes its own points);
//!   polyhedra through `FaceOffsets`, `FaceConnectivity`,
//!   `PolyhedronOffsets` and `PolyhedronToFaces`; partitions are welded
//!   like the pieces of a `.pvtu`.
//! - `ImageData`: `WholeExtent`, `Origin`, `Spacing` and `Direction`
//!   attributes, arrays shaped (z, y, x[, components]).
//! - Temporal data (`Steps`: `Values`, `PartOffsets`, `NumberOfParts`,
//!   `PointOffsets`, `CellOffsets`, `ConnectivityIdOffsets` and
//!   per-array `PointDataOffsets` / `CellDataOffsets`; for images a
//!   leading time dimension): one step is read, chosen by number or time.
//! - `PolyData` is surfaces: one clear error, as for the other formats;
//!   the composite and AMR types are refused by name.
//!
//! The arrays go into the cell model of `tetray-mesh` and through the same
//! assembly step as a `.vtu`. A file without a `Type` attribute is read by
//! what it holds (cells, or an image's extent).

mod image;
mod steps;
mod unstructured;

use std::path::Path;

use tetray_mesh::cells::{Linearize, ReadOptions, VtkRead};

use crate::preflight::MemoryError;
use crate::time::choose_step;
use crate::vtk::{ImageGrid, VtkError};
/// The HDF5 access, with this reader's errors.
type H5 = crate::h5::H5<VtkHdfError>;

impl crate::h5::H5Error for VtkHdfError {
    fn io(file: String, source: std::io::Error) -> Self {
        VtkHdfError::Io { file, source }
    }
    fn hdf5(file: String, what: String, message: String) -> Self {
        VtkHdfError::Hdf5 {
            file,
            what,
            message,
        }
    }
    fn invalid(file: String, what: String, message: String) -> Self {
        VtkHdfError::Invalid {
            file,
            what,
            message,
        }
    }
    fn missing(file: String, what: String) -> Self {
        VtkHdfError::Missing { file, what }
    }
    fn truncated(file: String, what: String, expected: u64, found: u64) -> Self {
        VtkHdfError::Truncated {
            file,
            what,
            expected,
            found,
        }
    }
    fn memory(e: MemoryError) -> Self {
        VtkHdfError::Memory(e)
    }
}

/// Everything that can go wrong reading a VTKHDF file; each names the file.
#[derive(Debug, thiserror::Error)]
pub enum VtkHdfError {
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },

    /// The HDF5 container or one of its objects could not be read.
    #[error("{file}: VTKHDF: {what}: {message}")]
    Hdf5 {
        file: String,
        what: String,
        message: String,
    },

    /// An object the format requires is absent.
    #[error("{file}: VTKHDF: no {what}")]
    Missing { file: String, what: String },

    /// Content that breaks the format's rules.
    #[error("{file}: VTKHDF: {what}: {message}")]
    Invalid {
        file: String,
        what: String,
        message: String,
    },

    /// A dataset whose declared size the file cannot hold.
    #[error(
        "{file}: VTKHDF: {what} declares {expected} bytes of data, more than the file's {found}"
    )]
    Truncated {
        file: String,
        what: String,
        expected: u64,
        found: u64,
    },

    /// A data type that holds no volume (surfaces) or that is not read.
    #[error("{file}: VTKHDF {found}: {why}")]
    Unsupported {
        file: String,
        found: String,
        why: &'static str,
    },

    /// A time step the file does not store, or a bad time.
    #[error("{file}: {message}")]
    Time { file: String, message: String },

    #[error(transparent)]
    Memory(#[from] MemoryError),

    /// The cells read could not be split into tetrahedra, or a value is
    /// not finite (the shared VTK assembly step).
    #[error(transparent)]
    Assemble(#[from] VtkError),
}

/// Options of [`read_vtkhdf_file`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct VtkHdfOptions {
    /// The 0-based time step of a temporal file (default: the first).
    pub time_step: Option<usize>,
    /// Read the time step whose time is nearest this.
    pub time: Option<f64>,
    pub linearize: Linearize,
}

/// A VTKHDF file read.
#[derive(Debug)]
pub struct VtkHdfRead {
    /// The cells split into tetrahedra, as the VTK readers give them.
    pub read: VtkRead,
    /// For image data, the regular grid itself (shear-warp renders it).
    pub image: Option<ImageGrid>,
    /// The stored times (empty for a file without steps).
    pub times: Vec<f64>,
    /// The step read, when the file has steps.
    pub time_step: Option<usize>,
    /// `Version` as stored (`[1, 0]`, `[2, 2]`...).
    pub version: [i64; 2],
}

/// Reads the VTKHDF file at `path`.
///
/// # Errors
/// [`VtkHdfError`], naming the file and the object at fault.
pub fn read_vtkhdf_file(path: &Path, opts: &VtkHdfOptions) -> Result<VtkHdfRead, VtkHdfError> {
    read(&H5::open(path)?, opts)
}

/// Reads a VTKHDF file held in memory (`name` is used in messages).
///
/// # Errors
/// As [`read_vtkhdf_file`].
pub fn read_vtkhdf_bytes(
    bytes: &[u8],
    name: &str,
    opts: &VtkHdfOptions,
) -> Result<VtkHdfRead, VtkHdfError> {
    read(&H5::from_bytes(bytes, name)?, opts)
}

/// Whether an HDF5 file holds a `/VTKHDF` group (and not, say, an Exodus
/// or CGNS tree).
pub(crate) fn is_vtkhdf(path: &Path) -> bool {
    H5::open(path).is_ok_and(|h5| h5.group("/VTKHDF").is_some())
}

/// Whether a VTKHDF file holds image data.
pub(crate) fn is_image_data(path: &Path) -> bool {
    H5::open(path).is_ok_and(|h5| {
        h5.group("/VTKHDF")
            .is_some_and(|root| data_type(&h5, &root) == "ImageData")
    })
}

/// The data type of the root: its `Type` attribute, else what it holds.
fn data_type(h5: &H5, root: &hdf5_reader::group::Group) -> String {
    if let Some(t) = h5.string_attribute(root, "Type") {
        return t;
    }
    if h5.numeric_attribute(root, "WholeExtent").is_some() {
        "ImageData".into()
    } else if h5.dataset(root, "Connectivity").is_some() || h5.dataset(root, "Types").is_some() {
        "UnstructuredGrid".into()
    } else if h5.group("/VTKHDF/Polygons").is_some() {
        "PolyData".into()
    } else {
        String::new()
    }
}

fn read(h5: &H5, opts: &VtkHdfOptions) -> Result<VtkHdfRead, VtkHdfError> {
    let root = h5.require_group("/VTKHDF")?;
    let version = match h5.numeric_attribute(&root, "Version").as_deref() {
        Some([major, minor, ..]) => [*major as i64, *minor as i64],
        Some([major]) => [*major as i64, 0],
        _ => [1, 0],
    };
    if version[0] > 2 {
        return Err(h5.invalid(
            "Version",
            format!(
                "{}.{} is newer than the versions read (1.x and 2.x)",
                version[0], version[1]
            ),
        ));
    }
    let kind = data_type(h5, &root);
    let steps = steps::Steps::read(h5)?;
    let time_step =
        choose_step(&steps.times, opts.time_step, opts.time).map_err(|e| VtkHdfError::Time {
            file: h5.name.clone(),
            message: e.to_string(),
        })?;
    let read_opts = ReadOptions {
        linearize: opts.linearize,
    };
    let unsupported = |why| VtkHdfError::Unsupported {
        file: h5.name.clone(),
        found: if kind.is_empty() {
            "(no Type)".into()
        } else {
            kind.clone()
        },
        why,
    };
    let (grid, image) = match kind.as_str() {
        "UnstructuredGrid" => (unstructured::read(h5, &root, &steps, time_step)?, None),
        "ImageData" => {
            let (grid, geometry) = image::read(h5, &root, &steps, time_step)?;
            (grid, Some(geometry))
        }
        "PolyData" => {
            return Err(unsupported(
                "polygonal data holds surfaces, no volume cell: nothing to volume-render",
            ));
        }
        "" => {
            return Err(unsupported(
                "the /VTKHDF group holds neither cells nor an image",
            ));
        }
        _ => {
            return Err(unsupported(
                "only UnstructuredGrid and ImageData are read (composite, AMR and hyper-tree \
                 data are not)",
            ));
        }
    };
    let image = match image {
        Some(geometry) => Some(crate::vtk::image_grid_of(&grid, geometry, &h5.name)?),
        None => None,
    };
    let read = crate::vtk::assemble_grid(grid, &h5.name, &read_opts)?;
    Ok(VtkHdfRead {
        read,
        image,
        times: steps.times,
        time_step,
        version,
    })
}
