//! Loading a mesh from a file, ready to render: the reader chosen by the
//! file's name (one module per format), then [`tetray_mesh::finish`]
//! (leave out the cells that cannot be walked, orient, validate, build the
//! topology). What was changed is in the [`tetray_mesh::LoadReport`].

use std::path::{Path, PathBuf};

use glam::DVec3;
use tetray_mesh::cells::{CellCounts, CellGrid};
use tetray_mesh::{LoadedMesh, MeshRead, finish};

use crate::cgns::{CgnsOptions, read_cgns};
use crate::ensight::{EnSightOptions, read_ensight};
use crate::exodus::{ExodusOptions, ExodusRead, read_exodus_file};
use crate::openfoam::{OpenFoamOptions, read_openfoam};
use crate::plot3d::{Plot3dRead, read_plot3d_bytes, read_plot3d_files};
use crate::probe::{Format, format_for};
use crate::series::{SeriesError, read_series};
use crate::time::choose_step;
use crate::vtkhdf::{VtkHdfOptions, VtkHdfRead, read_vtkhdf_file};
use crate::{IoError, vtk};

/// Options of [`load`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LoadOptions {
    /// The PLOT3D solution file; by default the grid file's sibling with
    /// `xyz` replaced by `q` (`postxyz.bin` -> `postq.bin`, `a.xyz` or
    /// `a.x` -> `a.q`), used when it exists.
    pub plot3d_q: Option<PathBuf>,
    /// Exodus II, VTKHDF, a file series: the 0-based time step to read
    /// (default: the first).
    pub time_step: Option<usize>,
    /// Exodus II, VTKHDF, a file series: read the time step whose stored
    /// time is nearest this (not together with `time_step`).
    pub time: Option<f64>,
    /// For a multi-block `.vtm`: keep only the block of this name (or
    /// path `outer/inner`, by the blocks' `name` attributes).
    pub block: Option<String>,
    /// Quadratic and Lagrange cells: subdivided through all their nodes
    /// (default) or reduced to their corners.
    pub linearize: vtk::Linearize,
}

/// The default solution file of a PLOT3D grid: the last `xyz` of the file
/// name (any case) replaced by `q`, or a final `.x` by `.q`.
pub fn plot3d_q_sibling(xyz: &Path) -> Option<PathBuf> {
    let name = xyz.file_name()?.to_string_lossy().into_owned();
    let lower = name.to_lowercase();
    let q_name = if let Some(at) = lower.rfind("xyz") {
        format!("{}q{}", &name[..at], &name[at + 3..])
    } else if lower.ends_with(".x") {
        format!("{}q", &name[..name.len() - 1])
    } else {
        return None;
    };
    Some(xyz.with_file_name(q_name))
}

/// Reads the mesh at `path` (the reader chosen by name, any case, or where
/// the name says nothing by the file's content, see [`crate::probe`]: `.vtk`
/// (any dataset type its DATASET line names), `.vtu`, `.vts`, `.vtr`,
/// `.vti`, their parallel forms `.pvt*`, multi-block `.vtm`, an Exodus II
/// file `.e`, `.exo`, `.ex2`, `.exii`, `.g`, `.gen`, `.e-s*`, VTKHDF
/// `.vtkhdf` (and `.hdf`, `.hdf5`, `.h5` holding a `/VTKHDF` group), a
/// PLOT3D grid `*xyz.bin`, `*.xyz`, `*.x`, an OpenFOAM case (its folder,
/// `system/controlDict` or a `.foam` marker), EnSight Gold `.case`, CGNS
/// `.cgns` (HDF5 or ADF storage), or a
/// time series of any of them,
/// `*.series` or `.pvd`), then orients, validates and builds the topology
/// (see [`tetray_mesh::prepare`]).
///
/// # Errors
/// [`IoError::UnknownFormat`] for a file neither its name nor its content
/// says the format of, the reader's
/// errors, and validation errors wrapped in [`tetray_mesh::MeshError::InFile`].
pub fn load(path: &Path, opts: &LoadOptions) -> Result<LoadedMesh, IoError> {
    let file = path.display().to_string();
    Ok(finish(read_file(path, opts)?).map_err(|e| e.in_file(&file))?)
}

/// The reader's output for the file at `path`, chosen as [`load`] says.
pub fn read_file(path: &Path, opts: &LoadOptions) -> Result<MeshRead, IoError> {
    let (format, _, _) = format_for(path)?;
    let vtk_opts = vtk::ReadOptions {
        linearize: opts.linearize,
    };
    let read = match format {
        Format::Legacy => {
            let read = vtk::read_legacy_file_with(path, &vtk_opts)?;
            let format = match read.dataset {
                "StructuredGrid" => "VTK legacy STRUCTURED_GRID",
                "RectilinearGrid" => "VTK legacy RECTILINEAR_GRID",
                "ImageData" => "VTK legacy STRUCTURED_POINTS",
                _ => "VTK legacy",
            };
            from_vtk(read, format)
        }
        Format::Xml => {
            let read = vtk::read_vtu_file_with(path, &vtk_opts)?;
            let format = match read.dataset {
                "StructuredGrid" => "VTK XML StructuredGrid",
                "RectilinearGrid" => "VTK XML RectilinearGrid",
                "ImageData" => "VTK XML ImageData",
                _ => "VTK XML",
            };
            from_vtk(read, format)
        }
        Format::Parallel => from_vtk(
            vtk::read_parallel_file_with(path, &vtk_opts)?,
            "VTK parallel XML",
        ),
        Format::MultiBlock => from_vtk(
            vtk::read_multiblock_file_with(path, opts.block.as_deref(), &vtk_opts)?,
            "VTK multi-block",
        ),
        Format::Exodus => {
            let exodus = ExodusOptions {
                time_step: opts.time_step,
                time: opts.time,
                linearize: opts.linearize,
            };
            from_exodus(read_exodus_file(path, &exodus)?)
        }
        Format::VtkHdf | Format::Hdf5 => {
            from_vtkhdf(read_vtkhdf_file(path, &vtkhdf_options(opts))?)
        }
        Format::Plot3d => {
            let mut warnings = Vec::new();
            let q = match &opts.plot3d_q {
                Some(q) => Some(q.clone()),
                None => match plot3d_q_sibling(path) {
                    Some(q) if q.is_file() => Some(q),
                    other => {
                        let looked = other
                            .map_or_else(String::new, |q| format!(" ({} not found)", q.display()));
                        warnings.push(format!(
                            "no PLOT3D solution file{looked}: the mesh has no scalar fields"
                        ));
                        None
                    }
                },
            };
            let mut read = from_plot3d(read_plot3d_files(path, q.as_deref())?);
            warnings.append(&mut read.warnings);
            read.warnings = warnings;
            read
        }
        Format::Series => read_series_step(path, opts)?,
        Format::Cgns => {
            let cgns = CgnsOptions {
                linearize: opts.linearize,
                time_step: opts.time_step,
                time: opts.time,
            };
            let read = read_cgns(path, &cgns)?;
            MeshRead {
                times: read.times,
                time_step: read.time_step,
                ..from_vtk(read.read, "CGNS")
            }
        }
        Format::EnSight => {
            let opts = EnSightOptions {
                time_step: opts.time_step,
                time: opts.time,
                linearize: opts.linearize,
            };
            let read = read_ensight(path, &opts)?;
            MeshRead {
                times: read.times,
                time_step: read.time_step,
                ..from_vtk(read.read, "EnSight Gold")
            }
        }
        Format::OpenFoam => {
            let foam = OpenFoamOptions {
                time_step: opts.time_step,
                time: opts.time,
                linearize: opts.linearize,
            };
            let read = read_openfoam(path, &foam)?;
            MeshRead {
                times: read.times,
                time_step: read.time_step,
                ..from_vtk(read.read, "OpenFOAM")
            }
        }
    };
    if read.times.is_empty() && (opts.time_step.is_some() || opts.time.is_some()) {
        // Asked of a file without time steps: the same error as for any.
        choose_step(&[], opts.time_step, opts.time).map_err(|e| IoError::Time {
            file: path.display().to_string(),
            message: e.to_string(),
        })?;
    }
    Ok(read)
}

/// The step of a series (`.series`, `.pvd`) chosen by `--time-step` or
/// `--time`, read by its own file's reader (the parts of a collection's
/// step welded like the blocks of a `.vtm`), with the series' times.
fn read_series_step(path: &Path, opts: &LoadOptions) -> Result<MeshRead, IoError> {
    let file = path.display().to_string();
    let steps = read_series(path)?;
    let times: Vec<f64> = steps.iter().map(|s| s.time).collect();
    let fail = |message: String| SeriesError {
        file: file.clone(),
        message,
    };
    let step = choose_step(&times, opts.time_step, opts.time)
        .map_err(|e| fail(e.to_string()))?
        .unwrap_or(0);
    let files = &steps[step].files;
    // A step's file is read whole: its own steps, if any, are not the
    // series'.
    let inner = LoadOptions {
        time_step: None,
        time: None,
        ..opts.clone()
    };
    let mut read = match files.as_slice() {
        [one] => {
            if format_for(one)?.0 == Format::Series {
                return Err(fail(format!(
                    "step {step} names {}, itself a series",
                    one.display()
                ))
                .into());
            }
            read_file(one, &inner)?
        }
        parts => from_vtk(
            vtk::read_parts(
                parts,
                &file,
                &vtk::ReadOptions {
                    linearize: opts.linearize,
                },
            )?,
            "VTK multi-block",
        ),
    };
    read.times = times;
    read.time_step = Some(step);
    Ok(read)
}

/// Some pieces of a parallel file ([`vtk::read_piece_subset`]) ready to
/// render, like [`load`] does the whole file, with the points relative to
/// `origin` (the whole mesh's, so every process rounds shared points
/// alike).
///
/// # Errors
/// As [`load`].
pub fn load_piece_subset(
    subset: vtk::PieceSubset,
    origin: DVec3,
    opts: &LoadOptions,
) -> Result<LoadedMesh, IoError> {
    let name = subset.name().to_string();
    let vtk_opts = vtk::ReadOptions {
        linearize: opts.linearize,
    };
    let read = from_vtk(subset.assemble(origin, &vtk_opts)?, "VTK parallel XML");
    Ok(finish(read).map_err(|e| e.in_file(&name))?)
}

/// Loads a PLOT3D grid and optional solution held in memory (`name` is
/// used in messages), like [`load`] does a file.
///
/// # Errors
/// As [`crate::read_plot3d_bytes`], and validation errors wrapped in
/// [`tetray_mesh::MeshError::InFile`].
pub fn load_plot3d_bytes(xyz: &[u8], q: Option<&[u8]>, name: &str) -> Result<LoadedMesh, IoError> {
    Ok(finish(from_plot3d(read_plot3d_bytes(xyz, q, name)?)).map_err(|e| e.in_file(name))?)
}

/// Loads a raw grid built in memory (by a caller that holds the arrays of
/// a dataset, such as the Python bindings) exactly as [`load`] loads the
/// same dataset from a serial VTK XML file: ghost and global-id arrays
/// handled, a structured grid without volume cells refused, cells split,
/// then [`tetray_mesh::finish`]. `name` is used in messages and `format`
/// in the report.
///
/// # Errors
/// As [`load`] for a `.vtu` (bad indices, NaN points, unsupported cells...).
pub fn load_grid(
    grid: CellGrid,
    name: &str,
    format: &'static str,
    opts: &LoadOptions,
) -> Result<LoadedMesh, IoError> {
    let vtk_opts = vtk::ReadOptions {
        linearize: opts.linearize,
    };
    let read = vtk::assemble_grid(grid, name, &vtk_opts)?;
    Ok(finish(from_vtk(read, format)).map_err(|e| e.in_file(name))?)
}

fn from_vtk(read: vtk::VtkRead, format: &'static str) -> MeshRead {
    let c = read.cells;
    MeshRead {
        mesh: read.mesh,
        format,
        warnings: read.warnings,
        cells_split: cells_split(&c),
        tets_from_split: c.tets_from_split,
        points_added: c.points_added,
        subdivided: c.subdivided,
        pieces: read.pieces,
        origin: read.origin,
        tet_cells: read.tet_cells,
        ..MeshRead::default()
    }
}

/// The cells split or subdivided into tetrahedra: every volume cell but
/// the linear tetrahedra.
fn cells_split(c: &CellCounts) -> usize {
    c.hexahedra
        + c.wedges
        + c.pyramids
        + c.voxels
        + c.subdivided.iter().map(|s| s.cells).sum::<usize>()
}

fn vtkhdf_options(opts: &LoadOptions) -> VtkHdfOptions {
    VtkHdfOptions {
        time_step: opts.time_step,
        time: opts.time,
        linearize: opts.linearize,
    }
}

fn from_vtkhdf(read: VtkHdfRead) -> MeshRead {
    MeshRead {
        times: read.times,
        time_step: read.time_step,
        ..from_vtk(read.read, "VTKHDF")
    }
}

fn from_exodus(read: ExodusRead) -> MeshRead {
    let c = read.cells;
    MeshRead {
        mesh: read.mesh,
        format: "Exodus II",
        warnings: read.warnings,
        cells_split: cells_split(&c),
        tets_from_split: c.tets_from_split,
        points_added: c.points_added,
        subdivided: c.subdivided,
        times: read.times,
        time_step: read.time_step,
        blocks: read.blocks,
        origin: read.origin,
        tet_cells: read.tet_cells,
        ..MeshRead::default()
    }
}

/// PLOT3D grids are read in f32 (most are single precision); they are
/// centred like the others, the subtraction done in f64.
fn from_plot3d(read: Plot3dRead) -> MeshRead {
    let hexahedra = read.hexahedra - read.blanked_hexahedra;
    let mut mesh = read.mesh;
    let origin = tetray_mesh::bounds_f64(mesh.points.iter().map(|p| p.as_dvec3()))
        .map_or(DVec3::ZERO, |(lo, hi)| tetray_mesh::centring_origin(lo, hi));
    if origin != DVec3::ZERO {
        for p in &mut mesh.points {
            *p = (p.as_dvec3() - origin).as_vec3();
        }
    }
    MeshRead {
        tets_from_split: mesh.tets.len(),
        mesh,
        origin,
        tet_cells: Vec::new(),
        format: "PLOT3D",
        warnings: read.warnings,
        degenerate_dropped: read.degenerate_dropped,
        inverted_fixed: read.reoriented,
        cells_split: hexahedra,
        ..MeshRead::default()
    }
}

/// Reads the regular grid alone of an image-data file (`.vti`, legacy
/// STRUCTURED_POINTS, VTKHDF ImageData, the chosen step of a temporal
/// one): no cells, no topology (shear-warp renders it).
///
/// # Errors
/// As [`load_image_data`].
pub fn load_image_grid(path: &Path, opts: &LoadOptions) -> Result<vtk::ImageGrid, IoError> {
    if format_for(path)?.0 == Format::VtkHdf {
        let read = read_vtkhdf_file(path, &vtkhdf_options(opts))?;
        return read.image.ok_or_else(|| not_vtkhdf_image(path));
    }
    if opts.time_step.is_some() || opts.time.is_some() {
        choose_step(&[], opts.time_step, opts.time).map_err(|e| IoError::Time {
            file: path.display().to_string(),
            message: e.to_string(),
        })?;
    }
    Ok(vtk::read_image_grid(path)?)
}

/// Reads an image-data file (`.vti`, legacy STRUCTURED_POINTS) once as
/// both what it is: the mesh [`load`] makes of it, and its regular grid.
///
/// # Errors
/// As [`load`], and a [`vtk::VtkError::Cell`] error for a file that is not a
/// single-piece axis-aligned image.
pub fn load_image_data(
    path: &Path,
    opts: &LoadOptions,
) -> Result<(LoadedMesh, vtk::ImageGrid), IoError> {
    let file = path.display().to_string();
    let vtk_opts = vtk::ReadOptions {
        linearize: opts.linearize,
    };
    let format = format_for(path)?.0;
    if format == Format::VtkHdf {
        let mut read = read_vtkhdf_file(path, &vtkhdf_options(opts))?;
        let image = read.image.take().ok_or_else(|| not_vtkhdf_image(path))?;
        let mesh = finish(from_vtkhdf(read)).map_err(|e| e.in_file(&file))?;
        return Ok((mesh, image));
    }
    let (read, image) = vtk::read_image_data_with(path, &vtk_opts)?;
    let format = if read.dataset == "ImageData" && format == Format::Xml {
        "VTK XML ImageData"
    } else {
        "VTK legacy STRUCTURED_POINTS"
    };
    let mesh = finish(from_vtk(read, format)).map_err(|e| e.in_file(&file))?;
    Ok((mesh, image))
}

fn not_vtkhdf_image(path: &Path) -> IoError {
    vtk::VtkError::from(tetray_mesh::cells::CellError::Invalid {
        file: path.display().to_string(),
        section: "VTKHDF".into(),
        message: "a regular grid needs VTKHDF ImageData, not UnstructuredGrid".into(),
    })
    .into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_siblings() {
        let p = Path::new;
        assert_eq!(
            plot3d_q_sibling(p("d/postxyz.bin")),
            Some(PathBuf::from("d/postq.bin"))
        );
        assert_eq!(
            plot3d_q_sibling(p("d/Wing.XYZ")),
            Some(PathBuf::from("d/Wing.q"))
        );
        assert_eq!(plot3d_q_sibling(p("grid.x")), Some(PathBuf::from("grid.q")));
    }
}
