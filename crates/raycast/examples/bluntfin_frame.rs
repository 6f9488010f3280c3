//! Times CPU frames of the Blunt Fin (data/plot3d/bluntfin{xyz,q}.bin).
//! Usage: bluntfin_frame [size] [frames] [threads] [method|absorb]

use std::path::Path;
use std::time::Instant;

use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_integrate::{
    IntegratorOptions, KernelVisitor, Method, ScalarIntegrator, SegmentKernel, TransferFunction,
    Typed,
};
use tetray_io::{LoadOptions, load};
use tetray_raycast::{RenderOptions, SegmentIntegrator, render_cpu};
use tetray_scene::Scene;

struct Absorb {
    cheap: bool,
}
impl SegmentIntegrator for Absorb {
    type Sample = f32;

    fn sample(&self, s: f32) -> f32 {
        s
    }

    fn segment(&self, &s_front: &f32, &s_back: &f32, length: f32) -> (glam::Vec3A, glam::Vec3A) {
        let tau = 0.5 * (s_front + s_back) * 0.2;
        let t = if self.cheap {
            1.0 - tau * length * 1e-3
        } else {
            (-tau * length).exp()
        };
        (glam::Vec3A::splat(1.0 - t), glam::Vec3A::splat(t))
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let size: u32 = args.get(1).map_or(512, |s| s.parse().unwrap());
    let frames: usize = args.get(2).map_or(5, |s| s.parse().unwrap());
    let threads: usize = args.get(3).map_or(2, |s| s.parse().unwrap());
    let method = args.get(4).cloned().unwrap_or_else(|| "absorb".to_string());
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let loaded = load(&root.join("bluntfinxyz.bin"), &LoadOptions::default()).unwrap();
    let t = Instant::now();
    let scene = Scene::from_loaded(loaded, "density", BuildPreset::default()).unwrap();
    println!(
        "scene: {} tets, {} boundary faces, {:.3}s",
        scene.tet_count(),
        scene.topology.boundary_faces.len(),
        t.elapsed().as_secs_f64()
    );
    let (lo, hi) = scene.bounds();
    let mut camera = Camera::reset_to_bounds(lo, hi).unwrap();
    camera.azimuth(30.0).unwrap();
    camera.elevation(20.0).unwrap();
    camera.orthogonalize_view_up().unwrap();
    let opts = RenderOptions {
        width: size,
        height: size,
        threads: Some(threads),
        ..RenderOptions::default()
    };
    let absorb = Absorb {
        cheap: std::env::var_os("NOEXP").is_some(),
    };
    let (lo_s, hi_s) = scene
        .scalar
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let tf = TransferFunction::default_for_range(lo_s, hi_s);
    let unit = (hi - lo).length() / (scene.tet_count() as f32).cbrt();
    let options = IntegratorOptions {
        unit_distance: unit,
        psi_table_size: std::env::var("PSI_SIZE").map_or(1024, |s| s.parse().unwrap()),
        ..IntegratorOptions::default()
    };
    if method == "absorb" {
        time_frames(&scene, &camera, &absorb, &opts, frames);
    } else {
        let method: Method = method.parse().unwrap();
        let scalar = ScalarIntegrator::new(method, &tf, &options).unwrap();
        struct Time<'a>(&'a Scene, &'a Camera, &'a RenderOptions, usize);
        impl KernelVisitor for Time<'_> {
            type Output = ();
            fn visit<K: SegmentKernel>(self, integrator: Typed<'_, K>) {
                time_frames(self.0, self.1, &integrator, self.2, self.3);
            }
        }
        scalar.dispatch(Time(&scene, &camera, &opts, frames));
    }
}

fn time_frames<I: SegmentIntegrator>(
    scene: &Scene,
    camera: &Camera,
    integrator: &I,
    opts: &RenderOptions,
    frames: usize,
) {
    let mut best = f64::INFINITY;
    for _ in 0..frames {
        let out = render_cpu(scene, camera, integrator, opts).unwrap();
        let s = out.stats;
        best = best.min(s.elapsed.as_secs_f64());
        println!(
            "{:.4}s rays {} hit {} segs {} steps {} entries {} fail {} bound {} -> {:.1} Mseg/s",
            s.elapsed.as_secs_f64(),
            s.counters.rays,
            s.counters.rays_hit,
            s.counters.segments,
            s.counters.steps,
            s.counters.entries,
            s.counters.walk_failures,
            s.counters.steps_bound_hits,
            s.segments_per_second() / 1e6
        );
    }
    println!("best {best:.4}s");
}
