//! CGNS in either storage: HDF5 (the default since CGNS 3: every node a
//! group with `name`, `label` and `type` attributes and its data in a
//! ` data` dataset, arrays in Fortran order, so HDF5's shape is reversed)
//! or the older ADF (`adf.rs`). Both give the same tree. Read:
//! the 3-D bases, their structured zones (`GridCoordinates`, cells of the
//! vertex lattice) and unstructured zones (`Elements_t` of the linear
//! and quadratic types, MIXED, NGON_n faces and NFACE_n polyhedra), and
//! `FlowSolution_t` arrays at `Vertex` or `CellCenter` (with `Rind`
//! layers stripped), of one step of the iterative data. Zones are welded.

mod adf;
mod zone;

use std::path::Path;

use tetray_mesh::cells::{Linearize, ReadOptions, VtkRead};

use crate::preflight::MemoryError;
use crate::time::choose_step;
use crate::vtk::VtkError;

/// The HDF5 access, with this reader's errors.
type H5 = crate::h5::H5<CgnsError>;

/// Everything that can go wrong reading a CGNS file; each names the file.
#[derive(Debug, thiserror::Error)]
pub enum CgnsError {
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{file}: CGNS: {what}: {message}")]
    Hdf5 {
        file: String,
        what: String,
        message: String,
    },
    #[error("{file}: CGNS: {what}: {message}")]
    Invalid {
        file: String,
        what: String,
        message: String,
    },
    #[error("{file}: CGNS: no {what}")]
    Missing { file: String, what: String },
    #[error("{file}: CGNS: {what} declares {expected} bytes of data, more than the file's {found}")]
    Truncated {
        file: String,
        what: String,
        expected: u64,
        found: u64,
    },
    /// A time step the file does not store, or a bad time.
    #[error("{file}: {message}")]
    Time { file: String, message: String },
    #[error(transparent)]
    Memory(#[from] MemoryError),
    #[error(transparent)]
    Assemble(#[from] VtkError),
}

impl crate::h5::H5Error for CgnsError {
    fn io(file: String, source: std::io::Error) -> Self {
        CgnsError::Io { file, source }
    }
    fn hdf5(file: String, what: String, message: String) -> Self {
        CgnsError::Hdf5 {
            file,
            what,
            message,
        }
    }
    fn invalid(file: String, what: String, message: String) -> Self {
        CgnsError::Invalid {
            file,
            what,
            message,
        }
    }
    fn missing(file: String, what: String) -> Self {
        CgnsError::Missing { file, what }
    }
    fn truncated(file: String, what: String, expected: u64, found: u64) -> Self {
        CgnsError::Truncated {
            file,
            what,
            expected,
            found,
        }
    }
    fn memory(e: MemoryError) -> Self {
        CgnsError::Memory(e)
    }
}

/// Options of [`read_cgns`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CgnsOptions {
    pub linearize: Linearize,
    /// The 0-based step of a file with iterative data (default: the first).
    pub time_step: Option<usize>,
    /// Read the step whose time is nearest this.
    pub time: Option<f64>,
}

/// A CGNS file read.
#[derive(Debug)]
pub struct CgnsRead {
    pub read: VtkRead,
    /// Zones read (welded into one grid).
    pub zones: usize,
    /// The times of the iterative data (empty for a file without).
    pub times: Vec<f64>,
    /// The step read, when there are times.
    pub time_step: Option<usize>,
}

/// Whether the first bytes are an ADF file (CGNS's older storage): a
/// what-string marker (`@(#)`, written with the high bits set or not),
/// then `ADF Database Version`.
pub(crate) fn is_adf(head: &[u8]) -> bool {
    head.get(4..)
        .is_some_and(|h| h.starts_with(b"ADF Database Version"))
}

/// Whether an HDF5 file is a CGNS tree (a `CGNSLibraryVersion` node or a
/// base labelled `CGNSBase_t`).
pub(crate) fn is_cgns(path: &Path) -> bool {
    let Ok(h5) = H5::open(path) else {
        return false;
    };
    let tree = Tree::Hdf5(h5);
    tree.label("/CGNSLibraryVersion") == "CGNSLibraryVersion_t"
        || tree
            .children("/", "CGNSBase_t")
            .is_ok_and(|bases| !bases.is_empty())
}

/// A CGNS tree in either storage; paths are absolute (`/Base/Zone`).
enum Tree {
    Hdf5(H5),
    Adf(adf::Adf),
}

impl Tree {
    fn invalid(&self, what: &str, message: String) -> CgnsError {
        match self {
            Tree::Hdf5(h5) => h5.invalid(what, message),
            Tree::Adf(adf) => adf.invalid(what, message),
        }
    }

    /// A node's label (`Zone_t`), empty when it has none.
    fn label(&self, path: &str) -> String {
        match self {
            Tree::Hdf5(h5) => h5
                .group(path)
                .and_then(|g| h5.string_attribute(&g, "label"))
                .unwrap_or_default(),
            Tree::Adf(adf) => adf.label(path).unwrap_or_default(),
        }
    }

    /// The paths of the children of the node at `path` labelled `wanted`.
    fn children(&self, path: &str, wanted: &str) -> Result<Vec<String>, CgnsError> {
        let names = match self {
            Tree::Hdf5(h5) => {
                let group = h5.require_group(path)?;
                h5.group_names(&group, path)?
            }
            Tree::Adf(adf) => adf.children(path)?,
        };
        Ok(names
            .iter()
            .map(|name| format!("{}/{name}", path.trim_end_matches('/')))
            .filter(|child| self.label(child) == wanted)
            .collect())
    }

    /// The data of the node at `path` as f64, in Fortran order.
    fn data_f64(&self, path: &str) -> Result<Vec<f64>, CgnsError> {
        match self {
            Tree::Hdf5(h5) => {
                let group = h5.require_group(path)?;
                let ds = h5.require_dataset(&group, path, " data")?;
                h5.all_f64(&ds, path)
            }
            Tree::Adf(adf) => adf.data_f64(path),
        }
    }

    fn data_i64(&self, path: &str) -> Result<Vec<i64>, CgnsError> {
        match self {
            Tree::Hdf5(h5) => {
                let group = h5.require_group(path)?;
                let ds = h5.require_dataset(&group, path, " data")?;
                h5.all_i64(&ds, path)
            }
            Tree::Adf(adf) => adf.data_i64(path),
        }
    }

    /// The data of a character node (`C1`) as text.
    fn data_text(&self, path: &str) -> Option<String> {
        let chars = self.data_i64(path).ok()?;
        let bytes: Vec<u8> = chars.iter().map(|&c| c as u8).collect();
        Some(
            String::from_utf8_lossy(&bytes)
                .trim_end_matches('\0')
                .trim()
                .to_string(),
        )
    }
}

/// The times of a base's iterative data (`BaseIterativeData_t`: its
/// number of steps, and `TimeValues`, else `IterationValues`, else the
/// step numbers); empty when it has none.
fn iterative_times(tree: &Tree, base: &str) -> Result<Vec<f64>, CgnsError> {
    let Some(data) = tree
        .children(base, "BaseIterativeData_t")?
        .into_iter()
        .next()
    else {
        return Ok(Vec::new());
    };
    let steps = tree.data_i64(&data)?.first().copied().unwrap_or(0);
    let steps =
        usize::try_from(steps).map_err(|_| tree.invalid(&data, format!("{steps} steps")))?;
    for name in ["TimeValues", "IterationValues"] {
        let path = format!("{data}/{name}");
        if tree.label(&path) == "DataArray_t" {
            let values = tree.data_f64(&path)?;
            if values.len() != steps {
                return Err(
                    tree.invalid(&path, format!("{} values for {steps} steps", values.len()))
                );
            }
            return Ok(values);
        }
    }
    Ok((0..steps).map(|s| s as f64).collect())
}

/// Reads the CGNS file at `path`.
///
/// # Errors
/// [`CgnsError`] naming the file and the node at fault.
pub fn read_cgns(path: &Path, opts: &CgnsOptions) -> Result<CgnsRead, CgnsError> {
    let name = path.display().to_string();
    let mut head = [0u8; 32];
    let mut n = 0;
    if let Ok(mut f) = std::fs::File::open(path) {
        use std::io::Read;
        n = f.read(&mut head).unwrap_or(0);
    }
    let tree = if is_adf(&head[..n]) {
        Tree::Adf(adf::Adf::open(path)?)
    } else {
        Tree::Hdf5(H5::open(path)?)
    };
    let mut grids = Vec::new();
    let mut warnings = Vec::new();
    let mut bases = Vec::new();
    for base in tree.children("/", "CGNSBase_t")? {
        let dims = tree.data_f64(&base)?;
        if dims.first().copied() == Some(3.0) {
            bases.push(base);
        } else {
            warnings.push(format!(
                "base {base}: cell dimension {:?}, not 3: skipped",
                dims.first()
            ));
        }
    }
    let times = match bases.first() {
        Some(base) => iterative_times(&tree, base)?,
        None => Vec::new(),
    };
    let time_step =
        choose_step(&times, opts.time_step, opts.time).map_err(|e| CgnsError::Time {
            file: name.clone(),
            message: e.to_string(),
        })?;
    for base in &bases {
        for zone in tree.children(base, "Zone_t")? {
            grids.push(zone::read_zone(&tree, &zone, time_step)?);
        }
    }
    if grids.is_empty() {
        return Err(CgnsError::Missing {
            file: name,
            what: "3-D base with a zone".into(),
        });
    }
    let zones = grids.len();
    let mut grid = crate::vtk::join_grids(grids, &name)?;
    grid.warnings.extend(warnings);
    let read = crate::vtk::assemble_grid(
        grid,
        &name,
        &ReadOptions {
            linearize: opts.linearize,
        },
    )?;
    Ok(CgnsRead {
        read,
        zones,
        times,
        time_step,
    })
}
