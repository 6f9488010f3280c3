//! `tetray info`: counts, bounds, scalar ranges and validation findings.

use anyhow::Context;
use clap::Args;
use serde::Serialize;
use tetray_mesh::MeshSummary;

use super::args::MeshArgs;
use super::scene;

/// `tetray info`.
#[derive(Debug, Clone, Args)]
pub struct InfoArgs {
    #[command(flatten)]
    pub mesh: MeshArgs,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Also describe the GPU adapter the ray caster would use (chosen by
    /// WGPU_ADAPTER_NAME / WGPU_BACKEND, else the default), and fail if
    /// there is none.
    #[arg(long)]
    pub gpu: bool,
}

/// What `--gpu` reports of the adapter.
#[derive(Debug, Serialize)]
struct AdapterJson {
    name: String,
    backend: String,
    device_type: String,
    driver: String,
    driver_info: String,
    timestamp_queries: bool,
    max_storage_buffer_binding_size: u64,
    max_buffer_size: u64,
    max_compute_workgroups_per_dimension: u32,
}

fn adapter_json() -> anyhow::Result<AdapterJson> {
    let ctx = tetray_gpu::GpuContext::new().context("--gpu")?;
    Ok(AdapterJson {
        name: ctx.info.name.clone(),
        backend: format!("{:?}", ctx.info.backend),
        device_type: format!("{:?}", ctx.info.device_type),
        driver: ctx.info.driver.clone(),
        driver_info: ctx.info.driver_info.clone(),
        timestamp_queries: ctx.timestamps,
        max_storage_buffer_binding_size: ctx.limits.max_storage_buffer_binding_size,
        max_buffer_size: ctx.limits.max_buffer_size,
        max_compute_workgroups_per_dimension: ctx.limits.max_compute_workgroups_per_dimension,
    })
}

/// The JSON form of [`MeshSummary`], plus the validation counters.
#[derive(Debug, Serialize)]
struct InfoJson<'a> {
    mesh: &'a str,
    format: &'a str,
    points: usize,
    tets: usize,
    interior_faces: usize,
    boundary_faces: usize,
    components: usize,
    bounds: Bounds,
    fields: Vec<FieldJson<'a>>,
    /// Cells of the file as read, before splitting (ParaView's count).
    input_cells: usize,
    cells_split: usize,
    tets_from_split: usize,
    reoriented: usize,
    degenerate_dropped: usize,
    /// Piece files joined (parallel and multi-block files; 0 otherwise).
    pieces: usize,
    welded_points: usize,
    ghost_cells_dropped: usize,
    hidden_cells_dropped: usize,
    /// Multi-block leaves read and skipped (`.vtm`; 0 otherwise); the
    /// Exodus element blocks are `blocks`.
    blocks_read: usize,
    blocks_skipped: usize,
    duplicate_points: usize,
    unused_points: usize,
    seam_faces: usize,
    /// The stored points (and `bounds`) are relative to this origin: file
    /// coordinates = origin + point.
    origin: [f64; 3],
    /// Points on another tetrahedron's face or edge (hanging nodes).
    hanging_nodes: usize,
    /// Pairs of boundary faces split differently on the two sides.
    folded_face_pairs: usize,
    /// The unmatched faces made boundary, both sides.
    nonconforming_faces: Vec<FaceJson>,
    /// Cells left out of the walk.
    excluded: ExcludedJson<'a>,
    /// ParaView's default opacity unit distance for this dataset.
    paraview_unit_distance: f32,
    load_seconds: f64,
    valid: bool,
    warnings: &'a [String],
    /// The stored times, one per time step (Exodus II, VTKHDF, a file
    /// series; empty otherwise).
    times: &'a [f64],
    /// The time step read (0-based).
    time_step: Option<usize>,
    /// Exodus II: the element blocks, kept (volume) or skipped.
    blocks: Vec<BlockJson<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    adapter: Option<AdapterJson>,
}

#[derive(Debug, Serialize)]
struct BlockJson<'a> {
    id: i64,
    name: &'a str,
    elem_type: &'a str,
    nodes_per_element: usize,
    cells: usize,
    kept: bool,
}

#[derive(Debug, Serialize)]
struct FaceJson {
    tet: u32,
    local_face: u8,
    vertices: [u32; 3],
}

#[derive(Debug, Serialize)]
struct ExcludedJson<'a> {
    /// File cell indices (VTK) or tetrahedron indices as given.
    cells: &'a [u32],
    tangled: usize,
    overlapping: usize,
    non_manifold: usize,
    tets: usize,
    volume: f64,
    volume_share: f64,
    flat_tets: usize,
}

#[derive(Debug, Serialize)]
struct Bounds {
    min: [f32; 3],
    max: [f32; 3],
}

#[derive(Debug, Serialize)]
struct FieldJson<'a> {
    name: &'a str,
    min: f32,
    max: f32,
}

pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    let adapter = if args.gpu {
        Some(adapter_json()?)
    } else {
        None
    };
    // A mesh that fails validation is an error naming the problem (exit 1).
    let input = scene::load_mesh(&args.mesh)?;
    let summary = MeshSummary::new(&input.loaded);
    let validation = &input.loaded.report.validation;
    if args.json {
        let (lo, hi) = summary.bounds;
        let json = InfoJson {
            mesh: &input.name,
            format: summary.format,
            points: summary.points,
            tets: summary.tets,
            interior_faces: summary.interior_faces,
            boundary_faces: summary.boundary_faces,
            components: summary.components,
            bounds: Bounds {
                min: lo.to_array(),
                max: hi.to_array(),
            },
            fields: summary
                .fields
                .iter()
                .map(|f| FieldJson {
                    name: &f.name,
                    min: f.min,
                    max: f.max,
                })
                .collect(),
            input_cells: input.input_cells(),
            cells_split: summary.cells_split,
            tets_from_split: summary.tets_from_split,
            reoriented: summary.inverted_fixed,
            degenerate_dropped: summary.degenerate_dropped,
            pieces: summary.pieces.pieces,
            welded_points: summary.pieces.welded_points,
            ghost_cells_dropped: summary.pieces.ghost_cells_dropped,
            hidden_cells_dropped: summary.pieces.hidden_cells_dropped,
            blocks_read: summary.pieces.blocks,
            blocks_skipped: summary.pieces.blocks_skipped,
            duplicate_points: validation.duplicate_points,
            unused_points: validation.unused_points,
            seam_faces: validation.seam_faces,
            origin: summary.origin.to_array(),
            hanging_nodes: validation.hanging_nodes,
            folded_face_pairs: validation.folded_face_pairs,
            nonconforming_faces: validation
                .nonconforming_faces
                .iter()
                .map(|f| FaceJson {
                    tet: f.tet,
                    local_face: f.local_face,
                    vertices: f.vertices,
                })
                .collect(),
            excluded: ExcludedJson {
                cells: &summary.excluded.cells,
                tangled: summary.excluded.tangled,
                overlapping: summary.excluded.overlapping,
                non_manifold: summary.excluded.non_manifold,
                tets: summary.excluded.tets,
                volume: summary.excluded.volume,
                volume_share: summary.excluded.volume_share,
                flat_tets: summary.excluded.flat_tets,
            },
            paraview_unit_distance: input.paraview_unit_distance(),
            load_seconds: input.load_time.as_secs_f64(),
            valid: true,
            warnings: &summary.warnings,
            times: &summary.times,
            time_step: summary.time_step,
            blocks: summary
                .blocks
                .iter()
                .map(|b| BlockJson {
                    id: b.id,
                    name: &b.name,
                    elem_type: &b.elem_type,
                    nodes_per_element: b.nodes_per_element,
                    cells: b.cells,
                    kept: b.kept,
                })
                .collect(),
            adapter,
        };
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        println!("mesh:            {}", input.name);
        print!("{summary}");
        println!(
            "unit distance:   {} (ParaView's default: diagonal / cbrt({} cells))",
            input.paraview_unit_distance(),
            input.input_cells()
        );
        println!("loaded in:       {:.3} s", input.load_time.as_secs_f64());
        if let Some(a) = &adapter {
            println!(
                "gpu adapter:     {} ({}, {}), driver {} {}",
                a.name, a.backend, a.device_type, a.driver, a.driver_info
            );
            println!(
                "gpu limits:      storage binding {} MB, buffer {} MB, timestamps {}",
                a.max_storage_buffer_binding_size >> 20,
                a.max_buffer_size >> 20,
                if a.timestamp_queries { "yes" } else { "no" }
            );
        }
    }
    Ok(())
}
