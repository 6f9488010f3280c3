//! Meshes that do not meet face to face render as exactly as conforming
//! ones: the unmatched faces are boundary faces, and a ray leaving through
//! one re-enters through the coincident face(s) of the other side by the
//! boundary BVH (the re-entry of seams: the query starts a little before
//! the exit, never integrates backwards, and skips no face of positive
//! extent). A box is split in two halves meshed so that the faces at x = 0
//! do not match:
//! - "diagonals": both halves Kuhn-split, the right half mirrored in y, so
//!   every square of the interface is cut along the other diagonal;
//! - "refined": the right half has twice the cells per axis, so the left
//!   half's interface squares hold hanging nodes (edge midpoints, centres).
//!
//! Points are welded (coincident points share one index), so the interface
//! is non-conforming by index, not a seam. Both meshes are checked against
//! the closed forms of `closed_form.rs`: Beer-Lambert for a constant field
//! and one linear segment per chord for a linear field with a linear
//! transfer function, per pixel to 1e-5 (`EXACT_TOL` there: the chord
//! error of f32 ray crossings times `L tau`, plus f32 compositing; the
//! interface adds one exit/entry pair per ray, whose distances are rounded
//! the same way as any face crossing).

mod support;

use std::collections::HashMap;

use glam::Vec3;
use support::compare::{Worst, assert_matches, expected_image, views};
use support::optics::{LinearField, TfF64, beer_lambert, linear_field_light, transfer_function};
use support::{box_chord, box_interval};
use tetray_boundary_bvh::BuildPreset;
use tetray_integrate::{IntegratorOptions, Method, OpacityMode, ScalarIntegrator};
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, box_grid, merge};
use tetray_mesh::{TetMesh, prepare};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;

const SIZE: u32 = 40;
const TOL: f64 = 1e-5;
const ANGLES: [(f32, f32); 3] = [(0.0, 0.0), (35.0, 25.0), (-120.0, -40.0)];
/// The box; every grid coordinate below is dyadic, so exact in f32 and the
/// two halves' interface points coincide bit for bit.
const LO: Vec3 = Vec3::new(-0.5, -0.25, 0.0);
const HI: Vec3 = Vec3::new(0.5, 0.75, 0.75);
const FIELD: LinearField = LinearField {
    offset: 0.3,
    gradient: Vec3::new(0.7, -1.1, 0.4),
};

/// One index per distinct position (the first), tetrahedra renumbered.
fn weld(mut mesh: TetMesh) -> TetMesh {
    let mut first: HashMap<[u32; 3], u32> = HashMap::new();
    let mut map = Vec::with_capacity(mesh.points.len());
    let mut points = Vec::new();
    for p in &mesh.points {
        let key = p.to_array().map(|c| (c + 0.0).to_bits());
        let next = points.len() as u32;
        let index = *first.entry(key).or_insert(next);
        if index == next {
            points.push(*p);
        }
        map.push(index);
    }
    mesh.points = points;
    for tet in &mut mesh.tets {
        *tet = tet.map(|v| map[v as usize]);
    }
    mesh
}

/// The box `lo..hi` cut at the middle of x: left and right halves.
fn halves(
    (lo, hi): (Vec3, Vec3),
    left_cells: [u32; 3],
    right_cells: [u32; 3],
    mirror_right: bool,
) -> TetMesh {
    let x = 0.5 * (lo.x + hi.x);
    let left = box_grid(lo, Vec3::new(x, hi.y, hi.z), left_cells, CellSplit::Six).unwrap();
    let mut right = box_grid(Vec3::new(x, lo.y, lo.z), hi, right_cells, CellSplit::Six).unwrap();
    if mirror_right {
        // y -> lo.y + hi.y - y maps the grid onto itself (exactly: dyadic),
        // flipping every Kuhn diagonal's y direction; `prepare` reorients.
        for p in &mut right.points {
            p.y = lo.y + hi.y - p.y;
        }
    }
    weld(merge(left, right).unwrap())
}

fn cases() -> Vec<(&'static str, TetMesh)> {
    vec![
        ("diagonals", halves((LO, HI), [2, 4, 3], [2, 4, 3], true)),
        ("refined", halves((LO, HI), [2, 4, 3], [4, 8, 6], false)),
    ]
}

fn scene(mesh: TetMesh, spec: ScalarSpec, name: &str) -> Scene {
    let mut mesh = mesh;
    add_field(&mut mesh, "s", spec);
    let loaded = prepare(mesh).unwrap();
    let v = &loaded.report.validation;
    assert!(
        !v.nonconforming_faces.is_empty(),
        "{name}: not non-conforming"
    );
    assert_eq!(v.seam_faces, 0, "{name}: welded, no seams");
    // No face of the interface matches: two face-connected pieces.
    assert_eq!(v.components, 2, "{name}");
    assert!(v.nonconforming_faces.len() >= 4, "{name}");
    if name == "diagonals" {
        // 4 x 3 interface squares, two triangles on each side of each.
        assert_eq!(v.nonconforming_faces.len(), 48, "{name}");
        assert_eq!(v.hanging_nodes, 0, "{name}");
    } else if name == "refined" {
        // The fine side's interface points that are not coarse corners:
        // 9 x 7 fine points minus 5 x 4 coarse ones.
        assert_eq!(v.hanging_nodes, 9 * 7 - 5 * 4, "{name}");
    }
    Scene::from_loaded(loaded, "s", BuildPreset::default()).unwrap()
}

/// Renders one view; counts the rays' re-entries (BVH entries beyond the
/// first of each ray) into `reentries`.
fn render(
    scene: &Scene,
    camera: &tetray_core::Camera,
    integrator: &ScalarIntegrator,
    reentries: &mut u64,
) -> tetray_core::Image {
    let opts = RenderOptions {
        width: SIZE,
        height: SIZE,
        ..RenderOptions::default()
    };
    let out = render_scalar(scene, camera, integrator, &opts).unwrap();
    assert_eq!(out.stats.counters.walk_failures, 0);
    assert_eq!(out.stats.counters.steps_bound_hits, 0);
    *reentries += out.stats.counters.entries - out.stats.counters.rays_hit;
    out.image
}

#[test]
fn nonconforming_box_is_beer_lambert() {
    const TEST: &str = "nonconforming_box_is_beer_lambert";
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
    let integrators: Vec<_> = [Method::Exact, Method::Ppi, Method::Average]
        .iter()
        .map(|&m| ScalarIntegrator::new(m, &tf, &options).unwrap())
        .collect();
    let mut worst = Worst::default();
    for (name, mesh) in cases() {
        let scene = scene(mesh, ScalarSpec::Constant(0.5), name);
        let mut reentries = 0;
        for (view, camera) in views(LO, HI, &ANGLES) {
            let expected = expected_image(&camera, SIZE, SIZE, |ray| {
                beer_lambert(lum.as_dvec3(), tau, box_chord(ray, LO, HI))
            });
            for integrator in &integrators {
                let image = render(&scene, &camera, integrator, &mut reentries);
                let method = integrator.method().name();
                let label = format!("{name}-{view}-{method}");
                worst.record(name, assert_matches(TEST, &label, &image, &expected, TOL));
            }
        }
        // Rays crossing x = 0 (all but the view along it) leave and re-enter.
        assert!(reentries > 0, "{name}: no ray crossed the interface");
    }
    worst.print(TEST);
}

#[test]
fn nonconforming_box_integrates_a_linear_field_exactly() {
    const TEST: &str = "nonconforming_box_integrates_a_linear_field_exactly";
    let unit = 0.5f32;
    let tf = transfer_function(
        &[(-1.0, [0.1, 0.3, 0.9]), (1.5, [0.95, 0.6, 0.05])],
        &[(-1.0, 0.05), (1.5, 0.8)],
    );
    let closed = TfF64::new(&tf);
    let options = IntegratorOptions {
        unit_distance: unit,
        opacity_mode: OpacityMode::Vtk,
        split_at_knots: true,
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::new(Method::Exact, &tf, &options).unwrap();
    let mut worst = Worst::default();
    for (name, mesh) in cases() {
        let scene = scene(mesh, FIELD.spec(), name);
        let mut reentries = 0;
        for (view, camera) in views(LO, HI, &ANGLES) {
            let expected = expected_image(&camera, SIZE, SIZE, |ray| {
                box_interval(ray, LO, HI).map_or([0.0; 4], |chord| {
                    linear_field_light(ray, FIELD, &closed, f64::from(unit), chord)
                })
            });
            let image = render(&scene, &camera, &integrator, &mut reentries);
            let label = format!("{name}-{view}");
            worst.record(name, assert_matches(TEST, &label, &image, &expected, TOL));
        }
        assert!(reentries > 0, "{name}: no ray crossed the interface");
    }
    worst.print(TEST);
}

/// Axis-aligned orthographic views of `[0, 4]^3` cut at x = 2, 31 pixels
/// of 1/8 world unit (as `closed_form.rs`'s vertex and edge rays): every
/// projection and crossing distance is exact, and rays meet the interface
/// exactly at vertices and edges of both sides' triangles, where the exit
/// of one side and the entry of the other are decided by different
/// triangles. Beer-Lambert per pixel to 2e-6 (`AXIS_TOL` there: only the
/// f32 rounding of each segment's light and of compositing remains), and
/// every ray hits.
#[test]
fn rays_through_interface_vertices_and_edges_are_beer_lambert() {
    const TEST: &str = "rays_through_interface_vertices_and_edges_are_beer_lambert";
    const PIXELS: u32 = 31;
    let (lo, hi) = (Vec3::ZERO, Vec3::splat(4.0));
    let lum = Vec3::new(0.3, 0.8, 0.6);
    let tf = transfer_function(&[(0.0, lum.to_array())], &[(0.0, 0.4)]);
    let tau = -(1.0f64 - 0.4).ln();
    let integrator =
        ScalarIntegrator::new(Method::Exact, &tf, &IntegratorOptions::default()).unwrap();
    let meshes = [
        (
            "axis-diagonals",
            halves((lo, hi), [2, 4, 4], [2, 4, 4], true),
        ),
        (
            "axis-refined",
            halves((lo, hi), [2, 4, 4], [4, 8, 8], false),
        ),
    ];
    let mut worst = Worst::default();
    for (name, mesh) in meshes {
        let scene = scene(mesh, ScalarSpec::Constant(1.0), name);
        for axis in 0..3 {
            for sign in [1.0f32, -1.0] {
                let (mut offset, mut up) = (Vec3::ZERO, Vec3::ZERO);
                offset[axis] = 10.0 * sign;
                up[(axis + 1) % 3] = 1.0;
                let camera = tetray_core::Camera {
                    position: Vec3::splat(2.0) + offset,
                    focal_point: Vec3::splat(2.0),
                    view_up: up,
                    view_angle: 30.0,
                    parallel_scale: Some(PIXELS as f32 / 16.0),
                };
                let opts = RenderOptions {
                    width: PIXELS,
                    height: PIXELS,
                    ..RenderOptions::default()
                };
                let out = render_scalar(&scene, &camera, &integrator, &opts).unwrap();
                assert_eq!(out.stats.counters.walk_failures, 0);
                assert_eq!(out.stats.counters.steps_bound_hits, 0);
                assert_eq!(
                    out.stats.counters.rays_hit,
                    u64::from(PIXELS * PIXELS),
                    "{name}"
                );
                let expected = expected_image(&camera, PIXELS, PIXELS, |ray| {
                    beer_lambert(lum.as_dvec3(), tau, box_chord(ray, lo, hi))
                });
                let label = format!("{name}-{axis}-{sign}");
                worst.record(
                    name,
                    assert_matches(TEST, &label, &out.image, &expected, 2e-6),
                );
            }
        }
    }
    worst.print(TEST);
}
