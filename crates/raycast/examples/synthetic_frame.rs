//! Times CPU frames of a structured box grid (walk cost without memory
//! effects of a large mesh). Usage: synthetic_frame [cells] [size] [frames]

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_mesh::Topology;
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, box_grid};
use tetray_raycast::{RenderOptions, SegmentIntegrator, render_cpu};
use tetray_scene::Scene;

struct Absorb;
impl SegmentIntegrator for Absorb {
    type Sample = f32;

    fn sample(&self, s: f32) -> f32 {
        s
    }

    fn segment(&self, &s_front: &f32, &s_back: &f32, length: f32) -> (glam::Vec3A, glam::Vec3A) {
        let t = 1.0 - 0.5 * (s_front + s_back) * length * 1e-3;
        (glam::Vec3A::splat(1.0 - t), glam::Vec3A::splat(t))
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let cells: u32 = args.get(1).map_or(8, |s| s.parse().unwrap());
    let size: u32 = args.get(2).map_or(512, |s| s.parse().unwrap());
    let frames: usize = args.get(3).map_or(5, |s| s.parse().unwrap());
    let mut mesh = box_grid(Vec3::ZERO, Vec3::ONE, [cells; 3], CellSplit::Five).unwrap();
    add_field(
        &mut mesh,
        "x",
        ScalarSpec::Linear {
            offset: 0.0,
            gradient: Vec3::X,
        },
    );
    let topology = Topology::build(&mesh).unwrap();
    let scene = Scene::new(mesh, topology, "x", BuildPreset::default()).unwrap();
    let mut camera = Camera::reset_to_bounds(Vec3::ZERO, Vec3::ONE).unwrap();
    camera.azimuth(30.0).unwrap();
    camera.elevation(20.0).unwrap();
    camera.orthogonalize_view_up().unwrap();
    let opts = RenderOptions {
        width: size,
        height: size,
        threads: Some(1),
        ..RenderOptions::default()
    };
    let mut best = f64::INFINITY;
    let mut steps = 0;
    for _ in 0..frames {
        let out = render_cpu(&scene, &camera, &Absorb, &opts).unwrap();
        best = best.min(out.stats.elapsed.as_secs_f64());
        steps = out.stats.counters.steps;
    }
    println!(
        "{} tets: best {best:.4}s, {steps} steps, {:.1} ns/step",
        scene.tet_count(),
        best * 1e9 / steps as f64
    );
}
