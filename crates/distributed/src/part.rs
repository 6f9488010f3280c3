//! A rank's part of a mesh, made ready through the engine: each rank loads
//! its part (a run of a parallel file's pieces, or a spatial slab of any
//! other mesh), the ranks agree on what the whole mesh gives a single
//! process (origin, bounds, field and range, unit distance, mean chord),
//! and the engine makes the rank's setup from that whole-mesh extent, so a
//! distributed frame and a single-process frame of the same options agree.

use std::path::Path;
use std::time::{Duration, Instant};

use glam::DVec3;
use mpi::traits::*;
use tetray_engine::{Extent, FrameOptions, Log, SOLID, Setup, Source};
use tetray_io::vtk::{parallel_piece_count, read_piece_subset};
use tetray_mesh::{LoadedMesh, Topology, centring_origin};

use crate::DistributedError;
use crate::frame::agree;
use crate::partition::{pieces_for_rank, spatial_split};
use crate::transport::reduce_bounds;

/// This rank's setup and what making it took.
pub struct Part {
    pub setup: Setup,
    /// Tetrahedra of the whole mesh.
    pub tets_total: u64,
    pub load_time: Duration,
    /// Agreeing, the part's scene, the camera and the integrator.
    pub setup_time: Duration,
}

/// Loads this rank's part of `source` and makes its setup from what the
/// ranks agree on. A collective call: every rank of `comm` calls it.
pub fn prepare_part<C: Communicator>(
    comm: &C,
    source: Source,
    options: &FrameOptions,
    log: Log<'_>,
) -> Result<Part, DistributedError> {
    let start = Instant::now();
    let (name, loaded, cells, origin) = load_part(comm, source)?;
    let load_time = start.elapsed();
    let start = Instant::now();
    let scalar = options.integrator.scalar.as_deref();
    let agreed = agree(comm, loaded.as_ref().map(|l| &l.mesh), cells, scalar)?;
    let summary = &agreed.summary;
    (log.info)(format!(
        "loaded {name} over {} ranks: {} tetrahedra in all, this rank {} ({:.3} s)",
        comm.size(),
        summary.tets,
        loaded.as_ref().map_or(0, |l| l.mesh.tets.len()),
        load_time.as_secs_f64()
    ));
    let field = agreed.field.clone().unwrap_or_else(|| {
        (log.warn)(format!(
            "{name} has no point scalar field: rendering a uniform volume"
        ));
        SOLID.to_string()
    });
    let extent = Extent {
        name,
        origin,
        bounds: summary.bounds,
        field,
        range: agreed.range,
        paraview_unit_distance: summary.paraview_unit_distance(),
        mean_chord: summary.mean_chord(),
    };
    let setup = tetray_engine::prepare_part(loaded, extent, options, log, load_time)?;
    Ok(Part {
        setup,
        tets_total: summary.tets,
        load_time,
        setup_time: start.elapsed(),
    })
}

/// Loads this rank's part: pieces [`pieces_for_rank`] of a parallel file
/// (with the whole mesh's origin), or a spatial slab of any other mesh
/// (loaded whole on every rank). Returns the data's name, the part (`None`:
/// nothing for this rank), its share of the input cells and the origin.
fn load_part<C: Communicator>(
    comm: &C,
    source: Source,
) -> Result<(String, Option<LoadedMesh>, usize, DVec3), DistributedError> {
    let (rank, size) = (comm.rank() as usize, comm.size() as usize);
    if let Source::File { path, options } = &source
        && is_parallel(path)
    {
        let name = path.display().to_string();
        if !path.is_file() {
            return Err(tetray_engine::EngineError::NoSuchFile(name).into());
        }
        let pieces = parallel_piece_count(path).map_err(tetray_io::IoError::from)?;
        let mine = pieces_for_rank(pieces, rank, size);
        let subset = if mine.is_empty() {
            None
        } else {
            Some(read_piece_subset(path, mine).map_err(tetray_io::IoError::from)?)
        };
        let bounds = reduce_bounds(comm, subset.as_ref().and_then(|s| s.bounds()))
            .ok_or(DistributedError::NoMesh)?;
        let origin = centring_origin(bounds.0, bounds.1);
        let loaded = match subset {
            Some(s) => Some(tetray_io::load_piece_subset(s, origin, options)?),
            None => None,
        };
        let cells = loaded.as_ref().map_or(0, LoadedMesh::input_cells);
        return Ok((name, loaded, cells, origin));
    }
    let input = tetray_engine::load(source)?;
    let whole = &input.loaded;
    let mesh = spatial_split(&whole.mesh, rank, size);
    // The whole mesh's cell count, counted once (for the unit distance).
    let cells = if rank == 0 { input.input_cells() } else { 0 };
    let origin = whole.origin();
    let loaded = if mesh.tets.is_empty() {
        None
    } else {
        let topology = Topology::build(&mesh)?;
        Some(LoadedMesh {
            mesh,
            topology,
            report: whole.report.clone(),
            overlaps: Vec::new(),
        })
    };
    Ok((input.name, loaded, cells, origin))
}

fn is_parallel(path: &Path) -> bool {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("pvtu" | "pvts" | "pvtr" | "pvti"))
}
