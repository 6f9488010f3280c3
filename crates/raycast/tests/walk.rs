//! The walk against geometry: with the `LengthAndScalar` integrator a pixel
//! holds the length of its ray inside the mesh and the integral of the
//! scalar along it, both known in closed form for boxes.

mod support;

use glam::Vec3;
use support::{LengthAndScalar, box_chord, box_interval, linear_integral, scene};
use tetray_core::Camera;
use tetray_mesh::synthetic::{
    CellSplit, ScalarSpec, add_field, box_grid, hollow_box, jittered_box, two_boxes,
};
use tetray_raycast::{RenderOptions, RenderStats, render_cpu, trace_pixel};
use tetray_scene::Scene;

const SIZE: u32 = 24;

/// Lengths are differences of f32 crossing distances (|t| < 5 here, ulp
/// 5e-7) summed over at most ~30 segments, against an f64 chord from the
/// same f32 ray: 1e-5 leaves a 5x margin.
const LENGTH_TOL: f64 = 1e-5;

/// Views from several directions, perspective and orthographic, framing
/// the bounds as VTK's ResetCamera does.
fn views(lo: Vec3, hi: Vec3) -> Vec<Camera> {
    let mut cameras = Vec::new();
    for (az, el) in [
        (0.0, 0.0),
        (30.0, 20.0),
        (-55.0, 35.0),
        (120.0, -40.0),
        (200.0, 75.0),
    ] {
        for ortho in [false, true] {
            let mut c = Camera::reset_to_bounds(lo, hi).unwrap();
            c.azimuth(az).unwrap();
            c.elevation(el).unwrap();
            c.orthogonalize_view_up().unwrap();
            if ortho {
                c.parallel_scale = Some(0.5 * (hi - lo).length() * 1.1);
            }
            cameras.push(c);
        }
    }
    cameras
}

fn options() -> RenderOptions {
    RenderOptions {
        width: SIZE,
        height: SIZE,
        ..RenderOptions::default()
    }
}

fn assert_clean(stats: &RenderStats, what: &str) {
    assert_eq!(stats.counters.walk_failures, 0, "{what}: walk failures");
    assert_eq!(
        stats.counters.steps_bound_hits, 0,
        "{what}: step bound hits"
    );
    assert_eq!(stats.counters.rays, u64::from(SIZE * SIZE), "{what}");
}

/// Renders every view and checks each pixel's length against `chord`.
fn check_lengths(
    scene: &Scene,
    lo: Vec3,
    hi: Vec3,
    chord: impl Fn(&tetray_core::watertight::RayFrame) -> f64,
) {
    for (v, camera) in views(lo, hi).iter().enumerate() {
        let out = render_cpu(scene, camera, &LengthAndScalar, &options()).unwrap();
        assert_clean(&out.stats, &format!("view {v}"));
        assert!(out.stats.counters.rays_hit > 0, "view {v} misses the mesh");
        for py in 0..SIZE {
            for px in 0..SIZE {
                let ray = camera.ray(px, py, SIZE, SIZE).unwrap();
                let want = chord(&ray);
                let got = f64::from(out.image.pixel(px, py).unwrap()[0]);
                assert!(
                    (got - want).abs() <= LENGTH_TOL,
                    "view {v} pixel ({px}, {py}): length {got}, chord {want}"
                );
            }
        }
    }
}

fn unit_box() -> (Vec3, Vec3) {
    (Vec3::new(-0.5, -0.25, 0.0), Vec3::new(0.5, 0.75, 0.8))
}

#[test]
fn structured_boxes_give_exact_chords() {
    let (lo, hi) = unit_box();
    for split in [CellSplit::Five, CellSplit::Six] {
        let mut mesh = box_grid(lo, hi, [3, 4, 2], split).unwrap();
        add_field(&mut mesh, "c", ScalarSpec::Constant(1.0));
        let scene = scene(mesh, "c");
        check_lengths(&scene, lo, hi, |ray| box_chord(ray, lo, hi));
    }
}

#[test]
fn irregular_box_gives_exact_chords() {
    let (lo, hi) = unit_box();
    let mut mesh = jittered_box(lo, hi, [4, 3, 3], 0.2, 7, CellSplit::Five).unwrap();
    add_field(&mut mesh, "c", ScalarSpec::Constant(1.0));
    let scene = scene(mesh, "c");
    check_lengths(&scene, lo, hi, |ray| box_chord(ray, lo, hi));
}

#[test]
fn hollow_box_subtracts_the_hole() {
    let (lo, hi) = (Vec3::splat(-0.5), Vec3::splat(0.5));
    let (hole_lo, hole_hi) = (Vec3::splat(-0.25), Vec3::splat(0.25));
    let mut mesh = hollow_box(lo, hi, [4, 4, 4], [1, 1, 1], [3, 3, 3], CellSplit::Five).unwrap();
    add_field(&mut mesh, "c", ScalarSpec::Constant(1.0));
    let scene = scene(mesh, "c");
    check_lengths(&scene, lo, hi, |ray| {
        box_chord(ray, lo, hi) - box_chord(ray, hole_lo, hole_hi)
    });
}

#[test]
fn two_boxes_add_their_chords() {
    let a = (Vec3::new(-1.0, -0.5, -0.5), Vec3::new(-0.2, 0.5, 0.5));
    let b = (Vec3::new(0.3, -0.3, -0.4), Vec3::new(1.0, 0.6, 0.2));
    let mut mesh = two_boxes((a.0, a.1, [2, 3, 2]), (b.0, b.1, [3, 2, 2]), CellSplit::Six).unwrap();
    add_field(&mut mesh, "c", ScalarSpec::Constant(1.0));
    let scene = scene(mesh, "c");
    let (lo, hi) = (a.0.min(b.0), a.1.max(b.1));
    check_lengths(&scene, lo, hi, |ray| {
        box_chord(ray, a.0, a.1) + box_chord(ray, b.0, b.1)
    });
}

#[test]
fn linear_scalar_integrates_exactly_on_an_irregular_mesh() {
    let (lo, hi) = unit_box();
    let (offset, gradient) = (0.3f32, Vec3::new(0.7, -1.1, 0.4));
    let mut mesh = jittered_box(lo, hi, [4, 4, 3], 0.2, 11, CellSplit::Five).unwrap();
    add_field(&mut mesh, "lin", ScalarSpec::Linear { offset, gradient });
    let scene = scene(mesh, "lin");
    for (v, camera) in views(lo, hi).iter().enumerate() {
        let out = render_cpu(&scene, camera, &LengthAndScalar, &options()).unwrap();
        assert_clean(&out.stats, &format!("view {v}"));
        for py in 0..SIZE {
            for px in 0..SIZE {
                let ray = camera.ray(px, py, SIZE, SIZE).unwrap();
                let want = box_interval(&ray, lo, hi).map_or(0.0, |(t0, t1)| {
                    linear_integral(&ray, f64::from(offset), gradient.as_dvec3(), t0, t1)
                });
                let got = f64::from(out.image.pixel(px, py).unwrap()[1]);
                // Scalars are f32 at the points (|s| < 2) and interpolated at
                // crossings in f64: ~1e-7 relative per segment, plus the
                // length error above times |s|.
                assert!(
                    (got - want).abs() <= 3.0 * LENGTH_TOL,
                    "view {v} pixel ({px}, {py}): integral {got}, closed form {want}"
                );
            }
        }
    }
}

#[test]
fn eye_inside_the_mesh_integrates_from_the_eye() {
    // Perspective eyes inside the box and inside the hole of a hollow box;
    // an orthographic view plane cutting through the box.
    let (lo, hi) = (Vec3::splat(-0.5), Vec3::splat(0.5));
    let (hole_lo, hole_hi) = (Vec3::splat(-0.25), Vec3::splat(0.25));
    let mut mesh = hollow_box(lo, hi, [4, 4, 4], [1, 1, 1], [3, 3, 3], CellSplit::Five).unwrap();
    add_field(&mut mesh, "c", ScalarSpec::Constant(1.0));
    let scene = scene(mesh, "c");
    let eyes = [
        Vec3::new(0.05, 0.02, 0.0),
        Vec3::new(0.35, -0.4, 0.3),
        Vec3::new(-0.38, 0.15, 0.1),
    ];
    for (e, eye) in eyes.into_iter().enumerate() {
        for ortho in [false, true] {
            let camera = Camera {
                position: eye,
                focal_point: eye + Vec3::new(0.3, -0.2, -1.0),
                view_up: Vec3::Y,
                view_angle: 100.0,
                parallel_scale: ortho.then_some(0.4),
            };
            let out = render_cpu(&scene, &camera, &LengthAndScalar, &options()).unwrap();
            assert_clean(&out.stats, &format!("eye {e}"));
            assert!(out.stats.eye_inside_bounds);
            for py in 0..SIZE {
                for px in 0..SIZE {
                    let ray = camera.ray(px, py, SIZE, SIZE).unwrap();
                    let want = box_chord(&ray, lo, hi) - box_chord(&ray, hole_lo, hole_hi);
                    let got = f64::from(out.image.pixel(px, py).unwrap()[0]);
                    assert!(
                        (got - want).abs() <= LENGTH_TOL,
                        "eye {e} ortho {ortho} pixel ({px}, {py}): length {got}, chord {want}"
                    );
                }
            }
        }
    }
}

#[test]
fn step_bound_stops_rays_and_is_counted() {
    let (lo, hi) = unit_box();
    let mut mesh = box_grid(lo, hi, [4, 4, 4], CellSplit::Five).unwrap();
    add_field(&mut mesh, "c", ScalarSpec::Constant(1.0));
    let scene = scene(mesh, "c");
    let camera = Camera::reset_to_bounds(lo, hi).unwrap();
    let opts = RenderOptions {
        max_steps_per_ray: Some(2),
        ..options()
    };
    let out = render_cpu(&scene, &camera, &LengthAndScalar, &opts).unwrap();
    // Every ray through the middle crosses at least 4 cells of 5 tets.
    assert!(out.stats.counters.steps_bound_hits > 0);
    assert_eq!(
        out.stats.counters.steps_bound_hits,
        out.stats.counters.rays_hit
    );
    let full = render_cpu(&scene, &camera, &LengthAndScalar, &options()).unwrap();
    assert_eq!(full.stats.counters.steps_bound_hits, 0);
    assert!(full.stats.counters.segments > out.stats.counters.segments);
    // The middle pixel's ray, alone: its steps count the one refused past
    // the bound; without the bound, every step it takes.
    let middle = |opts: &RenderOptions| {
        let (w, h) = (opts.width / 2, opts.height / 2);
        trace_pixel(&scene, &camera, &LengthAndScalar, opts, w, h)
            .unwrap()
            .1
    };
    let bounded = middle(&opts);
    assert!(bounded.step_bound_hit);
    // (A step through an edge has a segment of no length, not counted.)
    assert_eq!(bounded.steps, 3);
    assert!((1..=2).contains(&bounded.segments), "{bounded:?}");
    let whole = middle(&options());
    assert!(!whole.step_bound_hit);
    assert!(
        whole.steps > 3 && whole.steps >= whole.segments,
        "{whole:?}"
    );
}

#[test]
fn progress_reaches_every_row_and_threads_do_not_change_pixels() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let (lo, hi) = unit_box();
    let mut mesh = jittered_box(lo, hi, [3, 3, 3], 0.2, 5, CellSplit::Six).unwrap();
    add_field(
        &mut mesh,
        "lin",
        ScalarSpec::Linear {
            offset: 1.0,
            gradient: Vec3::ONE,
        },
    );
    let scene = scene(mesh, "lin");
    let camera = views(lo, hi)[2];
    let opts = RenderOptions {
        width: 40,
        height: 37,
        ..RenderOptions::default()
    };
    let calls = AtomicUsize::new(0);
    let last = AtomicUsize::new(0);
    let progress = |done: usize, total: usize| {
        assert_eq!(total, 37);
        calls.fetch_add(1, Ordering::Relaxed);
        last.fetch_max(done, Ordering::Relaxed);
    };
    let out = tetray_raycast::render_cpu_with_progress(
        &scene,
        &camera,
        &LengthAndScalar,
        &opts,
        Some(&progress),
    )
    .unwrap();
    assert_eq!(last.load(Ordering::Relaxed), 37);
    assert!(calls.load(Ordering::Relaxed) >= 2);
    assert_eq!(out.image.rgba.len(), 40 * 37);
    // Each pixel is computed alone: any thread count gives the same bits.
    for threads in [1, 3] {
        let other = render_cpu(
            &scene,
            &camera,
            &LengthAndScalar,
            &RenderOptions {
                threads: Some(threads),
                ..opts
            },
        )
        .unwrap();
        assert_eq!(other.image, out.image);
        assert_eq!(other.stats.counters.segments, out.stats.counters.segments);
    }
}
