//! The GPU ray caster against its CPU twin and against the f64 reference ray
//! caster (tetray_raycast, itself checked against closed forms), per
//! integrator, on closed-form scenes, rays through edges and vertices, and
//! the three PLOT3D datasets.
//!
//! Tolerances (per channel, premultiplied RGBA):
//! - GPU vs twin, 5e-6: the same f32 operations in the same order; only
//!   the device's arithmetic differs (fused multiply-adds the driver may
//!   form, its exp / log / sqrt within a few ulp), over up to ~100
//!   segments per ray. Measured: at most 1.3e-6.
//! - GPU vs reference, 3e-5: the reference interpolates crossing distances
//!   and scalars in f64 and the exact method is f64 inside; f32 rounding of
//!   segment lengths (~1e-7 relative) and of the methods' arithmetic
//!   accumulates along the ray. Measured: at most 5e-6 on the scenes,
//!   3e-5 on the datasets.
//! - Pixels allowed beyond: none, on the synthetic scenes and the datasets
//!   alike (measured on the datasets at 40 x 40: at most 2.3e-5 on every
//!   pixel, every method). The walks are also required to take the same
//!   steps, hits and entries, so a grazing ray that one side counted and
//!   the other missed would fail the test rather than hide in a budget.

mod support;

use glam::Vec3;
use support::{assert_close, gpu, render_all, scene};
use tetray_core::Camera;
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityMode, OpacityPoint, ScalarIntegrator,
    TransferFunction,
};
use tetray_mesh::synthetic::{
    CellSplit, ScalarSpec, add_field, box_grid, hollow_box, jittered_box, two_boxes,
};
use tetray_scene::Scene;

/// Every method the GPU kernel has.
const GPU_METHODS: [Method; 8] = [
    Method::Ppi,
    Method::Exact,
    Method::Average,
    Method::AverageOpacity,
    Method::LinAvgOpacity,
    Method::LinOpacity,
    Method::Preintegrated,
    Method::Riemann,
];

fn options(unit_distance: f32) -> IntegratorOptions {
    IntegratorOptions {
        unit_distance,
        opacity_mode: OpacityMode::Exact,
        riemann_step: 0.02,
        preintegration_length: 0.1,
        ..IntegratorOptions::default()
    }
}

/// A transfer function with interior knots in colour and opacity.
fn knotted_tf(lo: f32, hi: f32) -> TransferFunction {
    let at = |t: f32| lo + (hi - lo) * t;
    TransferFunction::new(
        vec![
            ColorPoint {
                scalar: at(0.0),
                rgb: Vec3::new(0.1, 0.2, 0.9),
            },
            ColorPoint {
                scalar: at(0.45),
                rgb: Vec3::new(0.9, 0.9, 0.3),
            },
            ColorPoint {
                scalar: at(1.0),
                rgb: Vec3::new(1.0, 0.1, 0.1),
            },
        ],
        vec![
            OpacityPoint {
                scalar: at(0.0),
                alpha: 0.1,
            },
            OpacityPoint {
                scalar: at(0.6),
                alpha: 0.9,
            },
            OpacityPoint {
                scalar: at(1.0),
                alpha: 0.3,
            },
        ],
    )
    .expect("valid transfer function")
}

fn view(lo: Vec3, hi: Vec3, azimuth: f32, elevation: f32) -> Camera {
    let mut camera = Camera::reset_to_bounds(lo, hi).expect("camera");
    camera.azimuth(azimuth).expect("azimuth");
    camera.elevation(elevation).expect("elevation");
    camera.orthogonalize_view_up().expect("view up");
    camera
}

/// Renders every GPU method and compares every pixel with the twin and
/// the reference (tolerances above).
fn check_methods(
    test: &str,
    scene: &Scene,
    tf: &TransferFunction,
    unit: f32,
    camera: &Camera,
    size: u32,
) {
    let Some(gpu) = gpu() else { return };
    for method in GPU_METHODS {
        let integrator = ScalarIntegrator::new(method, tf, &options(unit)).expect("integrator");
        let r = render_all(gpu, scene, &integrator, camera, size);
        let name = format!("{test}-{method}");
        assert_close(&format!("{name}-twin"), &r.gpu, &r.twin, 5e-6, 0, 5e-6);
        assert_close(&format!("{name}-reference"), &r.gpu, &r.cpu, 3e-5, 0, 3e-5);
        assert_eq!(
            r.gpu_stats.counters.steps_bound_hits, 0,
            "{name}: step bound"
        );
        assert_eq!(
            r.gpu_stats.counters.walk_failures, 0,
            "{name}: walk failures"
        );
        assert_eq!(
            r.gpu_stats.counters.rays_hit, r.cpu_stats.counters.rays_hit,
            "{name}: rays hit"
        );
        assert_eq!(
            r.gpu_stats.counters.steps, r.cpu_stats.counters.steps,
            "{name}: tetrahedra visited"
        );
        assert_eq!(
            r.gpu_stats.counters.entries, r.cpu_stats.counters.entries,
            "{name}: entries"
        );
        assert_eq!(
            r.gpu_stats.counters.segments, r.twin_stats[1],
            "{name}: segments vs twin"
        );
    }
}

/// Length of the ray `origin + t dir` (t >= 0) inside the box `[lo, hi]`,
/// by slab intersection.
fn slab_chord(origin: glam::DVec3, dir: glam::DVec3, lo: Vec3, hi: Vec3) -> f64 {
    let dir = dir.normalize();
    let (mut near, mut far) = (0.0f64, f64::INFINITY);
    for axis in 0..3 {
        let (o, d) = (origin[axis], dir[axis]);
        let (a, b) = (f64::from(lo[axis]), f64::from(hi[axis]));
        if d == 0.0 {
            if o < a || o > b {
                return 0.0;
            }
            continue;
        }
        let (t0, t1) = ((a - o) / d, (b - o) / d);
        near = near.max(t0.min(t1));
        far = far.min(t0.max(t1));
    }
    (far - near).max(0.0)
}

#[test]
fn constant_field_boxes_match_beer_lambert() {
    let Some(gpu) = gpu() else { return };
    let (lo, hi) = (Vec3::ZERO, Vec3::new(1.0, 0.8, 1.2));
    let mut mesh = box_grid(lo, hi, [4, 3, 5], CellSplit::Five).expect("box");
    add_field(&mut mesh, "s", ScalarSpec::Constant(0.5));
    let scene = scene(mesh, "s");
    let lum = Vec3::new(0.9, 0.5, 0.2);
    let alpha = 0.4f32;
    let tf = TransferFunction::new(
        vec![ColorPoint {
            scalar: 0.5,
            rgb: lum,
        }],
        vec![OpacityPoint { scalar: 0.5, alpha }],
    )
    .expect("tf");
    let unit = 0.5;
    let tau = -(1.0 - alpha).ln() / unit;
    let camera = view(lo, hi, 35.0, 25.0);
    let integrator = ScalarIntegrator::new(Method::Ppi, &tf, &options(unit)).expect("ppi");
    let size = 48;
    let r = render_all(gpu, &scene, &integrator, &camera, size);
    // Beer-Lambert with the chord of each pixel's ray through the box,
    // computed here from the camera and the box alone (slab intersection
    // in f64): colour = L (1 - T), alpha = 1 - T, T = exp(-tau chord).
    // Tolerance 2e-5: the renderer's crossing points are f32 (a relative
    // 1e-7 of the ~2-unit chords, 4 cells deep) and its exp / log are
    // within a few ulp; the slab chord is exact to f64.
    let rays = camera.pixel_rays(size, size).expect("rays");
    let mut crossed = 0;
    for (i, g) in r.gpu.rgba.iter().enumerate() {
        let ray = rays.ray(i as u32 % size, i as u32 / size);
        let chord = slab_chord(ray.origin.as_dvec3(), ray.dir.as_dvec3(), lo, hi);
        crossed += usize::from(chord > 0.0);
        let t_exact = (-f64::from(tau) * chord).exp();
        for ch in 0..3 {
            let want = f64::from(lum[ch]) * (1.0 - t_exact);
            assert!(
                (f64::from(g[ch]) - want).abs() < 2e-5,
                "pixel {i}: {g:?} vs {want} (chord {chord})"
            );
        }
        assert!(
            (f64::from(g[3]) - (1.0 - t_exact)).abs() < 2e-5,
            "pixel {i} alpha: {g:?} vs {} (chord {chord})",
            1.0 - t_exact
        );
    }
    // The box fills a good part of the view: the check is not vacuous.
    assert!(crossed > (size * size / 4) as usize, "{crossed} rays hit");
    check_methods("constant-box", &scene, &tf, unit, &camera, 40);
}

#[test]
fn nonconvex_scenes_reenter_like_the_reference() {
    let (lo, hi) = (Vec3::new(-1.0, -1.0, -1.0), Vec3::ONE);
    let mut hollow =
        hollow_box(lo, hi, [5, 5, 5], [1, 1, 1], [4, 4, 4], CellSplit::Five).expect("hollow");
    add_field(
        &mut hollow,
        "s",
        ScalarSpec::Linear {
            offset: 0.5,
            gradient: Vec3::new(0.2, -0.1, 0.15),
        },
    );
    let tf = knotted_tf(0.0, 1.0);
    let camera = view(lo, hi, 20.0, 30.0);
    check_methods("hollow-box", &scene(hollow, "s"), &tf, 0.4, &camera, 40);

    let mut boxes = two_boxes(
        (Vec3::ZERO, Vec3::ONE, [3, 3, 3]),
        (
            Vec3::new(1.6, 0.3, 0.0),
            Vec3::new(2.6, 1.3, 1.0),
            [3, 3, 3],
        ),
        CellSplit::Six,
    )
    .expect("two boxes");
    add_field(
        &mut boxes,
        "s",
        ScalarSpec::Linear {
            offset: 0.3,
            gradient: Vec3::new(0.2, 0.1, 0.1),
        },
    );
    let camera = view(Vec3::ZERO, Vec3::new(2.6, 1.3, 1.0), 0.0, 10.0);
    check_methods("two-boxes", &scene(boxes, "s"), &tf, 0.4, &camera, 40);
}

#[test]
fn linear_field_on_an_irregular_mesh() {
    let (lo, hi) = (Vec3::ZERO, Vec3::new(1.0, 1.2, 0.8));
    let mut mesh = jittered_box(lo, hi, [6, 5, 4], 0.2, 7, CellSplit::Five).expect("mesh");
    add_field(
        &mut mesh,
        "s",
        ScalarSpec::Linear {
            offset: 0.1,
            gradient: Vec3::new(0.5, 0.3, -0.2),
        },
    );
    let tf = knotted_tf(-0.2, 1.0);
    check_methods(
        "jittered",
        &scene(mesh, "s"),
        &tf,
        0.2,
        &view(lo, hi, 25.0, 15.0),
        48,
    );
}

#[test]
fn axis_aligned_rays_through_edges_and_vertices() {
    let Some(gpu) = gpu() else { return };
    // Orthographic views along the axes of structured grids whose vertices
    // fall on pixel centres: rays run exactly through vertices, along edges
    // and in face planes. Not one pixel may deviate.
    let (lo, hi) = (Vec3::ZERO, Vec3::splat(2.0));
    for split in [CellSplit::Five, CellSplit::Six] {
        let mut mesh = box_grid(lo, hi, [4, 4, 4], split).expect("grid");
        add_field(
            &mut mesh,
            "s",
            ScalarSpec::Linear {
                offset: 0.2,
                gradient: Vec3::new(0.1, 0.2, 0.3),
            },
        );
        let scene = scene(mesh, "s");
        let tf = knotted_tf(0.0, 1.5);
        let integrator = ScalarIntegrator::new(Method::Ppi, &tf, &options(0.5)).expect("ppi");
        for (direction, up) in [(Vec3::X, Vec3::Y), (Vec3::Y, Vec3::Z), (Vec3::Z, Vec3::X)] {
            let mut camera = Camera::reset_to_bounds(lo, hi).expect("camera");
            camera.focal_point = Vec3::splat(1.0);
            camera.position = Vec3::splat(1.0) - 5.0 * direction;
            camera.view_up = up;
            // 32 pixels over 4 world units: pixel centres at odd multiples
            // of 1/16 from the centre, cell edges every 8 pixels... and a
            // half-pixel shift puts centres exactly on the grid lines.
            camera.parallel_scale = Some(2.0);
            let r = render_all(gpu, &scene, &integrator, &camera, 33);
            let name = format!("axis-{split:?}-{direction:?}");
            assert_close(&format!("{name}-reference"), &r.gpu, &r.cpu, 1e-5, 0, 1e-5);
            assert_close(&format!("{name}-twin"), &r.gpu, &r.twin, 5e-6, 0, 5e-6);
            assert_eq!(
                r.gpu_stats.counters.steps_bound_hits + r.gpu_stats.counters.walk_failures,
                0,
                "{name}"
            );
            assert_eq!(
                r.gpu_stats.counters.steps, r.cpu_stats.counters.steps,
                "{name}"
            );
        }
    }
}

#[test]
fn camera_inside_the_mesh_and_early_termination() {
    let Some(gpu) = gpu() else { return };
    let (lo, hi) = (Vec3::ZERO, Vec3::new(2.0, 2.0, 2.0));
    let mut mesh = jittered_box(lo, hi, [5, 5, 5], 0.15, 3, CellSplit::Six).expect("mesh");
    add_field(
        &mut mesh,
        "s",
        ScalarSpec::Linear {
            offset: 0.2,
            gradient: Vec3::new(0.1, 0.2, 0.1),
        },
    );
    let scene = scene(mesh, "s");
    let tf = knotted_tf(0.0, 1.2);
    let integrator = ScalarIntegrator::new(Method::Ppi, &tf, &options(0.3)).expect("ppi");
    let mut inside = Camera::reset_to_bounds(lo, hi).expect("camera");
    inside.position = Vec3::new(1.0, 0.9, 1.1);
    inside.focal_point = Vec3::new(2.0, 1.5, 1.0);
    let r = render_all(gpu, &scene, &integrator, &inside, 40);
    assert!(
        r.gpu.rgba.iter().all(|p| p[3] > 0.0),
        "every ray starts in the mesh"
    );
    assert_close("inside-reference", &r.gpu, &r.cpu, 3e-5, 0, 3e-5);
    assert_close("inside-twin", &r.gpu, &r.twin, 5e-6, 0, 5e-6);

    // Early termination: both stop once opacity reaches 0.5.
    let (ctx, raycaster) = gpu;
    let camera = view(lo, hi, 30.0, 20.0);
    let data = tetray_gpu::SceneData::new(&scene).expect("data");
    let upload = tetray_gpu::GpuScene::upload(ctx, &data).expect("upload");
    let gpu_integrator = tetray_gpu::GpuIntegrator::new(ctx, &integrator).expect("integrator");
    let stopped = raycaster
        .render(
            ctx,
            &upload,
            &gpu_integrator,
            &camera,
            &tetray_gpu::GpuRenderOptions {
                width: 40,
                height: 40,
                early_termination: 0.5,
                max_steps_per_ray: None,
            },
        )
        .expect("render");
    let cpu = tetray_raycast::render_scalar(
        &scene,
        &camera,
        &integrator,
        &tetray_raycast::RenderOptions {
            width: 40,
            height: 40,
            early_termination: 0.5,
            ..Default::default()
        },
    )
    .expect("cpu");
    assert_eq!(stopped.stats.counters.segments, cpu.stats.counters.segments);
    assert_close(
        "early-termination",
        &stopped.image,
        &cpu.image,
        3e-5,
        0,
        3e-5,
    );

    // The step bound stops rays and is counted, like the reference's.
    let bounded = raycaster
        .render(
            ctx,
            &upload,
            &gpu_integrator,
            &camera,
            &tetray_gpu::GpuRenderOptions {
                width: 40,
                height: 40,
                early_termination: 1.0,
                max_steps_per_ray: Some(3),
            },
        )
        .expect("render");
    assert!(bounded.stats.counters.steps_bound_hits > 0);
    assert!(bounded.stats.counters.steps <= 3 * 40 * 40 + bounded.stats.counters.steps_bound_hits);
}

#[test]
fn plot3d_datasets_match_the_reference() {
    if gpu().is_none() {
        return;
    }
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    for name in ["bluntfin", "post", "comb"] {
        let loaded = tetray_io::load(&data.join(format!("{name}xyz.bin")), &Default::default())
            .expect("dataset");
        let field = if name == "post" {
            "velocity_magnitude"
        } else {
            "density"
        };
        let values = &loaded.mesh.field(field).expect("field").values;
        let (lo_s, hi_s) = values
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let scene = Scene::from_loaded(loaded, field, Default::default()).expect("scene");
        let (lo, hi) = scene.bounds();
        let unit = (hi - lo).length() / (scene.tet_count() as f32).cbrt();
        let tf = knotted_tf(lo_s, hi_s);
        check_methods(name, &scene, &tf, unit, &view(lo, hi, 30.0, 20.0), 40);
    }
}

#[test]
fn kernel_exit_table_is_the_walks() {
    let walk = tetray_raycast::LEFT_OUT_SLOT.map(u32::from);
    assert_eq!(tetray_gpu::twin::LEFT_OUT_SLOT, walk);
    // And the WGSL constant holds the same numbers.
    let source = tetray_gpu::shaders::RAYCAST;
    let start = source
        .find("const LEFT_OUT_SLOT")
        .expect("table in the kernel");
    let body = &source[start..source[start..].find(");").expect("end") + start];
    let body = &body[body.find('(').expect("values") + 1..];
    let numbers: Vec<u32> = body
        .split(|c: char| !c.is_ascii_digit())
        .filter(|w| !w.is_empty())
        .map(|d| d.parse().expect("number"))
        .collect();
    assert_eq!(numbers, walk);
}
