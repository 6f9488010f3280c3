//! Rendering from a running simulation: a rank hands over its part of the
//! mesh as arrays (no file), on the simulation's own communicator, and
//! gets the composited image back on rank 0.

use std::time::Duration;

use glam::DVec3;
use mpi::traits::*;
use tetray_engine::{CameraOptions, Extent, FrameOptions, IntegratorChoice, Log, TfSource};
use tetray_integrate::{Method, TransferFunction};
use tetray_mesh::cells::{CellGrid, ReadOptions, assemble_at};
use tetray_mesh::{LoadedMesh, MeshRead, ScalarField, TetMesh, centring_origin, finish, prepare};
use tetray_raycast::RenderOptions;

use crate::DistributedError;
use crate::frame::{DistributedFrame, agree, render_setup};
use crate::layout::DEFAULT_TILE;
use crate::transport::reduce_bounds;

/// One rank's part of the mesh: points in the simulation's coordinates
/// (f64), tetrahedra by point index (any orientation: they are oriented
/// here), one scalar per point.
#[derive(Debug, Clone, Copy)]
pub struct RankMesh<'a> {
    pub points: &'a [[f64; 3]],
    pub tets: &'a [[u32; 4]],
    pub scalars: &'a [f32],
}

/// How to look at the whole mesh.
#[derive(Debug, Clone)]
pub struct InSituView {
    pub width: u32,
    pub height: u32,
    /// VTK's ResetCamera fit of the whole mesh's bounds, then these turns
    /// (degrees) about the view-up and up.
    pub azimuth: f32,
    pub elevation: f32,
    /// Full vertical view angle, degrees.
    pub view_angle: f32,
    pub method: Method,
    /// Default: a ramp over the whole field's range.
    pub transfer_function: Option<TransferFunction>,
    /// Default: ParaView's (whole bounds diagonal over the cube root of
    /// the whole tetrahedron count).
    pub unit_distance: Option<f32>,
    /// Worker threads per rank (default: rayon's pool).
    pub threads: Option<usize>,
}

impl Default for InSituView {
    fn default() -> Self {
        InSituView {
            width: 256,
            height: 256,
            azimuth: 30.0,
            elevation: 20.0,
            view_angle: 30.0,
            method: Method::Ppi,
            transfer_function: None,
            unit_distance: None,
            threads: None,
        }
    }
}

/// The field name the arrays' scalars get.
const FIELD: &str = "scalar";

/// Renders every rank's part as one mesh; `Some(frame)` on rank 0. A
/// collective call: every rank of `comm` calls it, a rank with no
/// tetrahedra with empty arrays.
pub fn render_in_situ<C: Communicator>(
    comm: &C,
    part: RankMesh<'_>,
    view: &InSituView,
) -> Result<Option<DistributedFrame>, DistributedError> {
    if part.scalars.len() != part.points.len() {
        return Err(DistributedError::ScalarCount {
            scalars: part.scalars.len(),
            points: part.points.len(),
        });
    }
    let local = tetray_mesh::bounds_f64(part.points.iter().map(|&p| DVec3::from_array(p)));
    let (lo, hi) = reduce_bounds(comm, local).ok_or(DistributedError::NoMesh)?;
    // The whole mesh's origin, so shared points round alike on every rank.
    let origin = centring_origin(lo, hi);
    let mesh = TetMesh {
        points: part
            .points
            .iter()
            .map(|&p| (DVec3::from_array(p) - origin).as_vec3())
            .collect(),
        tets: part.tets.to_vec(),
        fields: vec![ScalarField {
            name: FIELD.into(),
            values: part.scalars.to_vec(),
        }],
    };
    let loaded = if mesh.tets.is_empty() {
        None
    } else {
        Some(prepare(mesh)?)
    };
    render_loaded(comm, loaded, origin, FIELD, view)
}

/// One rank's part as VTK cells ([`CellGrid`]: f64 points, any cell type
/// the file readers take, point and cell arrays), rendering the point
/// field `field` (cell arrays are averaged to the points of the rank's
/// cells). Non-tetrahedral cells are split by comparing point numbers, so
/// a face two ranks share is split alike only if both number its points
/// in the same order (as the pieces of one file do, see
/// `tetray_io::vtk::read_piece_subset`); planar shared faces are exact
/// either way.
pub fn render_in_situ_cells<C: Communicator>(
    comm: &C,
    grid: CellGrid,
    field: &str,
    view: &InSituView,
) -> Result<Option<DistributedFrame>, DistributedError> {
    let local = tetray_mesh::bounds_f64(
        grid.points
            .chunks_exact(3)
            .map(|p| DVec3::new(p[0], p[1], p[2])),
    );
    let (lo, hi) = reduce_bounds(comm, local).ok_or(DistributedError::NoMesh)?;
    let origin = centring_origin(lo, hi);
    let loaded = if grid.types.is_empty() {
        None
    } else {
        let read = assemble_at(grid, "in situ", &ReadOptions::default(), origin)?;
        Some(finish(MeshRead {
            mesh: read.mesh,
            format: "memory",
            warnings: read.warnings,
            origin: read.origin,
            tet_cells: read.tet_cells,
            ..MeshRead::default()
        })?)
    };
    render_loaded(comm, loaded, origin, field, view)
}

/// The frame of this rank's loaded part (`None`: nothing), its points
/// relative to the whole mesh's origin `origin`.
fn render_loaded<C: Communicator>(
    comm: &C,
    loaded: Option<LoadedMesh>,
    origin: DVec3,
    field: &str,
    view: &InSituView,
) -> Result<Option<DistributedFrame>, DistributedError> {
    let cells = loaded.as_ref().map_or(0, LoadedMesh::input_cells);
    let agreed = agree(comm, loaded.as_ref().map(|l| &l.mesh), cells, Some(field))?;
    let summary = &agreed.summary;
    let extent = Extent {
        name: "in situ".into(),
        origin,
        bounds: summary.bounds,
        field: field.to_string(),
        range: agreed.range,
        paraview_unit_distance: summary.paraview_unit_distance(),
        mean_chord: summary.mean_chord(),
    };
    let options = view.frame_options();
    let setup =
        tetray_engine::prepare_part(loaded, extent, &options, Log::quiet(), Duration::ZERO)?;
    let opts = RenderOptions {
        width: view.width,
        height: view.height,
        threads: view.threads,
        ..RenderOptions::default()
    };
    render_setup(comm, &setup, &setup.camera, &opts, DEFAULT_TILE)
}

impl InSituView {
    /// The engine's options of this view: VTK's ResetCamera fit of the
    /// whole mesh's bounds turned by the azimuth and elevation, the
    /// method, the transfer function (default: the engine's over the whole
    /// field's range) and the unit distance (default: ParaView's, of the
    /// whole mesh).
    pub fn frame_options(&self) -> FrameOptions {
        let tf = match &self.transfer_function {
            Some(tf) => TfSource::Points {
                color: tf.color_points().to_vec(),
                opacity: tf.opacity_points().to_vec(),
            },
            None => TfSource::Default,
        };
        FrameOptions {
            integrator: IntegratorChoice {
                method: self.method,
                tf,
                unit_distance: self.unit_distance,
                ..IntegratorChoice::default()
            },
            camera: CameraOptions {
                view_angle: self.view_angle,
                azimuth: Some(self.azimuth),
                elevation: Some(self.elevation),
                ..CameraOptions::default()
            },
            size: (self.width, self.height),
            ..FrameOptions::default()
        }
    }
}
