//! One distributed frame: the ranks agree on what the whole mesh looks
//! like (field, ranges, bounds), each casts its rays through its own part
//! into fragments, and the fragments are composited (`transport`).

use std::time::Instant;

use mpi::traits::*;
use tetray_core::{Camera, Image};
use tetray_engine::Setup;
use tetray_integrate::ScalarIntegrator;
use tetray_mesh::TetMesh;
use tetray_raycast::{RenderOptions, render_scalar_fragments};
use tetray_scene::Scene;

use crate::DistributedError;
use crate::layout::TileLayout;
use crate::report::{FrameReport, Row};
use crate::summary::MeshSummary;
use crate::transport::{all_agree, broadcast_names, composite, gather_rows, reduce_summary};

/// What every rank agreed on about the whole mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Agreed {
    /// The whole mesh's summary (bounds, cells, chords, ranges of the
    /// fields every rank has).
    pub summary: MeshSummary,
    /// The field to render; `None` when the mesh has no field every rank
    /// holds (render a uniform volume).
    pub field: Option<String>,
    /// The field's range over the whole mesh (`(0, 0)` without a field).
    pub range: (f32, f32),
}

/// Agrees with the other ranks on the field to render and the whole
/// mesh's summary. `mesh` is this rank's part (`None` or empty: a rank
/// with nothing to render, which vetoes no field); `requested` the field
/// asked for, else the first that varies over the whole mesh, else the
/// first (as `tetray_mesh::default_field` on the whole mesh).
pub fn agree<C: Communicator>(
    comm: &C,
    mesh: Option<&TetMesh>,
    input_cells: usize,
    requested: Option<&str>,
) -> Result<Agreed, DistributedError> {
    let empty = TetMesh::default();
    let mesh = mesh.unwrap_or(&empty);
    let local_names: Vec<String> = mesh.fields.iter().map(|f| f.name.clone()).collect();
    // The names of the first rank that has a part (an empty rank has none).
    let names = broadcast_names(comm, &local_names, !mesh.tets.is_empty());
    let has: Vec<bool> = names
        .iter()
        .map(|n| mesh.tets.is_empty() || mesh.field(n).is_some())
        .collect();
    let everywhere = all_agree(comm, &has);
    let names: Vec<String> = names
        .into_iter()
        .zip(everywhere)
        .filter_map(|(n, ok)| ok.then_some(n))
        .collect();
    let summary = reduce_summary(comm, &MeshSummary::of(mesh, input_cells, &names));
    let index = match requested {
        Some(name) => Some(names.iter().position(|n| n == name).ok_or_else(|| {
            DistributedError::UnknownField {
                name: name.to_string(),
                available: names.join(", "),
            }
        })?),
        None => summary.default_field(),
    };
    Ok(Agreed {
        field: index.map(|i| names[i].clone()),
        range: index.map_or((0.0, 0.0), |i| summary.field_ranges[i]),
        summary,
    })
}

/// A distributed frame on rank 0.
#[derive(Debug, Clone)]
pub struct DistributedFrame {
    /// Premultiplied RGBA, as the single-process renderer writes it.
    pub image: Image,
    pub report: FrameReport,
}

/// Renders one frame: this rank's `scene` (`None`: nothing to render, it
/// still takes part in the exchange) into fragments, composited over all
/// ranks of `comm` in tiles of `tile` pixels. `Some(frame)` on rank 0.
/// Every rank must call it with the same camera, integrator and options.
/// One frame of a rank's setup (made by [`crate::prepare_part`] or the in-situ
/// entry points) from `camera`: [`render_distributed`] of its part.
pub fn render_setup<C: Communicator>(
    comm: &C,
    setup: &Setup,
    camera: &Camera,
    opts: &RenderOptions,
    tile: u32,
) -> Result<Option<DistributedFrame>, DistributedError> {
    let scene = setup.scene_arc().map(|s| &**s);
    render_distributed(comm, scene, camera, &setup.integrator, opts, tile)
}

pub fn render_distributed<C: Communicator>(
    comm: &C,
    scene: Option<&Scene>,
    camera: &Camera,
    integrator: &ScalarIntegrator,
    opts: &RenderOptions,
    tile: u32,
) -> Result<Option<DistributedFrame>, DistributedError> {
    let layout = TileLayout::new(opts.width, opts.height, tile, comm.size() as usize)?;
    let start = Instant::now();
    let (fragments, segments) = match scene {
        Some(scene) => {
            let out = render_scalar_fragments(scene, camera, integrator, opts)?;
            (out.fragments, out.stats.counters.segments)
        }
        None => (Vec::new(), 0),
    };
    let trace_s = start.elapsed().as_secs_f64();
    let (image, cost) = composite(comm, &fragments, &layout)?;
    let row = Row {
        trace_s,
        fragments_sent: cost.fragments_sent as f64,
        fragments_received: cost.fragments_received as f64,
        bytes_exchanged: cost.bytes_exchanged as f64,
        bytes_gathered: cost.bytes_gathered as f64,
        wait_s: cost.wait.as_secs_f64(),
        exchange_s: cost.exchange.as_secs_f64(),
        sort_s: cost.sort.as_secs_f64(),
        blend_s: cost.blend.as_secs_f64(),
        gather_s: cost.gather.as_secs_f64(),
        segments: segments as f64,
        tets: scene.map_or(0.0, |s| s.tet_count() as f64),
    };
    let rows = gather_rows(comm, &row.to_vec());
    Ok(match (image, rows) {
        (Some(image), Some(rows)) => Some(DistributedFrame {
            image,
            report: FrameReport {
                ranks: layout.ranks,
                pixels: layout.pixels(),
                rows: rows.iter().map(|r| Row::from_slice(r)).collect(),
            },
        }),
        _ => None,
    })
}
