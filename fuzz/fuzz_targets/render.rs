//! From a file to a tiny render: a legacy VTK file loaded (reader, cell
//! assembly, topology), made a scene (boundary BVH, walk records), given
//! a transfer function over its first field and partial pre-integration,
//! and rendered 8 x 8 by the CPU ray caster from a ResetCamera fit, as
//! `tetray render --renderer cpu` does through the engine (which this
//! target leaves out: it pulls in the GPU stack, whose build under the
//! sanitizer would take most of the fuzzing time).
#![no_main]
use libfuzzer_sys::fuzz_target;
use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;

fuzz_target!(|data: &[u8]| {
    let scratch = tetray_fuzz::Scratch::new();
    let Some(path) = scratch.write("input.vtk", data) else {
        return;
    };
    let Ok(loaded) = tetray_io::load(&path, &tetray_io::LoadOptions::default()) else {
        return;
    };
    let Some(field) = loaded.mesh.fields.first() else {
        return;
    };
    let (lo, hi) = field
        .values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let name = field.name.clone();
    let Ok(scene) = Scene::new(loaded.mesh, loaded.topology, &name, BuildPreset::Fastest) else {
        return;
    };
    let (min, max) = scene.bounds();
    let Ok(mut camera) = Camera::reset_to_bounds(min, max) else {
        return;
    };
    let _ = camera.azimuth(30.0).and_then(|()| camera.elevation(20.0));
    let tf = if lo < hi {
        TransferFunction::default_for_range(lo, hi)
    } else {
        TransferFunction::default_for_range(lo, lo + 1.0)
    };
    let options = IntegratorOptions {
        psi_table_size: 64,
        scalar_range: Some((lo, hi.max(lo))),
        ..IntegratorOptions::default()
    };
    let Ok(integrator) = ScalarIntegrator::new(Method::Ppi, &tf, &options) else {
        return;
    };
    let opts = RenderOptions {
        width: 8,
        height: 8,
        early_termination: 1.0,
        max_steps_per_ray: Some(10_000),
        threads: Some(1),
    };
    let _ = render_scalar(&scene, &camera, &integrator, &opts);
});
