//! Renders the Blunt Fin (or another mesh) on the GPU, the CPU and the
//! kernel's CPU twin, compares them and prints the kernel's mesh traffic
//! counted by the twin; writes the GPU and CPU images as gpu.png and
//! cpu.png in the current folder. Usage: gpu_frame [size] [method] [mesh
//! field]
use std::path::Path;

use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_gpu::{GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene};
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_io::{LoadOptions, load};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let size: u32 = args.get(1).map_or(256, |s| s.parse().unwrap());
    let method: Method = args.get(2).map_or("ppi", |s| s.as_str()).parse()?;
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let path = args
        .get(3)
        .map_or(root.join("bluntfinxyz.bin"), |p| p.into());
    let field = args.get(4).map_or("density", |s| s.as_str());
    let loaded = load(&path, &LoadOptions::default())?;
    let scene = Scene::from_loaded(loaded, field, BuildPreset::default())?;
    let (lo, hi) = scene.bounds();
    let mut camera = Camera::reset_to_bounds(lo, hi)?;
    camera.azimuth(30.0)?;
    camera.elevation(20.0)?;
    camera.orthogonalize_view_up()?;
    let (s_lo, s_hi) = scene
        .scalar
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let tf = TransferFunction::default_for_range(s_lo, s_hi);
    let options = IntegratorOptions {
        unit_distance: (hi - lo).length() / (scene.tet_count() as f32).cbrt(),
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::new(method, &tf, &options)?;
    let ctx = GpuContext::new()?;
    println!("adapter: {}", ctx.adapter_name());
    let raycaster = GpuRaycaster::new(&ctx)?;
    let gpu_scene = GpuScene::new(&ctx, &scene)?;
    let gpu_integrator = GpuIntegrator::new(&ctx, &integrator)?;
    let opts = GpuRenderOptions {
        width: size,
        height: size,
        ..GpuRenderOptions::default()
    };
    for _ in 0..3 {
        let frame = raycaster.render(&ctx, &gpu_scene, &gpu_integrator, &camera, &opts)?;
        println!("gpu: {:?}", frame.stats);
    }
    let frame = raycaster.render(&ctx, &gpu_scene, &gpu_integrator, &camera, &opts)?;
    let cpu = render_scalar(
        &scene,
        &camera,
        &integrator,
        &RenderOptions {
            width: size,
            height: size,
            ..RenderOptions::default()
        },
    )?;
    println!("cpu: {:?}", cpu.stats);
    let t = std::time::Instant::now();
    let (twin, twin_stats, traffic) = tetray_gpu::twin::render_traffic(
        &tetray_gpu::SceneData::new(&scene)?,
        &tetray_gpu::IntegratorData::new(&integrator)?,
        &camera,
        &opts,
    )?;
    println!("twin: {twin_stats:?} in {:?}", t.elapsed());
    let steps = twin_stats[tetray_gpu::layout::STAT_STEPS_LO] as f64;
    println!(
        "kernel mesh traffic: {:.1} bytes per step (tetrahedra {:.1}, points {:.1})",
        traffic.walk_bytes() as f64 / steps,
        traffic.tet_bytes as f64 / steps,
        traffic.point_bytes as f64 / steps
    );
    let segments = twin_stats[tetray_gpu::layout::STAT_SEGMENTS_LO] as f64;
    let queries = traffic.bvh_queries as f64;
    let bvh = traffic.entry_bytes() as f64;
    let all = bvh + traffic.walk_bytes() as f64;
    println!(
        "entry queries: {queries} ({:.2} per ray), {:.0} bytes each (BVH {:.0}, points {:.0}); \
         all traffic {:.1} bytes per segment, of which entries {:.1}",
        queries / f64::from(size * size),
        bvh / queries,
        traffic.bvh_bytes as f64 / queries,
        traffic.bvh_point_bytes as f64 / queries,
        all / segments,
        bvh / segments
    );
    let compare = |name: &str, a: &tetray_core::Image, b: &tetray_core::Image| {
        let mut worst = 0.0f32;
        let mut differing = 0;
        for (a, b) in a.rgba.iter().zip(&b.rgba) {
            let d = (0..4).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max);
            worst = worst.max(d);
            if d > 1e-4 {
                differing += 1;
            }
        }
        println!("{name}: max difference {worst:e}, pixels above 1e-4: {differing}");
    };
    compare("gpu vs cpu", &frame.image, &cpu.image);
    compare("gpu vs twin", &frame.image, &twin);
    compare("twin vs cpu", &twin, &cpu.image);
    frame
        .image
        .write_png(Path::new("gpu.png"), glam::Vec3::ZERO)?;
    cpu.image
        .write_png(Path::new("cpu.png"), glam::Vec3::ZERO)?;
    Ok(())
}
