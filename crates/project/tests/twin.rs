//! The projection's CPU twin against the CPU ray caster (no adapter needed):
//! the same segments, found by projecting instead of walking, integrated
//! by the same f32 code and composited back to front instead of front to
//! back.
//!
//! Tolerances (per channel, premultiplied RGBA):
//! - twin (MPVO, adaptive) vs ray caster on a convex mesh, 2e-5: both
//!   integrate every segment piece by piece between the same knots with
//!   the same f32 kernels; they differ in how segment ends are found (the
//!   projection interpolates plane depths over the entry face, the walk
//!   intersects faces with its exact predicate: ~1e-6 relative per end)
//!   and in the compositing order (rounding of ~100 segments). Pixels
//!   beyond: a budget of 1% for centres within rounding of the mesh
//!   silhouette, which one renderer may count inside and the other not.
//! - adaptive sampling on vs off against the f64 reference on a spike: the
//!   error must drop by at least 4x in the mean (measured ~20x).

mod support;

use support::{
    assert_close, camera, convex_box, integrator, knotted_tf, mean_difference, prepare, raycast,
    spike_tf, twin,
};
use tetray_integrate::Method;
use tetray_project::SortKind;

const SIZE: u32 = 48;

#[test]
fn twin_with_mpvo_matches_the_ray_caster_on_a_convex_mesh() {
    let scene = convex_box(4);
    let (lo, hi) = (0.0, 1.2);
    let tf = knotted_tf(lo, hi);
    for method in [Method::Ppi, Method::Exact] {
        let integrator = integrator(method, &tf, 0.5);
        for orthographic in [false, true] {
            let camera = camera(&scene, orthographic);
            let expected = raycast(&scene, &integrator, &camera, SIZE);
            let prepared = prepare(&scene, &integrator, &camera, SIZE, SortKind::Mpvo, true);
            let (actual, segments) = twin(&prepared);
            assert!(segments > 0);
            let name = format!(
                "twin_convex_{method}_{}",
                if orthographic { "ortho" } else { "persp" }
            );
            assert_close(
                &name,
                &actual,
                &expected,
                2e-5,
                (SIZE * SIZE / 100) as usize,
                0.05,
            );
        }
    }
}

#[test]
fn adaptive_sampling_catches_an_opacity_spike() {
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
    let on = twin(&prepare(
        &scene,
        &exact,
        &camera,
        SIZE,
        SortKind::Mpvo,
        true,
    ))
    .0;
    let off = twin(&prepare(
        &scene,
        &exact,
        &camera,
        SIZE,
        SortKind::Mpvo,
        false,
    ))
    .0;
    let (error_on, error_off) = (
        mean_difference(&on, &reference),
        mean_difference(&off, &reference),
    );
    eprintln!("spike: mean error adaptive {error_on:e}, vertex sampling {error_off:e}");
    assert!(
        error_off > 4.0 * error_on,
        "on {error_on:e}, off {error_off:e}"
    );
    assert!(
        error_on < 1e-4,
        "adaptive sampling should be exact to f32: {error_on:e}"
    );
}
