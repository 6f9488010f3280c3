//! Shared by the benches: the embedded Blunt Fin as a scene, with its
//! default transfer function and camera, as `tetray render` sets them up.

#![allow(dead_code)]

use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_mesh::LoadedMesh;
use tetray_scene::Scene;

const XYZ: &[u8] = include_bytes!("../../data/plot3d/bluntfinxyz.bin");
const Q: &[u8] = include_bytes!("../../data/plot3d/bluntfinq.bin");

pub fn blunt_fin_mesh() -> LoadedMesh {
    tetray_io::load_plot3d_bytes(XYZ, Some(Q), "Blunt Fin").expect("the embedded dataset loads")
}

pub fn blunt_fin() -> Scene {
    Scene::from_loaded(blunt_fin_mesh(), "density", BuildPreset::default()).expect("scene")
}

/// The scalar's range and the default transfer function over it.
pub fn transfer_function(scene: &Scene) -> TransferFunction {
    let (lo, hi) = scene
        .scalar
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    TransferFunction::default_for_range(lo, hi)
}

/// `method` over the scene's default transfer function, unit distance
/// ParaView's for the Blunt Fin (diagonal / cbrt(37479 hexahedra)).
pub fn integrator(scene: &Scene, method: Method) -> ScalarIntegrator {
    let options = IntegratorOptions {
        unit_distance: 0.728,
        riemann_step: 0.05,
        preintegration_length: 0.2,
        ..IntegratorOptions::default()
    };
    ScalarIntegrator::new(method, &transfer_function(scene), &options).expect("integrator")
}

/// ResetCamera on the bounds for a square image.
pub fn camera(scene: &Scene) -> Camera {
    let (lo, hi) = scene.bounds();
    let mut camera = Camera::default();
    camera.reset(lo, hi, 1.0).expect("camera");
    camera
}
