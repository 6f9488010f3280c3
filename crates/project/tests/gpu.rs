//! The projection pipeline on whatever adapter there is (lavapipe in CI):
//! against its CPU twin, against the ray casters on a convex mesh, and
//! adaptive sampling on vs off.
//!
//! Tolerances (per channel, premultiplied RGBA):
//! - GPU vs twin, 1e-4: the same draws, vertex and fragment arithmetic;
//!   the rasterizer's interpolation of the plane attributes (its own
//!   barycentric arithmetic) moves segment ends by ~1e-6 relative, and the
//!   blender's rounding differs from the twin's. Pixels beyond: 1% whose
//!   centres lie within the rasterizer's fixed-point snapping of a
//!   silhouette edge, which it and the twin's exact edge test may decide
//!   differently.
//! - GPU projection (MPVO) vs the CPU ray caster on a convex mesh, 1e-4
//!   and 1%, for the same reasons plus those of tests/twin.rs.
//! - Over rgba16float (no FLOAT32_BLENDABLE) the blender rounds to 11 bits
//!   per draw: the tolerances widen to 4e-3.

mod support;

use support::{
    assert_close, camera, convex_box, covered, gpu, integrator, knotted_tf, mean_difference,
    prepare, project_gpu, raycast, spike_tf, twin,
};
use tetray_integrate::Method;
use tetray_project::SortKind;

const SIZE: u32 = 48;

fn tolerance() -> f32 {
    match gpu() {
        Some((_, projector)) if projector.format() == wgpu::TextureFormat::Rgba16Float => 4e-3,
        _ => 1e-4,
    }
}

#[test]
fn gpu_matches_its_twin() {
    let Some(gpu) = gpu() else { return };
    let scene = convex_box(4);
    let tf = knotted_tf(0.0, 1.2);
    let cases = [
        (Method::Ppi, SortKind::Mpvo, true, false),
        (Method::Ppi, SortKind::Centroid, true, true),
        (Method::Exact, SortKind::Mpvonc, false, false),
        (Method::LinOpacity, SortKind::Mpvo, true, false),
        (Method::Preintegrated, SortKind::Mpvo, true, false),
    ];
    for (method, sort, adaptive, orthographic) in cases {
        let integrator = integrator(method, &tf, 0.5);
        let camera = camera(&scene, orthographic);
        let prepared = prepare(&scene, &integrator, &camera, SIZE, sort, adaptive);
        let (expected, twin_segments) = twin(&prepared);
        let (actual, gpu_segments) = project_gpu(gpu, &prepared);
        let name = format!("gpu_vs_twin_{method}_{sort}_{adaptive}_{orthographic}");
        assert_close(
            &name,
            &actual,
            &expected,
            tolerance(),
            (SIZE * SIZE / 100) as usize,
            0.05,
        );
        // Fragments: the same up to the pixels on snapped edges.
        let diff = gpu_segments.abs_diff(twin_segments);
        assert!(
            diff * 100 <= twin_segments,
            "{name}: segments {gpu_segments} vs {twin_segments}"
        );
    }
}

#[test]
fn gpu_projection_with_mpvo_matches_the_ray_caster_on_a_convex_mesh() {
    let Some(gpu) = gpu() else { return };
    let scene = convex_box(4);
    let tf = knotted_tf(0.0, 1.2);
    let integrator = integrator(Method::Ppi, &tf, 0.5);
    for orthographic in [false, true] {
        let camera = camera(&scene, orthographic);
        let expected = raycast(&scene, &integrator, &camera, SIZE);
        let prepared = prepare(&scene, &integrator, &camera, SIZE, SortKind::Mpvo, true);
        let (actual, _) = project_gpu(gpu, &prepared);
        assert!(
            covered(&actual) > (SIZE * SIZE / 4) as usize,
            "the box fills the view"
        );
        let name = format!(
            "gpu_vs_raycast_{}",
            if orthographic { "ortho" } else { "persp" }
        );
        assert_close(
            &name,
            &actual,
            &expected,
            tolerance(),
            (SIZE * SIZE / 100) as usize,
            0.05,
        );
    }
}

#[test]
fn gpu_adaptive_sampling_catches_an_opacity_spike() {
    let Some(gpu) = gpu() else { return };
    let scene = convex_box(4);
    let tf = spike_tf(0.0, 1.2, 0.55, 0.02);
    let camera = camera(&scene, false);
    let reference = raycast(
        &scene,
        &integrator(Method::Reference, &tf, 0.5),
        &camera,
        SIZE,
    );
    let exact = integrator(Method::Exact, &tf, 0.5);
    let on_plan = prepare(&scene, &exact, &camera, SIZE, SortKind::Mpvo, true);
    let off_plan = prepare(&scene, &exact, &camera, SIZE, SortKind::Mpvo, false);
    assert!(
        on_plan.draws.len() > off_plan.draws.len(),
        "pieces add draws"
    );
    let on = project_gpu(gpu, &on_plan).0;
    let off = project_gpu(gpu, &off_plan).0;
    let (error_on, error_off) = (
        mean_difference(&on, &reference),
        mean_difference(&off, &reference),
    );
    eprintln!(
        "spike on the GPU: mean error adaptive {error_on:e} ({} draws), vertex sampling \
         {error_off:e} ({} draws)",
        on_plan.draws.len(),
        off_plan.draws.len()
    );
    assert!(
        error_off > 4.0 * error_on,
        "on {error_on:e}, off {error_off:e}"
    );
}
