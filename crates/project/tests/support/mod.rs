//! Shared helpers of the projection tests: the adapter (required in CI),
//! scenes with smooth fields, transfer functions, the projection through
//! the GPU and the twin with the same draws, and image comparison with
//! failure images.

#![allow(dead_code)]

use std::path::PathBuf;
use std::sync::OnceLock;

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_core::{Camera, Image};
use tetray_gpu::{GpuContext, GpuIntegrator, IntegratorData};
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityMode, OpacityPoint, ScalarIntegrator,
    TransferFunction,
};
use tetray_mesh::synthetic::{CellSplit, jittered_box};
use tetray_mesh::{ScalarField, TetMesh, Topology};
use tetray_project::{
    GpuProjectScene, GpuProjector, ProjectScene, SortKind, TetIntervals, View,
    layout::knot_scalars, plan, samples_adaptively, twin,
};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;

/// The adapter, shared by a test binary. `None` (with a loud message) when
/// there is none, unless `TETRAY_REQUIRE_GPU=1` (CI), where that fails.
pub fn gpu() -> Option<&'static (GpuContext, GpuProjector)> {
    static GPU: OnceLock<Option<(GpuContext, GpuProjector)>> = OnceLock::new();
    GPU.get_or_init(|| match GpuContext::new() {
        Ok(ctx) => {
            let projector = GpuProjector::new(&ctx).expect("the pipeline compiles");
            eprintln!(
                "projection tests on {} into {:?}",
                ctx.adapter_name(),
                projector.format()
            );
            Some((ctx, projector))
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

/// A smooth, non-linear field over the mesh points.
pub fn add_smooth_field(mesh: &mut TetMesh, name: &str) {
    let values = mesh
        .points
        .iter()
        .map(|p| 0.5 + 0.3 * (2.1 * p.x).sin() * (1.7 * p.y).cos() + 0.2 * p.z * p.z)
        .collect();
    mesh.fields.push(ScalarField {
        name: name.to_string(),
        values,
    });
}

/// A convex, irregular tetrahedralization of [-1, 1]^3 with a smooth field.
pub fn convex_box(cells: u32) -> Scene {
    let mut mesh = jittered_box(
        Vec3::splat(-1.0),
        Vec3::splat(1.0),
        [cells; 3],
        0.2,
        7,
        CellSplit::Five,
    )
    .expect("box");
    add_smooth_field(&mut mesh, "smooth");
    scene(mesh, "smooth")
}

/// A camera off every axis, perspective or orthographic.
pub fn camera(scene: &Scene, orthographic: bool) -> Camera {
    let (lo, hi) = scene.bounds();
    let mut camera = Camera {
        parallel_scale: orthographic.then_some(1.0),
        ..Camera::default()
    };
    camera.reset(lo, hi, 1.0).expect("reset");
    camera.azimuth(33.0).expect("azimuth");
    camera.elevation(21.0).expect("elevation");
    camera.orthogonalize_view_up().expect("up");
    camera
}

fn point(scalar: f32, rgb: [f32; 3]) -> ColorPoint {
    ColorPoint {
        scalar,
        rgb: Vec3::from_array(rgb),
    }
}

/// Colour and opacity with interior knots over [lo, hi].
pub fn knotted_tf(lo: f32, hi: f32) -> TransferFunction {
    let at = |t: f32| lo + (hi - lo) * t;
    TransferFunction::new(
        vec![
            point(at(0.0), [0.1, 0.2, 0.9]),
            point(at(0.45), [0.9, 0.9, 0.3]),
            point(at(1.0), [1.0, 0.1, 0.1]),
        ],
        vec![
            OpacityPoint {
                scalar: at(0.0),
                alpha: 0.05,
            },
            OpacityPoint {
                scalar: at(0.6),
                alpha: 0.6,
            },
            OpacityPoint {
                scalar: at(1.0),
                alpha: 0.2,
            },
        ],
    )
    .expect("tf")
}

/// An isosurface-like spike: transparent except for a narrow opacity peak
/// at `centre` (dissertation figure 4.1).
pub fn spike_tf(lo: f32, hi: f32, centre: f32, half_width: f32) -> TransferFunction {
    let opacity = |scalar, alpha| OpacityPoint { scalar, alpha };
    TransferFunction::new(
        vec![point(lo, [0.2, 0.4, 1.0]), point(hi, [1.0, 0.8, 0.2])],
        vec![
            opacity(lo, 0.0),
            opacity(centre - half_width, 0.0),
            opacity(centre, 0.95),
            opacity(centre + half_width, 0.0),
            opacity(hi, 0.0),
        ],
    )
    .expect("tf")
}

pub fn integrator(method: Method, tf: &TransferFunction, unit_distance: f32) -> ScalarIntegrator {
    ScalarIntegrator::new(
        method,
        tf,
        &IntegratorOptions {
            unit_distance,
            opacity_mode: OpacityMode::Exact,
            ..IntegratorOptions::default()
        },
    )
    .expect("integrator")
}

/// The CPU reference ray caster.
pub fn raycast(scene: &Scene, integrator: &ScalarIntegrator, camera: &Camera, size: u32) -> Image {
    render_scalar(
        scene,
        camera,
        integrator,
        &RenderOptions {
            width: size,
            height: size,
            ..RenderOptions::default()
        },
    )
    .expect("ray cast")
    .image
}

/// One view's draws, for the GPU and the twin alike.
pub struct Prepared {
    pub project: ProjectScene,
    pub data: IntegratorData,
    pub view: View,
    pub draws: Vec<[u32; 2]>,
    pub tets: usize,
}

pub fn prepare(
    scene: &Scene,
    integrator: &ScalarIntegrator,
    camera: &Camera,
    size: u32,
    sort: SortKind,
    adaptive: bool,
) -> Prepared {
    let project = ProjectScene::new(scene).expect("project scene");
    let data = IntegratorData::new(integrator).expect("integrator data");
    let intervals = TetIntervals::new(&project, &knot_scalars(&data));
    let view = View::new(camera, size, size).expect("view");
    let use_intervals = (adaptive && samples_adaptively(&data)).then_some(&intervals);
    let planned = plan(&project, use_intervals, &view, sort);
    Prepared {
        project,
        data,
        view,
        draws: planned.draws,
        tets: planned.tets,
    }
}

/// The twin's image and segment count.
pub fn twin(prepared: &Prepared) -> (Image, u64) {
    twin::render(
        &prepared.project,
        &prepared.data,
        &prepared.view,
        &prepared.draws,
    )
    .expect("twin")
}

/// The GPU's image and segment count.
pub fn project_gpu(gpu: &(GpuContext, GpuProjector), prepared: &Prepared) -> (Image, u64) {
    let (ctx, projector) = gpu;
    let scene = GpuProjectScene::upload(ctx, &prepared.project).expect("upload");
    let integrator = GpuIntegrator::upload(ctx, prepared.data.clone());
    let (image, stats) = projector
        .draw(ctx, &scene, &integrator, &prepared.view, &prepared.draws)
        .expect("draw");
    (image, stats.segments)
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

/// Mean over pixels of the largest channel difference.
pub fn mean_difference(a: &Image, b: &Image) -> f64 {
    let sum: f64 = a
        .rgba
        .iter()
        .zip(&b.rgba)
        .map(|(p, q)| f64::from((0..4).map(|c| (p[c] - q[c]).abs()).fold(0.0, f32::max)))
        .sum();
    sum / a.rgba.len().max(1) as f64
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
    for (name, image) in [
        ("actual", actual),
        ("expected", expected),
        ("difference", &diff),
    ] {
        image
            .write_png(&dir.join(format!("{name}.png")), Vec3::ZERO)
            .expect("write");
    }
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
) -> (f32, usize) {
    let (worst, over) = difference(actual, expected, max_diff);
    eprintln!("{test}: max difference {worst:e}, {over} pixels above {max_diff:e}");
    if over > budget || worst > outlier {
        let dir = write_failure(test, actual, expected);
        panic!(
            "{test}: {over} pixels differ by more than {max_diff} (budget {budget}), \
             max {worst} (limit {outlier}); images in {}",
            dir.display()
        );
    }
    (worst, over)
}

/// Pixels with any opacity.
pub fn covered(image: &Image) -> usize {
    image.rgba.iter().filter(|p| p[3] > 0.0).count()
}
