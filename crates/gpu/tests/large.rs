//! What large meshes and images need: arrays split over two storage
//! bindings, images cut into several dispatches, and a clear error when a
//! mesh cannot fit.

mod support;

use glam::Vec3;
use support::{assert_close, gpu, scene};
use tetray_core::Camera;
use tetray_gpu::{GpuError, GpuIntegrator, GpuRenderOptions, GpuScene, SceneData, TILE};
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, jittered_box};
use tetray_raycast::{RenderOptions, render_scalar};

fn setup() -> (tetray_scene::Scene, ScalarIntegrator, Camera) {
    let (lo, hi) = (Vec3::ZERO, Vec3::new(2.0, 1.0, 1.0));
    let mut mesh = jittered_box(lo, hi, [8, 4, 4], 0.2, 11, CellSplit::Five).expect("mesh");
    add_field(
        &mut mesh,
        "s",
        ScalarSpec::Linear {
            offset: 0.0,
            gradient: Vec3::new(0.5, 0.2, 0.1),
        },
    );
    let scene = scene(mesh, "s");
    let tf = TransferFunction::default_for_range(0.0, 1.3);
    let integrator = ScalarIntegrator::new(
        Method::Ppi,
        &tf,
        &IntegratorOptions {
            unit_distance: 0.3,
            ..Default::default()
        },
    )
    .expect("integrator");
    let mut camera = Camera::reset_to_bounds(lo, hi).expect("camera");
    camera.azimuth(20.0).expect("azimuth");
    camera.orthogonalize_view_up().expect("view up");
    (scene, integrator, camera)
}

#[test]
fn split_bindings_and_tiles_render_like_the_reference() {
    let Some((ctx, raycaster)) = gpu() else {
        return;
    };
    let (scene, integrator, camera) = setup();
    let data = SceneData::new(&scene).expect("data");
    // Bindings of 60% of each array: both split in two.
    let tet_limit = (data.tets.len() * 16 * 6 / 10) as u64;
    let point_limit = (data.points.len() * 16 * 6 / 10) as u64;
    let split = GpuScene::upload_with_binding_limits(ctx, &data, tet_limit, point_limit);
    let Ok(split) = split else {
        panic!(
            "a mesh needing two bindings uploads: {}",
            split.err().map(|e| e.to_string()).unwrap_or_default()
        );
    };
    let gpu_integrator = GpuIntegrator::new(ctx, &integrator).expect("integrator");
    // Wider than one dispatch tile, so the frame is several dispatches.
    let (width, height) = (TILE + 37, 24);
    let opts = GpuRenderOptions {
        width,
        height,
        ..Default::default()
    };
    let frame = raycaster
        .render(ctx, &split, &gpu_integrator, &camera, &opts)
        .expect("render");
    let cpu = render_scalar(
        &scene,
        &camera,
        &integrator,
        &RenderOptions {
            width,
            height,
            ..Default::default()
        },
    )
    .expect("cpu");
    assert_eq!(frame.stats.counters.steps, cpu.stats.counters.steps);
    assert_close("split-and-tiled", &frame.image, &cpu.image, 3e-5, 0, 3e-5);
}

#[test]
fn a_mesh_beyond_two_bindings_is_refused_naming_the_limit() {
    let Some((ctx, _)) = gpu() else { return };
    let (scene, _, _) = setup();
    let data = SceneData::new(&scene).expect("data");
    // Each binding holds a tenth of the tetrahedra: two cannot.
    let limit = (data.tets.len() * 16 / 10) as u64;
    match GpuScene::upload_with_binding_limits(ctx, &data, limit, u64::MAX) {
        Err(e @ GpuError::TooLarge { .. }) => {
            let message = e.to_string();
            assert!(
                message.contains("max_storage_buffer_binding_size"),
                "{message}"
            );
            assert!(message.contains("tetrahedra"), "{message}");
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("uploaded a mesh that cannot fit"),
    }
}
