//! The CPU ray caster with the real integrators (`ScalarIntegrator`) against
//! closed forms of the volume rendering integral, pixel by pixel, computed in
//! f64 from each pixel's own f32 ray:
//!
//! - constant material: Beer-Lambert (eq. 2.17), which every method
//!   integrates exactly, on convex and nonconvex meshes;
//! - a linear scalar with a linear transfer function in VTK opacity mode
//!   (`tau = alpha / u`): luminance and attenuation are linear along the
//!   whole chord of a convex box, one segment of eq. 2.19-2.20;
//! - a transfer function with interior knots: the chord cut where the
//!   scalar crosses a knot (adaptive transfer function sampling, section
//!   4.3), every piece linear, composited front to back (eq. 2.13);
//! - rays through grid vertices, along edges and in face planes;
//! - early ray termination.
//!
//! The walk's geometry alone is checked by `walk.rs` and
//! `degenerate_rays.rs`; this file checks what the integrators make of it.
//! On failure the actual, expected and difference images are written to
//! `target/test-output/<test>/`.

mod support;

use glam::Vec3;
use support::compare::{
    Expected, Worst, assert_matches, deviation, expected_image, views, write_images,
};
use support::optics::{
    LinearField, TfF64, beer_lambert, linear_field_light, luminance_variation, transfer_function,
};
use support::{box_chord, box_interval, scene};
use tetray_core::watertight::RayFrame;
use tetray_core::{Camera, Image};
use tetray_integrate::{
    IntegratorOptions, Method, OpacityMode, ScalarIntegrator, TransferFunction,
};
use tetray_mesh::synthetic::{
    CellSplit, ScalarSpec, add_field, box_grid, hollow_box, jittered_box, two_boxes,
};
use tetray_raycast::{RenderOptions, RenderOutput, RenderStats, render_scalar};
use tetray_scene::Scene;

/// Pixels per side of the oblique views.
const SIZE: u32 = 40;

/// Oblique view angles (azimuth, elevation), each seen in perspective and
/// orthographically.
const ANGLES: [(f32, f32); 3] = [(0.0, 0.0), (35.0, 25.0), (-120.0, -40.0)];

/// How far the length a ray integrates may be from the f64 chord of the
/// same f32 ray. Crossing distances come from f32 projections of the
/// vertices relative to the ray origin (a few ulp of |t| ~ 4, ~5e-7),
/// amplified at grazing crossings by 1 / sin of the angle between ray and
/// face. Measured: 3.3e-6 at most (a box face entered at 12 degrees);
/// walk.rs allows 1e-5.
const CHORD_ERROR: f64 = 5e-6;

/// Tolerance of every method on constant material and of the exact methods
/// (exact, reference) on linear material. The chord error moves a pixel by
/// `L tau exp(-tau chord) <= L tau` times `CHORD_ERROR`: `L tau` is at most
/// 0.64 for the constant material and 1.25 for the linear-field transfer
/// functions (6.3e-6). Each segment's light is rounded to f32 and
/// composited in f32, ~6e-8 per segment over at most ~40 segments.
/// Measured: 2.3e-6 at most.
const EXACT_TOL: f64 = 1e-5;

/// Bilinear error of the default Psi table (1024^2 nodes, quadratic gamma
/// spacing): measured 8.2e-7 at most on a 700^2 sample of `tau D` in
/// [0, 50]^2 off the nodes, against `psi::psi` in f64.
const PSI_TABLE_ERROR: f64 = 1.1e-6;

/// Partial pre-integration differs from the exact method only by the Psi
/// table: in eq. 5.5 Psi multiplies `L_b - L_f`, so a cell adds at most
/// `PSI_TABLE_ERROR` times the luminance change across it, attenuated by
/// what lies in front, and a ray at most `PSI_TABLE_ERROR` times the total
/// variation of its luminance (at most 1.5 for the transfer functions of
/// the linear-field tests: 1.7e-6), on top of `EXACT_TOL`'s rounding.
/// Measured: no larger than the exact method's error (2.3e-6; the walk's
/// rounding dominates) and within 2.4e-7 of the exact render, a difference
/// `check_split_methods` checks against the bound itself.
const PPI_TOL: f64 = 2e-5;

fn render_options(size: u32) -> RenderOptions {
    RenderOptions {
        width: size,
        height: size,
        ..RenderOptions::default()
    }
}

fn integrator(
    method: Method,
    tf: &TransferFunction,
    options: &IntegratorOptions,
) -> ScalarIntegrator {
    ScalarIntegrator::new(method, tf, options).unwrap()
}

/// The mesh was walked completely: every ray that met it finished its walk.
fn assert_clean(stats: &RenderStats, what: &str) {
    assert_eq!(stats.counters.walk_failures, 0, "{what}: walk failures");
    assert_eq!(
        stats.counters.steps_bound_hits, 0,
        "{what}: step bound hits"
    );
    assert!(stats.counters.rays_hit > 0, "{what}: no ray meets the mesh");
}

fn render(
    scene: &Scene,
    camera: &Camera,
    integrator: &ScalarIntegrator,
    opts: &RenderOptions,
) -> RenderOutput {
    let out = render_scalar(scene, camera, integrator, opts).unwrap();
    assert_clean(&out.stats, integrator.method().name());
    out
}

// ---------------------------------------------------------------------------
// 1. Constant material: Beer-Lambert with every method.

/// A mesh with a constant scalar and the length of a ray inside it.
struct ConstantCase {
    name: &'static str,
    scene: Scene,
    lo: Vec3,
    hi: Vec3,
    chord: Box<dyn Fn(&RayFrame) -> f64>,
}

fn constant_cases() -> Vec<ConstantCase> {
    let with_field = |mut mesh: tetray_mesh::TetMesh| {
        add_field(&mut mesh, "c", ScalarSpec::Constant(0.5));
        scene(mesh, "c")
    };
    let (lo, hi) = (Vec3::new(-0.5, -0.25, 0.0), Vec3::new(0.5, 0.75, 0.8));
    let (outer, inner) = (
        (Vec3::splat(-0.5), Vec3::splat(0.5)),
        (Vec3::splat(-0.25), Vec3::splat(0.25)),
    );
    let a = (Vec3::new(-1.0, -0.5, -0.5), Vec3::new(-0.2, 0.5, 0.5));
    let b = (Vec3::new(0.3, -0.3, -0.4), Vec3::new(1.0, 0.6, 0.2));
    vec![
        ConstantCase {
            name: "box",
            scene: with_field(box_grid(lo, hi, [3, 4, 2], CellSplit::Five).unwrap()),
            lo,
            hi,
            chord: Box::new(move |ray| box_chord(ray, lo, hi)),
        },
        // Rays leave into the hole and enter the mesh again.
        ConstantCase {
            name: "hollow",
            scene: with_field(
                hollow_box(
                    outer.0,
                    outer.1,
                    [4, 4, 4],
                    [1, 1, 1],
                    [3, 3, 3],
                    CellSplit::Five,
                )
                .unwrap(),
            ),
            lo: outer.0,
            hi: outer.1,
            chord: Box::new(move |ray| {
                box_chord(ray, outer.0, outer.1) - box_chord(ray, inner.0, inner.1)
            }),
        },
        // Rays cross a gap between two meshes.
        ConstantCase {
            name: "two-boxes",
            scene: with_field(
                two_boxes((a.0, a.1, [2, 3, 2]), (b.0, b.1, [3, 2, 2]), CellSplit::Six).unwrap(),
            ),
            lo: a.0.min(b.0),
            hi: a.1.max(b.1),
            chord: Box::new(move |ray| box_chord(ray, a.0, a.1) + box_chord(ray, b.0, b.1)),
        },
    ]
}

#[test]
fn constant_material_is_beer_lambert_with_every_method() {
    const TEST: &str = "constant_material_is_beer_lambert_with_every_method";
    // Channels differ; exact opacity mode: tau = -ln(1 - alpha) / u.
    let lum = Vec3::new(0.9, 0.55, 0.2);
    let (alpha, unit_distance) = (0.3f32, 0.5f32);
    let tf = transfer_function(
        &[(0.0, lum.to_array()), (1.0, lum.to_array())],
        &[(0.0, alpha), (1.0, alpha)],
    );
    let tau = -(1.0 - f64::from(alpha)).ln() / f64::from(unit_distance);
    let options = IntegratorOptions {
        unit_distance,
        opacity_mode: OpacityMode::Exact,
        ..IntegratorOptions::default()
    };
    let integrators: Vec<_> = Method::ALL
        .iter()
        .map(|&m| integrator(m, &tf, &options))
        .collect();
    let opts = render_options(SIZE);
    let mut worst = Worst::default();
    for case in constant_cases() {
        for (view, camera) in views(case.lo, case.hi, &ANGLES) {
            let expected = expected_image(&camera, SIZE, SIZE, |ray| {
                beer_lambert(lum.as_dvec3(), tau, (case.chord)(ray))
            });
            for integrator in &integrators {
                let out = render(&case.scene, &camera, integrator, &opts);
                let name = integrator.method().name();
                let label = format!("{}-{view}-{name}", case.name);
                worst.record(
                    name,
                    assert_matches(TEST, &label, &out.image, &expected, EXACT_TOL),
                );
            }
        }
    }
    worst.print(TEST);
}

// ---------------------------------------------------------------------------
// 2. Linear scalar on irregular meshes.

/// The box of the linear-field tests and its field (range -0.875..1.245).
const LIN_LO: Vec3 = Vec3::new(-0.5, -0.25, 0.0);
const LIN_HI: Vec3 = Vec3::new(0.5, 0.75, 0.8);
const LIN_UNIT: f32 = 0.5;
const LIN_FIELD: LinearField = LinearField {
    offset: 0.3,
    gradient: Vec3::new(0.7, -1.1, 0.4),
};

/// Irregular tetrahedralizations of the box with the linear field.
fn jittered_scenes() -> Vec<(&'static str, Scene)> {
    [
        ("five", [4, 4, 3], 11, CellSplit::Five),
        ("six", [3, 4, 3], 5, CellSplit::Six),
    ]
    .into_iter()
    .map(|(name, cells, seed, split)| {
        let mut mesh = jittered_box(LIN_LO, LIN_HI, cells, 0.2, seed, split).unwrap();
        add_field(&mut mesh, "lin", LIN_FIELD.spec());
        (name, scene(mesh, "lin"))
    })
    .collect()
}

/// VTK opacity mode: attenuation linear in the opacity, so in the scalar.
fn vtk_options(unit_distance: f32, split_at_knots: bool) -> IntegratorOptions {
    IntegratorOptions {
        unit_distance,
        opacity_mode: OpacityMode::Vtk,
        split_at_knots,
        ..IntegratorOptions::default()
    }
}

/// Renders every jittered scene in every view with each integrator: per
/// view, its label, the closed form and one image per integrator.
fn linear_renders(
    tf: &TransferFunction,
    integrators: &[ScalarIntegrator],
) -> Vec<(String, Expected, Vec<Image>)> {
    let closed = TfF64::new(tf);
    let mut renders = Vec::new();
    for (mesh, scene) in jittered_scenes() {
        for (view, camera) in views(LIN_LO, LIN_HI, &ANGLES) {
            let expected = expected_image(&camera, SIZE, SIZE, |ray| {
                box_interval(ray, LIN_LO, LIN_HI).map_or([0.0; 4], |chord| {
                    linear_field_light(ray, LIN_FIELD, &closed, f64::from(LIN_UNIT), chord)
                })
            });
            let images = integrators
                .iter()
                .map(|i| render(&scene, &camera, i, &render_options(SIZE)).image)
                .collect();
            renders.push((format!("{mesh}-{view}"), expected, images));
        }
    }
    renders
}

/// The exact, reference and PPI methods, cutting at knots, against the
/// closed form; and PPI against the exact render of the same rays, where
/// the walk and its rounding are shared and only the Psi table differs.
fn check_split_methods(test: &str, tf: &TransferFunction, worst: &mut Worst) {
    let methods = [Method::Exact, Method::Reference, Method::Ppi];
    let options = vtk_options(LIN_UNIT, true);
    let integrators = methods.map(|m| integrator(m, tf, &options));
    // Eq. 5.5: Psi multiplies L_b - L_f, so a cell adds at most the table
    // error times the luminance change across it, attenuated by what lies
    // in front; over a ray, at most the table error times the luminance's
    // total variation. Plus 2e-6 for the two methods' different f32
    // rounding of up to ~40 segments.
    let psi_bound = PSI_TABLE_ERROR * luminance_variation(tf) + 2e-6;
    let mut table_error = 0.0f64;
    for (label, expected, images) in linear_renders(tf, &integrators) {
        for (method, image) in methods.iter().zip(&images) {
            let tolerance = if *method == Method::Ppi {
                PPI_TOL
            } else {
                EXACT_TOL
            };
            let label = format!("{label}-{method}");
            let error = assert_matches(test, &label, image, &expected, tolerance);
            worst.record(method.name(), error);
        }
        let exact: Expected = images[0].rgba.iter().map(|p| p.map(f64::from)).collect();
        let label = format!("{label}-ppi-vs-exact");
        table_error = table_error.max(assert_matches(test, &label, &images[2], &exact, psi_bound));
    }
    worst.record(&format!("ppi - exact (bound {psi_bound:.1e})"), table_error);
}

#[test]
fn linear_field_with_linear_tf_matches_one_segment_per_chord() {
    const TEST: &str = "linear_field_with_linear_tf_matches_one_segment_per_chord";
    // Two points beyond the data range: no knot inside, so luminance and
    // attenuation are linear along every chord.
    let tf = transfer_function(
        &[(-1.0, [0.1, 0.3, 0.9]), (1.5, [0.95, 0.6, 0.05])],
        &[(-1.0, 0.05), (1.5, 0.8)],
    );
    let mut worst = Worst::default();
    check_split_methods(TEST, &tf, &mut worst);
    worst.print(TEST);
}

/// Luminance and opacity with knots inside the data range (-0.875..1.245),
/// at different scalars for the two, with sharp turns.
fn knotted_tf() -> TransferFunction {
    transfer_function(
        &[
            (-1.0, [0.1, 0.2, 0.9]),
            (-0.2, [0.2, 0.9, 0.3]),
            (0.5, [1.0, 0.8, 0.1]),
            (1.5, [0.9, 0.1, 0.1]),
        ],
        &[(-1.0, 0.0), (0.0, 0.7), (0.3, 0.1), (1.5, 0.6)],
    )
}

#[test]
fn interior_knots_are_integrated_exactly_by_splitting() {
    const TEST: &str = "interior_knots_are_integrated_exactly_by_splitting";
    let tf = knotted_tf();
    let mut worst = Worst::default();
    check_split_methods(TEST, &tf, &mut worst);
    // Without the cuts a cell holding a knot is integrated as if luminance
    // and attenuation were linear between its ends: the error of sampling
    // the transfer function at the vertices only (section 4.3).
    let methods = [Method::Exact, Method::Ppi];
    let unsplit = methods.map(|m| integrator(m, &tf, &vtk_options(LIN_UNIT, false)));
    let mut errors = [0.0f64; 2];
    for (_, expected, images) in linear_renders(&tf, &unsplit) {
        for (error, image) in errors.iter_mut().zip(&images) {
            *error = error.max(deviation(image, &expected, EXACT_TOL).max);
        }
    }
    for (method, error) in methods.iter().zip(errors) {
        let name = format!("{method} without knot splitting");
        worst.record(&name, error);
        // Measured: 1.3e-2, over 5000 times the split's error.
        assert!(
            error > 100.0 * EXACT_TOL,
            "{name}: max error {error:e}, expected far above {EXACT_TOL:e}"
        );
    }
    worst.print(TEST);
}

// ---------------------------------------------------------------------------
// 3. Rays through vertices, along edges and in face planes.

/// 31 pixels of 1/8 world unit: centres at 0.125, 0.25, .., 3.875 on the
/// grid [0, 4]^3 of unit cells, every projected coordinate exact; rays run
/// through vertices (pixels 7, 15, 23 on both axes), along edges, in cell
/// faces and in the splits' diagonal planes, never on the mesh boundary.
const GRID_SIZE: u32 = 31;
const GRID_CENTRE: Vec3 = Vec3::splat(2.0);

/// Along the axes every projection and crossing distance is exact, so only
/// the f32 rounding of each segment's light and of compositing remains
/// (~6e-8 per segment, ~25 segments). Measured: 2.5e-7 at most. PPI adds
/// the Psi table's error times the luminance's variation (see `PPI_TOL`).
const AXIS_TOL: f64 = 2e-6;

/// The six axis-aligned orthographic views of the grid, named by the side
/// the camera is on.
fn axis_views() -> Vec<(String, Camera)> {
    let mut cameras = Vec::new();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let (mut offset, mut up) = (Vec3::ZERO, Vec3::ZERO);
            offset[axis] = 10.0 * sign;
            up[(axis + 1) % 3] = 1.0;
            let camera = Camera {
                position: GRID_CENTRE + offset,
                focal_point: GRID_CENTRE,
                view_up: up,
                view_angle: 30.0,
                parallel_scale: Some(GRID_SIZE as f32 / 16.0),
            };
            cameras.push((
                format!(
                    "{}-{}",
                    ["x", "y", "z"][axis],
                    if sign > 0.0 { "pos" } else { "neg" }
                ),
                camera,
            ));
        }
    }
    cameras
}

#[test]
fn rays_through_vertices_edges_and_faces_match_closed_forms() {
    const TEST: &str = "rays_through_vertices_edges_and_faces_match_closed_forms";
    let (lo, hi) = (Vec3::ZERO, Vec3::splat(4.0));
    // Dyadic gradient: every vertex scalar is exact, and the knots at 1,
    // 1.5 and 2 are met exactly at vertices, edges and faces.
    let field = LinearField {
        offset: 0.5,
        gradient: Vec3::new(0.25, -0.125, 0.375),
    };
    let lum = Vec3::new(0.3, 0.8, 0.6);
    let constant_tf = transfer_function(&[(0.0, lum.to_array())], &[(0.0, 0.4)]);
    let linear_tf = transfer_function(
        &[(-0.25, [0.9, 0.2, 0.1]), (3.25, [0.1, 0.5, 1.0])],
        &[(-0.25, 0.05), (3.25, 0.8)],
    );
    let knotted_tf = transfer_function(
        &[
            (0.0, [0.9, 0.2, 0.1]),
            (1.0, [0.2, 0.9, 0.4]),
            (2.0, [1.0, 1.0, 0.2]),
            (3.0, [0.1, 0.5, 1.0]),
        ],
        &[(0.0, 0.05), (1.5, 0.9), (3.0, 0.2)],
    );
    let constant_options = IntegratorOptions::default();
    let (vtk, u) = (vtk_options(1.0, true), 1.0);
    let tau = -(1.0f64 - 0.4).ln();
    let opts = render_options(GRID_SIZE);
    let mut worst = Worst::default();
    for split in [CellSplit::Five, CellSplit::Six] {
        let mut mesh = box_grid(lo, hi, [4, 4, 4], split).unwrap();
        add_field(&mut mesh, "c", ScalarSpec::Constant(1.0));
        add_field(&mut mesh, "lin", field.spec());
        let constant = scene(mesh.clone(), "c");
        let linear = scene(mesh, "lin");
        for (view, camera) in axis_views() {
            let every_ray_hits = |out: &RenderOutput| {
                assert_eq!(
                    out.stats.counters.rays_hit,
                    u64::from(GRID_SIZE * GRID_SIZE),
                    "{split:?} {view}"
                );
            };
            let beer = expected_image(&camera, GRID_SIZE, GRID_SIZE, |ray| {
                beer_lambert(lum.as_dvec3(), tau, box_chord(ray, lo, hi))
            });
            for method in Method::ALL {
                let out = render(
                    &constant,
                    &camera,
                    &integrator(method, &constant_tf, &constant_options),
                    &opts,
                );
                every_ray_hits(&out);
                let label = format!("{split:?}-{view}-constant-{method}");
                worst.record(
                    method.name(),
                    assert_matches(TEST, &label, &out.image, &beer, AXIS_TOL),
                );
            }
            for (tf_name, tf) in [("linear", &linear_tf), ("knotted", &knotted_tf)] {
                let closed = TfF64::new(tf);
                let expected = expected_image(&camera, GRID_SIZE, GRID_SIZE, |ray| {
                    linear_field_light(ray, field, &closed, u, box_interval(ray, lo, hi).unwrap())
                });
                let ppi_tol = AXIS_TOL + PSI_TABLE_ERROR * luminance_variation(tf);
                for (method, tolerance) in [
                    (Method::Exact, AXIS_TOL),
                    (Method::Reference, AXIS_TOL),
                    (Method::Ppi, ppi_tol),
                ] {
                    let out = render(&linear, &camera, &integrator(method, tf, &vtk), &opts);
                    every_ray_hits(&out);
                    let label = format!("{split:?}-{view}-{tf_name}-{method}");
                    let error = assert_matches(TEST, &label, &out.image, &expected, tolerance);
                    worst.record(&format!("{method} {tf_name}"), error);
                }
            }
        }
    }
    worst.print(TEST);
}

// ---------------------------------------------------------------------------
// 4. Early ray termination.

#[test]
fn early_termination_stops_just_past_the_threshold() {
    const TEST: &str = "early_termination_stops_just_past_the_threshold";
    let (lo, hi) = (Vec3::splat(-0.5), Vec3::splat(0.5));
    let mut mesh = box_grid(lo, hi, [10, 10, 10], CellSplit::Five).unwrap();
    add_field(&mut mesh, "c", ScalarSpec::Constant(0.0));
    // A segment lies in one tetrahedron: it is no longer than its longest edge.
    let longest_edge = mesh
        .tets
        .iter()
        .flat_map(|t| {
            let p = t.map(|v| mesh.points[v as usize].as_dvec3());
            [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)].map(|(i, j)| p[i].distance(p[j]))
        })
        .fold(0.0f64, f64::max);
    let scene = scene(mesh, "c");
    let lum = Vec3::new(0.7, 0.4, 0.95);
    let (alpha, unit_distance) = (0.7f32, 0.25f32);
    let tau = -(1.0 - f64::from(alpha)).ln() / f64::from(unit_distance);
    let tf = transfer_function(&[(0.0, lum.to_array())], &[(0.0, alpha)]);
    let options = IntegratorOptions {
        unit_distance,
        ..IntegratorOptions::default()
    };
    let ppi = integrator(Method::Ppi, &tf, &options);
    // EXACT_TOL's reasoning with `L tau` up to 4.6 here: the chord error
    // moves a pixel by up to 2.3e-5, plus 5e-6 for rounding (2.8e-5).
    let tolerance = f64::from(lum.max_element()) * tau * CHORD_ERROR + 5e-6;
    // The ray stops after the segment that takes it past the threshold,
    // with more than 0.1 of the light left before it: it overshoots by
    // less than 0.1 (1 - exp(-tau h)) for the longest segment h.
    let threshold = 0.9;
    let overshoot = 0.1 * -(-tau * longest_edge).exp_m1();
    for (view, camera) in views(lo, hi, &ANGLES[1..]) {
        let full = render(&scene, &camera, &ppi, &render_options(SIZE));
        let stopped = render(
            &scene,
            &camera,
            &ppi,
            &RenderOptions {
                early_termination: threshold as f32,
                ..render_options(SIZE)
            },
        );
        let expected = expected_image(&camera, SIZE, SIZE, |ray| {
            beer_lambert(lum.as_dvec3(), tau, box_chord(ray, lo, hi))
        });
        // Disabled (1.0): the closed form.
        let label = format!("{view}-disabled");
        let full_error = assert_matches(TEST, &label, &full.image, &expected, tolerance);
        // Stopped rays end in [threshold, threshold + overshoot] and never
        // past the full integral; the others are the closed form. Constant
        // material: the colour is L times the opacity, wherever a ray stops.
        let (mut stopped_rays, mut highest, mut bad) = (0, 0.0f64, Vec::new());
        for (i, (got, want)) in stopped.image.rgba.iter().zip(&expected).enumerate() {
            let a = f64::from(got[3]);
            let alpha_ok = if want[3] > threshold {
                stopped_rays += 1;
                highest = highest.max(a);
                a >= threshold.min(want[3]) - tolerance
                    && a <= (threshold + overshoot).min(want[3]) + tolerance
            } else {
                (a - want[3]).abs() <= tolerance
            };
            let colour_ok =
                (0..3).all(|c| (f64::from(got[c]) - f64::from(lum[c]) * a).abs() <= tolerance);
            if !(alpha_ok && colour_ok) {
                bad.push((i, *got, want[3]));
            }
        }
        if !bad.is_empty() {
            let folder = write_images(TEST, &format!("{view}-stopped"), &stopped.image, &expected);
            panic!(
                "{view}: {} pixels wrong, first (index, rgba, full alpha) {:?}; images in {}",
                bad.len(),
                bad[0],
                folder.display()
            );
        }
        assert!(stopped_rays > 0, "{view}: no ray reaches the threshold");
        let (s_full, s_stopped) = (
            full.stats.counters.segments,
            stopped.stats.counters.segments,
        );
        eprintln!(
            "{TEST}: {view}: disabled: max error {full_error:.2e} (tolerance {tolerance:.1e}); \
             {stopped_rays} rays stopped, alpha at most {highest:.4} (bound {:.4}), \
             segments {s_full} -> {s_stopped}",
            threshold + overshoot
        );
        // Measured: about 38% fewer.
        assert!(
            s_stopped * 10 < s_full * 9,
            "{view}: segments {s_full} -> {s_stopped}"
        );
    }
}
