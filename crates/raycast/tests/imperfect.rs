//! Meshes that are not perfect still render, correctly, and the loader
//! says what it changed:
//! - the real samples `data/real/can.vtu` (a crushed can: hexahedra
//!   deformed until some splits overlap) and `data/real/uGridEx.vtk` (a
//!   hexahedron's face against two triangles cut the other way);
//! - huge coordinates: a mesh moved by 1e7 (and one with cells of 1e-3 at
//!   1e6) gives the image of the mesh at the origin, the camera given in
//!   the file's coordinates;
//! - tangled and folded cells: left out of the walk, reported, and
//!   composited in the holes they leave (a box folded inside renders as
//!   the box: Beer-Lambert for a constant field, the unfolded grid's image
//!   for a linear one); a twisted connectivity only adds light inside its
//!   hole.
//!
//! Meshes with f64 coordinates are written as legacy VTK text (shortest
//! round-trip decimals, so the reader gets the f64 values exactly).

mod support;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use support::box_chord;
use support::compare::{Expected, Worst, assert_matches, expected_image, views};
use support::optics::{beer_lambert, transfer_function};
use tetray_boundary_bvh::BuildPreset;
use tetray_core::{Camera, Image, relative_to_origin};
use tetray_integrate::{IntegratorOptions, Method, OpacityMode, ScalarIntegrator};
use tetray_io::{LoadOptions, load};
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, jittered_box};
use tetray_mesh::{LoadedMesh, MeshSummary};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;

const SIZE: u32 = 40;
const ANGLES: [(f32, f32); 2] = [(35.0, 25.0), (-120.0, -40.0)];

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/real")
        .join(name)
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("tetray-imperfect");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A legacy VTK unstructured grid: f64 points, cells of one VTK type, one
/// point scalar `s`.
fn write_vtk(path: &Path, points: &[DVec3], cells: &[Vec<u32>], cell_type: u32, s: &[f64]) {
    let mut text =
        String::from("# vtk DataFile Version 3.0\ntest\nASCII\nDATASET UNSTRUCTURED_GRID\n");
    writeln!(text, "POINTS {} double", points.len()).unwrap();
    for p in points {
        writeln!(text, "{:?} {:?} {:?}", p.x, p.y, p.z).unwrap();
    }
    let size: usize = cells.iter().map(|c| c.len() + 1).sum();
    writeln!(text, "CELLS {} {size}", cells.len()).unwrap();
    for c in cells {
        let ids: Vec<String> = c.iter().map(u32::to_string).collect();
        writeln!(text, "{} {}", c.len(), ids.join(" ")).unwrap();
    }
    writeln!(text, "CELL_TYPES {}", cells.len()).unwrap();
    for _ in cells {
        writeln!(text, "{cell_type}").unwrap();
    }
    writeln!(
        text,
        "POINT_DATA {}\nSCALARS s double 1\nLOOKUP_TABLE default",
        s.len()
    )
    .unwrap();
    for v in s {
        writeln!(text, "{v:?}").unwrap();
    }
    std::fs::write(path, text).unwrap();
}

fn render(scene: &Scene, camera: &Camera, integrator: &ScalarIntegrator) -> Image {
    let opts = RenderOptions {
        width: SIZE,
        height: SIZE,
        ..RenderOptions::default()
    };
    let out = render_scalar(scene, camera, integrator, &opts).unwrap();
    assert_eq!(out.stats.counters.walk_failures, 0);
    assert_eq!(out.stats.counters.steps_bound_hits, 0);
    out.image
}

/// [`render`], and the frame's counters.
fn render_with_stats(
    scene: &Scene,
    camera: &Camera,
    integrator: &ScalarIntegrator,
) -> (Image, tetray_core::WalkCounters) {
    let opts = RenderOptions {
        width: SIZE,
        height: SIZE,
        ..RenderOptions::default()
    };
    let out = render_scalar(scene, camera, integrator, &opts).unwrap();
    (out.image, out.stats.counters)
}

fn as_expected(image: &Image) -> Expected {
    image.rgba.iter().map(|p| p.map(f64::from)).collect()
}

/// Exact integration, a linear transfer function over `range`, unit
/// distance `unit` (VTK opacity mode).
fn integrator(range: (f32, f32), unit: f32) -> ScalarIntegrator {
    let (lo, hi) = range;
    let tf = transfer_function(
        &[(lo, [0.1, 0.3, 0.9]), (hi, [0.95, 0.6, 0.05])],
        &[(lo, 0.05), (hi, 0.8)],
    );
    let options = IntegratorOptions {
        unit_distance: unit,
        opacity_mode: OpacityMode::Vtk,
        ..IntegratorOptions::default()
    };
    ScalarIntegrator::new(Method::Exact, &tf, &options).unwrap()
}

fn field_range(scene: &Scene) -> (f32, f32) {
    tetray_mesh::value_range(&scene.scalar)
}

#[test]
fn real_imperfect_samples_load_render_and_report() {
    // The crushed can: tangled hexahedra left out, reported with their
    // share of the volume; the rest renders.
    let can = load(&data("can.vtu"), &LoadOptions::default()).unwrap();
    let changes = can.report.changes().expect("the can is changed on load");
    eprintln!("can.vtu: {changes}");
    let x = &can.report.excluded;
    assert!(!x.cells.is_empty() && x.tets > 0, "{changes}");
    assert!(x.volume_share > 0.0 && x.volume_share < 0.05, "{changes}");
    // uGridEx: the hexahedron's face against two triangles cut the other
    // way is a non-conforming contact, its faces made boundary.
    let ugrid = load(&data("uGridEx.vtk"), &LoadOptions::default()).unwrap();
    let changes = ugrid.report.changes().expect("uGridEx is changed on load");
    eprintln!("uGridEx.vtk: {changes}");
    assert!(!ugrid.report.validation.nonconforming_faces.is_empty());
    // `tetray info` prints the details: which faces, which cells, how much.
    let text = MeshSummary::new(&ugrid).to_string();
    assert!(
        text.contains("non-conforming:  6 faces made boundary"),
        "{text}"
    );
    assert!(text.contains("tetrahedron "), "{text}");
    // 6 of the can's 39 folded hexahedra are split around an added point
    // (star-shaped around it); 33 have no split of one orientation.
    assert_eq!(can.report.points_added, 6, "{changes}");
    assert!(
        can.report
            .warnings
            .iter()
            .any(|w| w.starts_with("6 folded hexahedra split around a point")),
        "{:?}",
        can.report.warnings
    );
    assert_eq!(can.overlaps.len(), can.report.excluded.tets);
    let text = MeshSummary::new(&can).to_string();
    assert!(
        text.contains("left out:        33 cells (33 tangled"),
        "{text}"
    );
    assert!(text.contains("  cells:         "), "{text}");
    for (name, loaded) in [("can", can), ("uGridEx", ugrid)] {
        let field = loaded.mesh.fields[0].name.clone();
        let scene = Scene::from_loaded(loaded, &field, BuildPreset::default()).unwrap();
        let (lo, hi) = scene.bounds();
        let range = field_range(&scene);
        let range = if range.0 < range.1 {
            range
        } else {
            (range.0, range.0 + 1.0)
        };
        let unit = 0.1 * (hi - lo).length();
        let camera = views(lo, hi, &ANGLES)[0].1;
        let image = render(&scene, &camera, &integrator(range, unit));
        let covered = image.rgba.iter().filter(|p| p[3] > 1e-3).count();
        // uGridEx is small and faint in this view (83 of 1600 measured).
        assert!(covered > 40, "{name}: {covered} pixels covered");
    }
}

/// An irregular box with a linear field, points moved by `offset` after
/// scaling by `scale` (in f64), written and loaded.
fn moved_box(scale: f64, offset: DVec3, name: &str) -> LoadedMesh {
    let mesh = jittered_box(
        Vec3::new(-0.5, -0.25, 0.0),
        Vec3::new(0.5, 0.75, 0.8),
        [4, 4, 3],
        0.2,
        7,
        CellSplit::Five,
    )
    .unwrap();
    let spec = ScalarSpec::Linear {
        offset: 0.3,
        gradient: Vec3::new(0.7, -1.1, 0.4),
    };
    let points: Vec<DVec3> = mesh
        .points
        .iter()
        .map(|p| p.as_dvec3() * scale + offset)
        .collect();
    let s: Vec<f64> = mesh
        .points
        .iter()
        .map(|p| spec.eval(p.as_dvec3()))
        .collect();
    let cells: Vec<Vec<u32>> = mesh.tets.iter().map(|t| t.to_vec()).collect();
    let path = scratch(name);
    write_vtk(&path, &points, &cells, 10, &s);
    load(&path, &LoadOptions::default()).unwrap()
}

/// Tolerance 1e-5 per pixel: both meshes are the same f64 geometry rounded
/// to f32 at different places (the moved one relative to its centre, the
/// other relative to zero, a rounding of ~6e-8 of the box size each), the
/// cameras likewise; the closed-form tests bound what such roundings do
/// to a pixel at 1e-5 (`EXACT_TOL` of `closed_form.rs`).
#[test]
fn far_from_the_origin_renders_as_at_the_origin() {
    const TEST: &str = "far_from_the_origin_renders_as_at_the_origin";
    let mut worst = Worst::default();
    for (scale, offset) in [
        (1.0, DVec3::new(1e7, -1e7, 1e7)),
        // Cells of 1e-3 at 1e6: in f32 at 1e6 (ulp 0.0625) they would be
        // points.
        (4e-3, DVec3::new(1e6, 1e6, -1e6)),
    ] {
        let base = moved_box(scale, DVec3::ZERO, "base.vtk");
        let moved = moved_box(scale, offset, "moved.vtk");
        assert_eq!(base.origin(), DVec3::ZERO);
        assert!(
            (moved.origin() - offset).length() < scale,
            "{:?}",
            moved.origin()
        );
        assert!(
            moved
                .report
                .changes()
                .unwrap()
                .contains("relative to the origin")
        );
        assert!(moved.report.excluded.is_empty());
        assert_eq!(moved.mesh.tets.len(), base.mesh.tets.len());
        let origin = moved.origin();
        let base = Scene::from_loaded(base, "s", BuildPreset::default()).unwrap();
        let moved = Scene::from_loaded(moved, "s", BuildPreset::default()).unwrap();
        let integrator = integrator(field_range(&base), 0.5 * scale as f32);
        let (lo, hi) = base.bounds();
        for (view, camera) in views(lo, hi, &ANGLES) {
            let expected = as_expected(&render(&base, &camera, &integrator));
            // The same camera in the moved file's coordinates, then as the
            // CLI takes it: the origin subtracted in f64.
            let world = |p: Vec3| p.as_dvec3() + offset;
            let moved_camera = Camera {
                position: relative_to_origin(world(camera.position), origin),
                focal_point: relative_to_origin(world(camera.focal_point), origin),
                ..camera
            };
            let image = render(&moved, &moved_camera, &integrator);
            let label = format!("scale{scale}-{view}");
            worst.record(
                &format!("scale {scale}"),
                assert_matches(TEST, &label, &image, &expected, 1e-5),
            );
        }
    }
    worst.print(TEST);
}

/// A 3 x 3 x 3 grid of unit hexahedra (VTK order) over `[0, 3]^3`, point
/// `(i, j, k)` at index `i + 4 j + 16 k`, moved by `moved`.
fn hex_grid(moved: &[(usize, DVec3)]) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let id = |i: u32, j: u32, k: u32| i + 4 * j + 16 * k;
    let mut points: Vec<DVec3> = (0..64)
        .map(|n| DVec3::new(f64::from(n % 4), f64::from(n / 4 % 4), f64::from(n / 16)))
        .collect();
    for &(p, d) in moved {
        points[p] += d;
    }
    let mut cells = Vec::new();
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..3 {
                cells.push(vec![
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ]);
            }
        }
    }
    (points, cells)
}

fn load_hexes(points: &[DVec3], cells: &[Vec<u32>], s: &[f64], name: &str) -> LoadedMesh {
    let path = scratch(name);
    write_vtk(&path, points, cells, 12, s);
    load(&path, &LoadOptions::default()).unwrap()
}

/// The centre hexahedron's connectivity twisted (its top face listed as a
/// bow-tie): split, its tetrahedra have both orientations, and it is left
/// out and reported. Its faces enclose no region the hole matches, so its
/// pieces may fill the hole only in part; they never add light outside it:
/// with a constant field every pixel's opacity lies between Beer-Lambert
/// through the box minus the centre cube and through the whole box (1e-5,
/// the closed-form tolerance), and some pixels gain light.
#[test]
fn a_twisted_cell_adds_light_only_inside_its_hole() {
    let (points, mut cells) = hex_grid(&[]);
    let s = vec![0.5; points.len()];
    cells[13].swap(6, 7);
    let tangled = load_hexes(&points, &cells, &s, "tangled.vtk");
    let x = &tangled.report.excluded;
    assert_eq!(x.cells, [13], "{:?}", tangled.report.changes());
    assert_eq!(x.tangled, 1);
    // The cell's absolute volume over the box's 27 (the twisted cell's
    // tetrahedra are the unit cube's, folded: their volumes sum to more).
    assert!(
        x.volume_share > 0.9 / 27.0 && x.volume_share < 2.0 / 27.0,
        "{}",
        x.volume_share
    );
    assert!(
        tangled
            .report
            .changes()
            .unwrap()
            .contains("1 cells left out (1 tangled")
    );
    let (lum, tau, integrator) = constant_field_integrator();
    let tangled = Scene::from_loaded(tangled, "s", BuildPreset::default()).unwrap();
    let (lo, hi) = (Vec3::ZERO, Vec3::splat(3.0));
    let mut gained = 0;
    for (view, camera) in views(lo, hi, &[(0.0, 0.0), (35.0, 25.0), (-120.0, -40.0)]) {
        let alpha = |chord: f64| beer_lambert(lum.as_dvec3(), tau, chord)[3];
        let without = expected_image(&camera, SIZE, SIZE, |ray| {
            let chord = box_chord(ray, lo, hi) - box_chord(ray, Vec3::ONE, Vec3::splat(2.0));
            [0.0, 0.0, 0.0, alpha(chord)]
        });
        let whole = expected_image(&camera, SIZE, SIZE, |ray| {
            [0.0, 0.0, 0.0, alpha(box_chord(ray, lo, hi))]
        });
        let (image, stats) = render_with_stats(&tangled, &camera, &integrator);
        assert!(stats.overlap_segments > 0, "{view}");
        for (i, p) in image.rgba.iter().enumerate() {
            let a = f64::from(p[3]);
            assert!(
                a >= without[i][3] - 1e-5 && a <= whole[i][3] + 1e-5,
                "{view} pixel {i}: alpha {a} outside [{}, {}]",
                without[i][3],
                whole[i][3]
            );
            gained += usize::from(a > without[i][3] + 1e-4);
        }
    }
    assert!(gained > 0);
}

/// A grey constant-field integrator: luminance, attenuation per unit
/// length and the integrator (exact opacity mode, unit distance 1.5).
fn constant_field_integrator() -> (Vec3, f64, ScalarIntegrator) {
    let lum = Vec3::new(0.9, 0.55, 0.2);
    let (alpha, unit) = (0.3f32, 1.5f32);
    let tf = transfer_function(
        &[(0.0, lum.to_array()), (1.0, lum.to_array())],
        &[(0.0, alpha), (1.0, alpha)],
    );
    let tau = -(1.0 - f64::from(alpha)).ln() / f64::from(unit);
    let options = IntegratorOptions {
        unit_distance: unit,
        opacity_mode: OpacityMode::Exact,
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::new(Method::Exact, &tf, &options).unwrap();
    (lum, tau, integrator)
}

/// An interior point pushed (0.5, 0.9, -0.9) cells folds three of the
/// hexahedra around it: no split of theirs has one orientation, and they
/// are left out of the walk and composited in the hole they leave. The box
/// renders as the unfolded box:
/// - a constant field: Beer-Lambert through the whole box, 1e-5 per pixel
///   (the closed-form tolerance);
/// - a linear field (linear in the moved positions too, so every
///   tetrahedron interpolates it exactly): the image of the grid with the
///   point in place, 1e-5 (two meshes cut the rays at different places:
///   f32 rounding of the segments' ends and scalars).
#[test]
fn folded_cells_fill_the_hole_they_leave() {
    const TEST: &str = "folded_cells_fill_the_hole_they_leave";
    let moved = [(1 + 4 + 16, DVec3::new(0.5, 0.9, -0.9))];
    let (points, cells) = hex_grid(&moved);
    let linear = |p: &DVec3| 0.2 + 0.1 * p.x - 0.05 * p.y + 0.15 * p.z;
    let s: Vec<f64> = points.iter().map(linear).collect();
    let folded = load_hexes(&points, &cells, &s, "folded.vtk");
    let changes = folded.report.changes().unwrap();
    eprintln!("{TEST}: {changes}");
    assert_eq!(folded.report.excluded.tangled, 3, "{changes}");
    let constant = load_hexes(&points, &cells, &vec![0.5; s.len()], "folded-constant.vtk");
    let (in_place, cells) = hex_grid(&[]);
    let s_in_place: Vec<f64> = in_place.iter().map(linear).collect();
    let reference = load_hexes(&in_place, &cells, &s_in_place, "unfolded.vtk");
    let folded = Scene::from_loaded(folded, "s", BuildPreset::default()).unwrap();
    let constant = Scene::from_loaded(constant, "s", BuildPreset::default()).unwrap();
    let reference = Scene::from_loaded(reference, "s", BuildPreset::default()).unwrap();
    let linear_integrator = integrator(field_range(&reference), 1.0);
    let (lum, tau, constant_integrator) = constant_field_integrator();
    let (lo, hi) = reference.bounds();
    let mut worst = Worst::default();
    for (view, camera) in views(lo, hi, &ANGLES) {
        let closed = expected_image(&camera, SIZE, SIZE, |ray| {
            beer_lambert(lum.as_dvec3(), tau, box_chord(ray, lo, hi))
        });
        let (image, stats) = render_with_stats(&constant, &camera, &constant_integrator);
        assert!(stats.overlap_segments > 0 && stats.overlap_overflows == 0);
        worst.record(
            "constant, closed form",
            assert_matches(TEST, &format!("{view}-constant"), &image, &closed, 1e-5),
        );
        let expected = as_expected(&render(&reference, &camera, &linear_integrator));
        let image = render(&folded, &camera, &linear_integrator);
        worst.record(
            "linear, unfolded grid",
            assert_matches(TEST, &view, &image, &expected, 1e-5),
        );
    }
    worst.print(TEST);
}
