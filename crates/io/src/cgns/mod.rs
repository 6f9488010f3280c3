//! CGNS in its HDF5 storage (the default since CGNS 3): every node a group
//! with `name`, `label` and `type` attributes and its data in a ` data`
//! dataset, arrays in Fortran order (so HDF5's shape is reversed). Read:
//! the 3-D bases, their structured zones (`GridCoordinates`, cells of the
//! vertex lattice) and unstructured zones (`Elements_t` of the linear
//! types, MIXED, and the quadratic tetrahedra and pyramids whose node
//! order is VTK's), and `FlowSolution_t` arrays at `Vertex` or
//! `CellCenter` (with `Rind` layers stripped). Zones are welded. Files in
//! the older ADF storage are recognised and refused with the conversion
//! that makes them readable (`adf2hdf`).

mod zone;

use std::path::Path;

use tetray_mesh::cells::{Linearize, ReadOptions, VtkRead, weld};

use crate::preflight::MemoryError;
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
    /// The older ADF storage, which this reader does not parse.
    #[error(
        "{file}: CGNS in the ADF storage is not read; convert it to the HDF5 storage (CGNS's \
         `adf2hdf {file} out.cgns`, Debian package cgns-convert) and open that"
    )]
    Adf { file: String },
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
}

/// A CGNS file read.
#[derive(Debug)]
pub struct CgnsRead {
    pub read: VtkRead,
    /// Zones read (welded into one grid).
    pub zones: usize,
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
    let Some(root) = h5.group("/") else {
        return false;
    };
    h5.group("/CGNSLibraryVersion").is_some()
        || h5.group_names(&root, "/").is_ok_and(|names| {
            names.iter().any(|n| {
                h5.group(&format!("/{n}"))
                    .is_some_and(|g| label(&h5, &g) == "CGNSBase_t")
            })
        })
}

/// A node's `label` attribute.
fn label(h5: &H5, group: &hdf5_reader::group::Group) -> String {
    h5.string_attribute(group, "label").unwrap_or_default()
}

/// The children of the node at `path` whose label is `wanted`, by name.
fn children(h5: &H5, path: &str, wanted: &str) -> Result<Vec<String>, CgnsError> {
    let group = h5.require_group(path)?;
    let mut out = Vec::new();
    for name in h5.group_names(&group, path)? {
        let child = format!("{}/{name}", path.trim_end_matches('/'));
        if h5.group(&child).is_some_and(|g| label(h5, &g) == wanted) {
            out.push(child);
        }
    }
    Ok(out)
}

/// The ` data` of the node at `path` as f64, with its HDF5 shape.
fn data_f64(h5: &H5, path: &str) -> Result<(Vec<f64>, Vec<usize>), CgnsError> {
    let group = h5.require_group(path)?;
    let ds = h5.require_dataset(&group, path, " data")?;
    let shape = crate::h5::H5::<CgnsError>::shape(&ds);
    Ok((h5.all_f64(&ds, path)?, shape))
}

fn data_i64(h5: &H5, path: &str) -> Result<Vec<i64>, CgnsError> {
    let group = h5.require_group(path)?;
    let ds = h5.require_dataset(&group, path, " data")?;
    h5.all_i64(&ds, path)
}

/// The ` data` of a character node (`C1`) as text.
fn data_text(h5: &H5, path: &str) -> Option<String> {
    let chars = data_i64(h5, path).ok()?;
    let bytes: Vec<u8> = chars.iter().map(|&c| c as u8).collect();
    Some(
        String::from_utf8_lossy(&bytes)
            .trim_end_matches('\0')
            .trim()
            .to_string(),
    )
}

/// Reads the CGNS file at `path`.
///
/// # Errors
/// [`CgnsError`] naming the file and the node at fault.
pub fn read_cgns(path: &Path, opts: &CgnsOptions) -> Result<CgnsRead, CgnsError> {
    let name = path.display().to_string();
    let mut head = [0u8; 32];
    if let Ok(mut f) = std::fs::File::open(path) {
        use std::io::Read;
        let n = f.read(&mut head).unwrap_or(0);
        if is_adf(&head[..n]) {
            return Err(CgnsError::Adf { file: name });
        }
    }
    let h5 = H5::open(path)?;
    let mut grids = Vec::new();
    let mut warnings = Vec::new();
    for base in children(&h5, "/", "CGNSBase_t")? {
        let (dims, _) = data_f64(&h5, &base)?;
        if dims.first().copied() != Some(3.0) {
            warnings.push(format!(
                "base {base}: cell dimension {:?}, not 3: skipped",
                dims.first()
            ));
            continue;
        }
        for zone in children(&h5, &base, "Zone_t")? {
            grids.push(zone::read_zone(&h5, &zone, &mut warnings)?);
        }
    }
    if grids.is_empty() {
        return Err(CgnsError::Missing {
            file: name,
            what: "3-D base with a zone".into(),
        });
    }
    let zones = grids.len();
    let mut grid = if zones == 1 {
        grids.pop().expect("one zone")
    } else {
        let mut g = weld(grids, &name).map_err(|e| CgnsError::from(VtkError::from(e)))?;
        g.pieces.pieces = zones;
        g
    };
    grid.warnings.extend(warnings);
    let read = crate::vtk::assemble_grid(
        grid,
        &name,
        &ReadOptions {
            linearize: opts.linearize,
        },
    )?;
    Ok(CgnsRead { read, zones })
}
