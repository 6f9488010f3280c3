//! In situ, as a simulation would call it: every rank builds its part of
//! a mesh in memory (a hollow box, split spatially by rank), hands the
//! arrays to `render_in_situ` on the world communicator, and rank 0
//! writes the image. Rank 0 then renders the whole mesh alone (the same
//! camera fit, transfer function and unit distance, from the whole mesh)
//! and prints the largest difference per pixel channel; it exits with 1
//! when that exceeds 1e-5 (the compositing is exact up to f32 rounding).
//!
//! ```sh
//! mpirun -n 4 target/release/examples/in_situ [out.exr]
//! ```

use std::process::ExitCode;

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_distributed::in_situ::fit_camera;
use tetray_distributed::mpi::traits::*;
use tetray_distributed::{render_in_situ, spatial_split, InSituView, RankMesh};
use tetray_integrate::{IntegratorOptions, ScalarIntegrator, TransferFunction};
use tetray_mesh::{paraview_unit_distance, prepare, ScalarField, TetMesh};
use tetray_raycast::scenes::{hollow_box, CellSplit};
use tetray_raycast::{render_scalar, RenderOptions, Scene};

/// A nonlinear field, so a wrong split or order would show.
fn field(p: Vec3) -> f32 {
    (p.x * 1.7).sin() * 0.5 + p.y * p.z * 0.3
}

fn whole_mesh() -> TetMesh {
    let mut mesh = hollow_box(
        Vec3::new(-2.0, -1.0, -1.0),
        Vec3::new(2.0, 1.0, 1.5),
        [10, 5, 6],
        [2, 1, 1],
        [8, 4, 5],
        CellSplit::Five,
    )
    .expect("a valid box");
    let values = mesh.points.iter().map(|&p| field(p)).collect();
    mesh.fields.push(ScalarField {
        name: "s".into(),
        values,
    });
    mesh
}

fn main() -> ExitCode {
    let Some(universe) = tetray_distributed::mpi::initialize() else {
        eprintln!("error: MPI is already initialised");
        return ExitCode::FAILURE;
    };
    let world = universe.world();
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let whole = whole_mesh();
    let part = spatial_split(&whole, rank, size);
    let points: Vec<[f64; 3]> = part
        .points
        .iter()
        .map(|p| p.as_dvec3().to_array())
        .collect();
    let view = InSituView {
        width: 96,
        height: 72,
        azimuth: 70.0,
        elevation: 15.0,
        ..InSituView::default()
    };
    let frame = match render_in_situ(
        &world,
        RankMesh {
            points: &points,
            tets: &part.tets,
            scalars: &part.fields[0].values,
        },
        &view,
    ) {
        Ok(frame) => frame,
        Err(e) => {
            eprintln!("error: rank {rank}: {e}");
            world.abort(1);
        }
    };
    let Some(frame) = frame else {
        return ExitCode::SUCCESS;
    };
    println!("{}", frame.report.describe());
    if let Some(path) = std::env::args().nth(1) {
        if let Err(e) = frame.image.write_exr(std::path::Path::new(&path)) {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    }
    // The whole mesh in this one process.
    let loaded = prepare(whole).expect("a valid mesh");
    let cells = loaded.mesh.tets.len();
    let scene = Scene::new(loaded.mesh, loaded.topology, "s", BuildPreset::default())
        .expect("a valid scene");
    let (lo, hi) = scene.bounds();
    let (s_lo, s_hi) = tetray_mesh::value_range(&scene.scalar);
    let camera = fit_camera(lo, hi, &view).expect("a valid camera");
    let tf = TransferFunction::default_for_range(s_lo, s_hi);
    let options = IntegratorOptions {
        unit_distance: paraview_unit_distance((lo, hi), cells),
        scalar_range: Some((s_lo, s_hi)),
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::new(view.method, &tf, &options).expect("an integrator");
    let opts = RenderOptions {
        width: view.width,
        height: view.height,
        ..RenderOptions::default()
    };
    let reference = render_scalar(&scene, &camera, &integrator, &opts).expect("a frame");
    let worst = frame
        .image
        .rgba
        .iter()
        .zip(&reference.image.rgba)
        .flat_map(|(a, b)| (0..4).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0f32, f32::max);
    let lit = reference.image.rgba.iter().filter(|p| p[3] > 0.0).count();
    println!(
        "in situ over {size} ranks: max error {worst:e} against one process ({lit} pixels lit)"
    );
    if worst > 1e-5 || lit == 0 {
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
