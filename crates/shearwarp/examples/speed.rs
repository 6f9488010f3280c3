//! Frames per second of shear-warp (pre-integrated and post-classified,
//! parallel and perspective) and of the exact tetrahedral CPU ray caster
//! on the same analytic N^3 grid (default 256), 512 x 512, oblique view.
//!
//! `cargo run --release -p tetray-shearwarp --example speed -- [N] [--no-tets]`

use std::time::Instant;

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityPoint, ScalarIntegrator, TransferFunction,
};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;
use tetray_shearwarp::{Classification, ClassifyOptions, RegularGrid, ShearWarp, ShearWarpOptions};

const SIZE: u32 = 512;
const FRAMES: usize = 5;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.iter().find_map(|a| a.parse().ok()).unwrap_or(256);
    let tets = !args.iter().any(|a| a == "--no-tets");
    let start = Instant::now();
    let h = 2.0 / (n - 1) as f32;
    let grid = RegularGrid::from_fn([n, n, n], Vec3::splat(-1.0), Vec3::splat(h), |p| {
        (-2.5 * p.length_squared()).exp() + 0.15 * (5.0 * p.x).sin() * (4.0 * p.y).cos()
    })?;
    println!(
        "grid {n}^3 ({} points) made in {:.2} s; {} threads",
        n * n * n,
        start.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
    let tf = TransferFunction::new(
        vec![
            ColorPoint {
                scalar: 0.0,
                rgb: Vec3::new(0.2, 0.3, 0.9),
            },
            ColorPoint {
                scalar: 1.0,
                rgb: Vec3::new(1.0, 0.3, 0.1),
            },
        ],
        vec![
            OpacityPoint {
                scalar: 0.0,
                alpha: 0.0,
            },
            OpacityPoint {
                scalar: 0.25,
                alpha: 0.0,
            },
            OpacityPoint {
                scalar: 1.0,
                alpha: 0.9,
            },
        ],
    )?;
    // ParaView's unit distance for the grid: diagonal / cells^(1/3).
    let unit = (3.0f32).sqrt() * 2.0 / (n - 1) as f32;
    let camera = |parallel: bool| -> Result<Camera, Box<dyn std::error::Error>> {
        let mut cam = Camera {
            parallel_scale: parallel.then_some(1.0),
            ..Camera::default()
        };
        let (lo, hi) = grid.bounds();
        cam.reset(lo, hi, 1.0)?;
        cam.azimuth(30.0)?;
        cam.elevation(20.0)?;
        cam.orthogonalize_view_up()?;
        Ok(cam)
    };
    for c in [
        Classification::PreIntegrated,
        Classification::PostClassified,
    ] {
        let t = Instant::now();
        let opts = ClassifyOptions {
            classification: c,
            unit_distance: unit,
            ..ClassifyOptions::default()
        };
        let sw = ShearWarp::new(grid.clone(), &tf, &opts)?;
        sw.prepare_all_axes();
        println!(
            "shear-warp {}: set up in {:.2} s",
            c.name(),
            t.elapsed().as_secs_f64()
        );
        for parallel in [true, false] {
            let cam = camera(parallel)?;
            let frame = ShearWarpOptions {
                width: SIZE,
                height: SIZE,
                early_termination: 0.99,
                skip_empty: true,
            };
            sw.render(&cam, &frame)?; // warm
            let t = Instant::now();
            let mut last = None;
            for _ in 0..FRAMES {
                last = Some(sw.render(&cam, &frame)?);
            }
            let s = t.elapsed().as_secs_f64() / FRAMES as f64;
            let st = last.map(|o| o.stats).unwrap_or_default();
            println!(
                "  {}: {:.2} frames/s ({:.1} ms; composite {:.1} ms, warp {:.1} ms; {} slabs, {} skipped empty, {} rays stopped)",
                if parallel { "parallel" } else { "perspective" },
                1.0 / s,
                s * 1e3,
                st.composite_time.as_secs_f64() * 1e3,
                st.warp_time.as_secs_f64() * 1e3,
                st.slabs_composited,
                st.slabs_skipped,
                st.rays_terminated
            );
        }
    }
    if !tets {
        return Ok(());
    }
    let t = Instant::now();
    let loaded = tetray_mesh::prepare(grid.to_tet_mesh("s"))?;
    let scene = Scene::from_loaded(loaded, "s", BuildPreset::default())?;
    println!(
        "tetrahedral ray caster: {} tetrahedra, scene ready in {:.1} s",
        scene.tet_count(),
        t.elapsed().as_secs_f64()
    );
    let options = IntegratorOptions {
        unit_distance: unit,
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::new(Method::Exact, &tf, &options)?;
    for parallel in [true, false] {
        let cam = camera(parallel)?;
        let opts = RenderOptions {
            width: SIZE,
            height: SIZE,
            early_termination: 0.99,
            ..RenderOptions::default()
        };
        let t = Instant::now();
        let out = render_scalar(&scene, &cam, &integrator, &opts)?;
        let s = t.elapsed().as_secs_f64();
        println!(
            "  exact, {}: {:.3} frames/s ({:.2} s; {} segments)",
            if parallel { "parallel" } else { "perspective" },
            1.0 / s,
            s,
            out.stats.counters.segments
        );
    }
    Ok(())
}
