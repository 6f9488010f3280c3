//! Which mesh a frame is made of, and loading it: a file (every format
//! `tetray_io::load` reads), the embedded Blunt Fin, or a raw grid built in
//! memory, which goes through the same assembly as a `.vtu`
//! ([`tetray_io::load_grid`]).

use std::path::PathBuf;
use std::time::{Duration, Instant};

use tetray_mesh::cells::CellGrid;
use tetray_mesh::LoadedMesh;

use crate::error::{bail, FrameError};

/// The embedded default dataset: NASA's Blunt Fin, PLOT3D big-endian.
const BLUNT_FIN_XYZ: &[u8] = include_bytes!("../../../data/plot3d/bluntfinxyz.bin");
const BLUNT_FIN_Q: &[u8] = include_bytes!("../../../data/plot3d/bluntfinq.bin");
pub const EMBEDDED_NAME: &str = "embedded Blunt Fin";

/// Which mesh to load (the CLI's `MeshArgs`). No path means the embedded
/// Blunt Fin dataset.
#[derive(Debug, Clone, Default)]
pub struct MeshOptions {
    pub mesh: Option<PathBuf>,
    /// PLOT3D solution file.
    pub q: Option<PathBuf>,
    /// Exodus II time step, from 0.
    pub time_step: Option<usize>,
    /// Exodus II: the time step nearest this time.
    pub time: Option<f64>,
    /// Multi-block `.vtm`: keep only this block.
    pub block: Option<String>,
    pub linearize: tetray_io::vtk::Linearize,
}

/// A mesh as loaded, with what it took.
pub struct MeshInput {
    /// The file name, [`EMBEDDED_NAME`], or the name an in-memory grid was
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

/// Loads the mesh the options name, or the embedded default.
pub fn load_mesh(args: &MeshOptions) -> Result<MeshInput, FrameError> {
    let start = Instant::now();
    let (name, loaded) = match &args.mesh {
        None => {
            if args.q.is_some() {
                bail!("--q needs a PLOT3D grid file (the embedded dataset has its own)");
            }
            if args.time_step.is_some() || args.time.is_some() {
                bail!("--time-step and --time need an Exodus II file");
            }
            let loaded =
                tetray_io::load_plot3d_bytes(BLUNT_FIN_XYZ, Some(BLUNT_FIN_Q), EMBEDDED_NAME)?;
            (EMBEDDED_NAME.to_string(), loaded)
        }
        Some(path) => {
            if !path.is_file() {
                return Err(FrameError::NoSuchFile(path.display().to_string()));
            }
            if let Some(q) = args.q.as_deref().filter(|q| !q.is_file()) {
                return Err(FrameError::NoSuchFile(format!("--q {}", q.display())));
            }
            let options = tetray_io::LoadOptions {
                plot3d_q: args.q.clone(),
                time_step: args.time_step,
                time: args.time,
                block: args.block.clone(),
                linearize: args.linearize,
            };
            let loaded = tetray_io::load(path, &options)?;
            let timed = args.time_step.is_some() || args.time.is_some();
            if timed && loaded.report.format != "Exodus II" {
                bail!(
                    "{}: --time-step and --time apply to Exodus II files, this is {}",
                    path.display(),
                    loaded.report.format
                );
            }
            (path.display().to_string(), loaded)
        }
    };
    Ok(MeshInput {
        name,
        loaded,
        load_time: start.elapsed(),
    })
}

/// Loads a raw grid built in memory (points, VTK cells, point and cell
/// arrays) through the same assembly and checks as a `.vtu` file holding
/// it; `name` is used in messages, `format` in the report.
pub fn load_grid(
    grid: CellGrid,
    name: &str,
    format: &'static str,
    linearize: tetray_io::vtk::Linearize,
) -> Result<MeshInput, FrameError> {
    let start = Instant::now();
    let options = tetray_io::LoadOptions {
        linearize,
        ..tetray_io::LoadOptions::default()
    };
    let loaded = tetray_io::load_grid(grid, name, format, &options)?;
    Ok(MeshInput {
        name: name.to_string(),
        loaded,
        load_time: start.elapsed(),
    })
}

pub fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
