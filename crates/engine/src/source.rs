//! Where a frame's data comes from, and loading it: a file (every format
//! `tetray_io` reads, recognised by name or content), the embedded Blunt
//! Fin, cells held in memory (assembled as a `.vtu` holding them would be),
//! or a tetrahedral mesh already made (a process's part of a distributed
//! mesh, a synthetic mesh).

use std::path::PathBuf;
use std::time::{Duration, Instant};

use tetray_io::{DataKind, ImageGrid, LoadOptions};
use tetray_mesh::LoadedMesh;
use tetray_mesh::cells::CellGrid;

use crate::error::EngineError;

/// The embedded default dataset: NASA's Blunt Fin, PLOT3D big-endian.
const BLUNT_FIN_XYZ: &[u8] = include_bytes!("../../../data/plot3d/bluntfinxyz.bin");
const BLUNT_FIN_Q: &[u8] = include_bytes!("../../../data/plot3d/bluntfinq.bin");
pub const EMBEDDED_NAME: &str = "embedded Blunt Fin";

/// The data of a frame.
#[derive(Debug, Clone)]
pub enum Source {
    /// The embedded Blunt Fin (density, momentum, energy...).
    Embedded,
    /// A file; `options` choose the PLOT3D solution, the time step, the
    /// block of a multi-block file and how higher-order cells are split.
    File { path: PathBuf, options: LoadOptions },
    /// Cells held in memory, assembled and checked as the same cells read
    /// from a `.vtu` file; `name` is used in messages, `format` in the
    /// load report.
    Arrays {
        grid: Box<CellGrid>,
        name: String,
        format: &'static str,
        linearize: tetray_io::vtk::Linearize,
    },
    /// A tetrahedral mesh already loaded (topology built, points relative
    /// to its origin).
    Mesh { mesh: Box<LoadedMesh>, name: String },
}

impl Source {
    /// A file with default options.
    pub fn file(path: impl Into<PathBuf>) -> Source {
        Source::File {
            path: path.into(),
            options: LoadOptions::default(),
        }
    }

    /// The name used in messages.
    pub fn name(&self) -> String {
        match self {
            Source::Embedded => EMBEDDED_NAME.to_string(),
            Source::File { path, .. } => path.display().to_string(),
            Source::Arrays { name, .. } | Source::Mesh { name, .. } => name.clone(),
        }
    }

    /// Whether the data is image data (`.vti`, legacy STRUCTURED_POINTS),
    /// which shear-warp can render as its regular grid.
    pub fn is_image_data(&self) -> Result<bool, EngineError> {
        match self {
            Source::File { path, .. } => {
                check_file(path)?;
                Ok(tetray_io::probe(path)?.kind == DataKind::ImageData)
            }
            _ => Ok(false),
        }
    }
}

/// A mesh as loaded, with what it took.
pub struct MeshInput {
    /// The file name, [`EMBEDDED_NAME`], or the name in-memory data was
    /// given.
    pub name: String,
    pub loaded: LoadedMesh,
    pub load_time: Duration,
}

impl MeshInput {
    /// Cells of the dataset as read (see [`LoadedMesh::input_cells`]).
    pub fn input_cells(&self) -> usize {
        self.loaded.input_cells()
    }

    /// ParaView's default opacity unit distance (see
    /// [`LoadedMesh::paraview_unit_distance`]).
    pub fn paraview_unit_distance(&self) -> f32 {
        self.loaded.paraview_unit_distance()
    }

    /// One line: what was loaded.
    pub fn describe(&self) -> String {
        let (mesh, report) = (&self.loaded.mesh, &self.loaded.report);
        let split = if report.cells_split > 0 {
            let per_type: Vec<String> = report
                .subdivided
                .iter()
                .map(|s| format!("{} {} (type {})", s.cells, s.name, s.type_id))
                .collect();
            let detail = if per_type.is_empty() {
                String::new()
            } else {
                format!(
                    ", among them {}; {} points added",
                    per_type.join(", "),
                    report.points_added
                )
            };
            format!(
                " ({} cells split into {}{detail})",
                report.cells_split, report.tets_from_split
            )
        } else {
            String::new()
        };
        let p = &report.pieces;
        let pieces = if p.pieces > 0 {
            format!(
                " from {} pieces ({} points welded, {} ghost cells dropped)",
                p.pieces, p.welded_points, p.ghost_cells_dropped
            )
        } else {
            String::new()
        };
        format!(
            "loaded {} ({}{pieces}): {} points, {} tetrahedra{split}, {} boundary faces, {} component{} in {:.3} s",
            self.name,
            report.format,
            mesh.points.len(),
            mesh.tets.len(),
            self.loaded.topology.boundary_faces.len(),
            report.validation.components,
            plural(report.validation.components),
            self.load_time.as_secs_f64()
        )
    }
}

/// Loads the tetrahedra of `source`.
pub fn load(source: Source) -> Result<MeshInput, EngineError> {
    let start = Instant::now();
    let name = source.name();
    let loaded = match source {
        Source::Embedded => {
            tetray_io::load_plot3d_bytes(BLUNT_FIN_XYZ, Some(BLUNT_FIN_Q), EMBEDDED_NAME)?
        }
        Source::File { path, options } => {
            check_file(&path)?;
            if let Some(q) = options.plot3d_q.as_deref().filter(|q| !q.is_file()) {
                return Err(EngineError::NoSuchFile(format!(
                    "PLOT3D solution {}",
                    q.display()
                )));
            }
            tetray_io::load(&path, &options)?
        }
        Source::Arrays {
            grid,
            name,
            format,
            linearize,
        } => {
            let options = LoadOptions {
                linearize,
                ..LoadOptions::default()
            };
            tetray_io::load_grid(*grid, &name, format, &options)?
        }
        Source::Mesh { mesh, .. } => *mesh,
    };
    Ok(MeshInput {
        name,
        loaded,
        load_time: start.elapsed(),
    })
}

/// Loads an image-data file once as both its tetrahedra and its regular
/// grid.
pub(crate) fn load_image_data(
    path: &std::path::Path,
    options: &LoadOptions,
) -> Result<(MeshInput, ImageGrid), EngineError> {
    let start = Instant::now();
    let name = path.display().to_string();
    let (loaded, image) = tetray_io::load_image_data(path, options)?;
    let input = MeshInput {
        name,
        loaded,
        load_time: start.elapsed(),
    };
    Ok((input, image))
}

pub(crate) fn check_file(path: &std::path::Path) -> Result<(), EngineError> {
    // A folder may be an OpenFOAM case: the reader says.
    if path.is_file() || path.is_dir() {
        Ok(())
    } else {
        Err(EngineError::NoSuchFile(path.display().to_string()))
    }
}

pub fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}
