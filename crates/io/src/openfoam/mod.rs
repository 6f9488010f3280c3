//! OpenFOAM cases: a case folder, its `system/controlDict`, or a `.foam` /
//! `.OpenFOAM` marker file in it. The mesh is `constant/polyMesh` (or a
//! time folder's own `polyMesh`, for moving meshes); the time folders
//! (folders named by a number: `0`, `0.5`, `1e-05`) are the time steps,
//! their `volScalarField` and `volVectorField` files the cell fields. A
//! case without `constant/polyMesh` but with `processor*` folders is read
//! decomposed: every processor's mesh and fields, welded like the pieces of
//! a `.pvtu`. Files may be ASCII or binary, gzip-compressed (`points.gz`).
//! Cell fields become point fields by averaging, as for the VTK formats.

mod fields;
mod foam;
mod mesh;

use std::io::Read;
use std::path::{Path, PathBuf};

use tetray_mesh::cells::{CellError, Linearize, ReadOptions, VtkRead};

use crate::time::choose_step;
use crate::vtk::VtkError;

/// Everything that can go wrong reading an OpenFOAM case; each names the
/// file or folder.
#[derive(Debug, thiserror::Error)]
pub enum OpenFoamError {
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },

    /// A file that breaks the format (byte offset `at`).
    #[error("{file}: OpenFOAM: {message} (at byte {at})")]
    Invalid {
        file: String,
        at: usize,
        message: String,
    },

    /// A list longer than the bytes left in its file.
    #[error("{file}: OpenFOAM: {what} is longer than the file's {found} bytes")]
    Truncated {
        file: String,
        what: String,
        found: u64,
    },

    /// A folder or file the case needs is absent.
    #[error("{file}: OpenFOAM: no {what}")]
    Missing { file: String, what: String },

    #[error(transparent)]
    Memory(#[from] crate::preflight::MemoryError),

    /// A time step the case does not store, or a bad time.
    #[error("{file}: {message}")]
    Time { file: String, message: String },

    /// The cells could not be split into tetrahedra, or a value is not
    /// finite (the shared VTK assembly step).
    #[error(transparent)]
    Assemble(#[from] VtkError),
}

/// Options of [`read_openfoam`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OpenFoamOptions {
    /// The 0-based time step (time folder, by increasing time).
    pub time_step: Option<usize>,
    /// Read the time folder whose time is nearest this.
    pub time: Option<f64>,
    pub linearize: Linearize,
}

/// An OpenFOAM case read.
#[derive(Debug)]
pub struct OpenFoamRead {
    pub read: VtkRead,
    /// The times of the time folders, increasing.
    pub times: Vec<f64>,
    pub time_step: Option<usize>,
    /// Processor folders read (0 for a reconstructed case).
    pub processors: usize,
}

/// Whether `folder` is an OpenFOAM case (it has a mesh, reconstructed or
/// decomposed, or a `system/controlDict`).
pub(crate) fn is_case(folder: &Path) -> bool {
    folder.join("constant/polyMesh").is_dir()
        || folder.join("system/controlDict").is_file()
        || !processors(folder).is_empty()
}

/// Reads the case that `path` names (see the module's documentation).
///
/// # Errors
/// [`OpenFoamError`] naming the file or folder at fault.
pub fn read_openfoam(path: &Path, opts: &OpenFoamOptions) -> Result<OpenFoamRead, OpenFoamError> {
    let case = case_folder(path)?;
    let name = case.display().to_string();
    let decomposed = processors(&case);
    let roots = if case.join("constant/polyMesh").is_dir() {
        vec![case.clone()]
    } else if !decomposed.is_empty() {
        decomposed.clone()
    } else {
        return Err(OpenFoamError::Missing {
            file: name,
            what: "constant/polyMesh, and no processor* folders".into(),
        });
    };
    let folders = time_folders(&roots[0])?;
    let times: Vec<f64> = folders.iter().map(|(t, _)| *t).collect();
    let step = choose_step(&times, opts.time_step, opts.time).map_err(|e| OpenFoamError::Time {
        file: name.clone(),
        message: e.to_string(),
    })?;
    let folder = step.map(|s| folders[s].1.clone());
    let mut grids = Vec::with_capacity(roots.len());
    let mut warnings = Vec::new();
    for root in &roots {
        let moving = folder.as_ref().map(|f| root.join(f).join("polyMesh"));
        let mesh_folder = match moving {
            Some(m) if m.join("points").is_file() || m.join("points.gz").is_file() => m,
            _ => root.join("constant/polyMesh"),
        };
        let mut grid = mesh::read_poly_mesh(&mesh_folder)?;
        if let Some(f) = &folder {
            let ncells = grid.types.len();
            let time = root.join(f);
            if time.is_dir() {
                grid.cell_arrays = fields::read_fields(&time, ncells, &mut warnings)?;
            } else {
                return Err(OpenFoamError::Missing {
                    file: root.display().to_string(),
                    what: format!("time folder {f}"),
                });
            }
        }
        grids.push(grid);
    }
    let mut grid = crate::vtk::join_grids(grids, &name)?;
    warnings.dedup();
    grid.warnings.extend(warnings);
    if grid.types.is_empty() {
        return Err(VtkError::from(CellError::Invalid {
            file: name,
            section: "polyMesh".into(),
            message: "the mesh has no cells".into(),
        })
        .into());
    }
    let read = crate::vtk::assemble_grid(
        grid,
        &name,
        &ReadOptions {
            linearize: opts.linearize,
        },
    )?;
    Ok(OpenFoamRead {
        read,
        times,
        time_step: step,
        processors: if roots.len() > 1 || roots[0] != case {
            roots.len()
        } else {
            0
        },
    })
}

/// The case folder of `path`: the folder itself, the folder of a marker
/// file, two up from `system/controlDict`, else the nearest folder above
/// that is a case.
fn case_folder(path: &Path) -> Result<PathBuf, OpenFoamError> {
    if path.is_dir() {
        return Ok(path.to_path_buf());
    }
    let parent = path.parent().unwrap_or(Path::new("."));
    let parent = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    for folder in parent.ancestors().take(4) {
        if is_case(folder) {
            return Ok(folder.to_path_buf());
        }
    }
    Err(OpenFoamError::Missing {
        file: path.display().to_string(),
        what: "case around this file (a folder with constant/polyMesh, processor* or \
               system/controlDict)"
            .into(),
    })
}

/// The `processor<N>` folders of a case with a mesh, by N.
fn processors(case: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(case) else {
        return Vec::new();
    };
    let mut found: Vec<(usize, PathBuf)> = entries
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let n = name.strip_prefix("processor")?.parse().ok()?;
            let path = e.path();
            path.join("constant/polyMesh").is_dir().then_some((n, path))
        })
        .collect();
    found.sort();
    found.into_iter().map(|(_, p)| p).collect()
}

/// The time folders of a case (or processor folder): (time, folder
/// name), by increasing time.
fn time_folders(root: &Path) -> Result<Vec<(f64, String)>, OpenFoamError> {
    let entries = std::fs::read_dir(root).map_err(|source| OpenFoamError::Io {
        file: root.display().to_string(),
        source,
    })?;
    let mut out: Vec<(f64, String)> = entries
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let t: f64 = name.parse().ok()?;
            t.is_finite().then_some((t, name))
        })
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

/// A file's bytes, or those of its gzip-compressed twin `<name>.gz`.
pub(super) fn read_maybe_gz(path: &Path) -> Result<(PathBuf, Vec<u8>), OpenFoamError> {
    let io = |file: &Path, source| OpenFoamError::Io {
        file: file.display().to_string(),
        source,
    };
    let gz_name = format!("{}.gz", path.display());
    let gz = if path.extension().is_some_and(|e| e == "gz") {
        path.to_path_buf()
    } else {
        PathBuf::from(gz_name)
    };
    if path.is_file() && path.extension().is_none_or(|e| e != "gz") {
        return Ok((
            path.to_path_buf(),
            std::fs::read(path).map_err(|e| io(path, e))?,
        ));
    }
    if gz.is_file() {
        let file = std::fs::File::open(&gz).map_err(|e| io(&gz, e))?;
        let mut bytes = Vec::new();
        flate2::read::GzDecoder::new(file)
            .read_to_end(&mut bytes)
            .map_err(|e| io(&gz, e))?;
        return Ok((gz, bytes));
    }
    Err(OpenFoamError::Missing {
        file: path.parent().unwrap_or(path).display().to_string(),
        what: path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
    })
}
