//! Shared helpers of the GPU tests: the adapter (required in CI), scenes,
//! renders on the GPU, its CPU twin and the f64 reference, and image
//! comparison with failure images.

#![allow(dead_code)]

use std::path::PathBuf;
use std::sync::OnceLock;

use tetray_boundary_bvh::BuildPreset;
use tetray_core::{Camera, Image};
use tetray_gpu::{
    GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene, GpuStats, IntegratorData,
    SceneData,
};
use tetray_integrate::ScalarIntegrator;
use tetray_mesh::{TetMesh, Topology};
use tetray_raycast::{RenderOptions, RenderStats, render_scalar};
use tetray_scene::Scene;

/// The adapter and compiled kernel, shared by a test binary. `None` (with a
/// loud message) when there is no adapter, unless `TETRAY_REQUIRE_GPU=1`
/// (CI), where that is a failure.
pub fn gpu() -> Option<&'static (GpuContext, GpuRaycaster)> {
    static GPU: OnceLock<Option<(GpuContext, GpuRaycaster)>> = OnceLock::new();
    GPU.get_or_init(|| match GpuContext::new() {
        Ok(ctx) => {
            eprintln!("GPU tests on {}", ctx.adapter_name());
            let raycaster = GpuRaycaster::new(&ctx).expect("the kernel compiles");
            Some((ctx, raycaster))
        }
        Err(e) => {
            if std::env::var("TETRAY_REQUIRE_GPU").as_deref() == Ok("1") {
                panic!("TETRAY_REQUIRE_GPU=1 but no adapter: {e}");
            }
            eprintln!("\n!!! SKIPPING GPU TEST: no adapter ({e}) !!!\n");
            None
        }
    })
    .as_ref()
}

pub fn scene(mesh: TetMesh, field: &str) -> Scene {
    let topology = Topology::build(&mesh).expect("topology");
    Scene::new(mesh, topology, field, BuildPreset::default()).expect("scene")
}

/// The three renders of one view.
pub struct Renders {
    pub gpu: Image,
    pub gpu_stats: GpuStats,
    pub twin: Image,
    pub twin_stats: [u64; tetray_gpu::layout::STAT_COUNT],
    pub cpu: Image,
    pub cpu_stats: RenderStats,
}

pub fn render_all(
    gpu: &(GpuContext, GpuRaycaster),
    scene: &Scene,
    integrator: &ScalarIntegrator,
    camera: &Camera,
    size: u32,
) -> Renders {
    let (ctx, raycaster) = gpu;
    let scene_data = SceneData::new(scene).expect("scene data");
    let integrator_data = IntegratorData::new(integrator).expect("integrator data");
    let gpu_scene = GpuScene::upload(ctx, &scene_data).expect("upload");
    let gpu_integrator = GpuIntegrator::upload(ctx, integrator_data.clone());
    let opts = GpuRenderOptions {
        width: size,
        height: size,
        ..GpuRenderOptions::default()
    };
    let frame = raycaster
        .render(ctx, &gpu_scene, &gpu_integrator, camera, &opts)
        .expect("gpu render");
    let (twin, twin_stats) =
        tetray_gpu::twin::render(&scene_data, &integrator_data, camera, &opts).expect("twin");
    let cpu = render_scalar(
        scene,
        camera,
        integrator,
        &RenderOptions {
            width: size,
            height: size,
            ..RenderOptions::default()
        },
    )
    .expect("cpu render");
    Renders {
        gpu: frame.image,
        gpu_stats: frame.stats,
        twin,
        twin_stats,
        cpu: cpu.image,
        cpu_stats: cpu.stats,
    }
}

/// Largest per-channel difference and the number of pixels differing by
/// more than `threshold`.
pub fn difference(a: &Image, b: &Image, threshold: f32) -> (f32, usize) {
    let mut worst = 0.0f32;
    let mut count = 0;
    for (p, q) in a.rgba.iter().zip(&b.rgba) {
        let d = (0..4).map(|c| (p[c] - q[c]).abs()).fold(0.0, f32::max);
        worst = worst.max(d);
        count += usize::from(d > threshold);
    }
    (worst, count)
}

/// Writes actual / expected / difference EXRs for a failed comparison.
pub fn write_failure(test: &str, actual: &Image, expected: &Image) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../target/test-output")
        .join(test);
    std::fs::create_dir_all(&dir).expect("output folder");
    let diff: Vec<[f32; 4]> = actual
        .rgba
        .iter()
        .zip(&expected.rgba)
        .map(|(a, b)| std::array::from_fn(|c| (a[c] - b[c]).abs()))
        .collect();
    let diff = Image::from_pixels(actual.width, actual.height, diff).expect("image");
    actual.write_exr(&dir.join("actual.exr")).expect("write");
    expected
        .write_exr(&dir.join("expected.exr"))
        .expect("write");
    diff.write_exr(&dir.join("difference.exr")).expect("write");
    dir
}

/// Asserts `actual` is within `max_diff` of `expected` everywhere except at
/// most `budget` pixels (which may differ by anything up to `outlier`).
pub fn assert_close(
    test: &str,
    actual: &Image,
    expected: &Image,
    max_diff: f32,
    budget: usize,
    outlier: f32,
) {
    let (worst, over) = difference(actual, expected, max_diff);
    eprintln!("{test}: max {worst:.2e}, {over} pixels over {max_diff:.0e}");
    if over > budget || worst > outlier {
        let dir = write_failure(test, actual, expected);
        panic!(
            "{test}: {over} pixels differ by more than {max_diff} (budget {budget}), \
             max {worst} (limit {outlier}); images in {}",
            dir.display()
        );
    }
}
