//! [`TimeSteps`]: a step whose points and cells are the held step's, as
//! read, only brings its fields (the setup then equals one made from
//! scratch for that step, field, range and integrator); a step whose
//! points move is made anew with the first step's camera; a bad field in a
//! later step is an error that names the file, and the setup is unchanged.

use std::path::{Path, PathBuf};

use glam::Vec3;
use tetray_engine::{FrameOptions, Log, TimeSteps};
use tetray_io::vtk::write_legacy;
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, box_grid};

/// Legacy VTK unstructured grid: a unit cube of 6 tetrahedra (points
/// stretched along x by `stretch`), the field f = scale * (x + 2y + 3z)
/// over the unstretched cube; `bad` puts a NaN in it.
fn write_step(path: &Path, scale: f32, stretch: f32, bad: bool) {
    write_step_at(path, scale, stretch, bad, 0.0);
}

/// [`write_step`] with the cube moved `offset` along x.
fn write_step_at(path: &Path, scale: f32, stretch: f32, bad: bool, offset: f32) {
    let (min, max) = (
        Vec3::new(offset, 0.0, 0.0),
        Vec3::new(offset + stretch, 1.0, 1.0),
    );
    let mut mesh = box_grid(min, max, [1, 1, 1], CellSplit::Six).expect("the cube");
    let spec = ScalarSpec::Linear {
        offset: -scale * offset / stretch,
        gradient: Vec3::new(scale / stretch, 2.0 * scale, 3.0 * scale),
    };
    add_field(&mut mesh, "f", spec);
    if bad {
        mesh.fields[0].values[5] = f32::NAN;
    }
    let mut file = std::fs::File::create(path).expect("create a step");
    write_legacy(&mesh, &mut file, false).expect("write a step");
}

/// A series of steps `(scale, stretch, bad)` in a fresh folder.
fn series(name: &str, steps: &[(f32, f32, bool)]) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("tetray-engine-steps-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let mut files = Vec::new();
    for (k, &(scale, stretch, bad)) in steps.iter().enumerate() {
        write_step(&dir.join(format!("s{k}.vtk")), scale, stretch, bad);
        files.push(format!(r#"{{"name": "s{k}.vtk", "time": {k}}}"#));
    }
    let path = dir.join("run.series");
    std::fs::write(
        &path,
        format!(
            r#"{{"file-series-version": "1.0", "files": [{}]}}"#,
            files.join(", ")
        ),
    )
    .expect("write the series");
    path
}

fn options() -> FrameOptions {
    FrameOptions {
        size: (16, 12),
        ..FrameOptions::default()
    }
}

const QUIET: Log<'static> = Log {
    info: &|_| {},
    warn: &|_| {},
};

#[test]
fn a_step_of_the_same_mesh_brings_only_its_fields() {
    let path = series("kept", &[(1.0, 1.0, false), (2.0, 1.0, false)]);
    let mut steps = TimeSteps::new(&path, Default::default());
    assert_eq!(steps.times().expect("times"), vec![0.0, 1.0]);
    let mut setup = steps.prepare(Some(0), &options(), QUIET).expect("step 0");
    assert_eq!(setup.extent.range, (0.0, 6.0));
    let cost = steps
        .advance(&mut setup, 1, &options(), QUIET)
        .expect("step 1");
    assert!(cost.kept, "{cost:?}");
    // Exactly what a setup made from scratch for step 1 holds.
    let fresh = TimeSteps::new(&path, Default::default())
        .prepare(Some(1), &options(), QUIET)
        .expect("step 1 from scratch");
    assert_eq!(setup.extent, fresh.extent);
    assert_eq!(setup.extent.range, (0.0, 12.0));
    let (kept, made) = (setup.scene().expect("scene"), fresh.scene().expect("scene"));
    assert_eq!(kept.scalar, made.scalar);
    assert_eq!(kept.mesh.tets, made.mesh.tets);
    assert_eq!(kept.point_records(), made.point_records());
    assert_eq!(setup.tf, fresh.tf);
    assert_eq!(setup.camera, fresh.camera);
    // The range over both steps, as an animation's colour range.
    assert_eq!(
        steps.range(&[0, 1], None).expect("range"),
        Some((0.0, 12.0))
    );
}

#[test]
fn a_moving_mesh_is_made_anew_from_the_first_view() {
    let path = series("moving", &[(1.0, 1.0, false), (1.0, 1.5, false)]);
    let mut steps = TimeSteps::new(&path, Default::default());
    let mut setup = steps.prepare(Some(0), &options(), QUIET).expect("step 0");
    let first = setup.camera;
    let cost = steps
        .advance(&mut setup, 1, &options(), QUIET)
        .expect("step 1");
    assert!(!cost.kept, "{cost:?}");
    assert_eq!(setup.camera, first);
    assert_eq!(setup.extent.bounds.1.x, 1.5);
    // Made from scratch, step 1 would be framed otherwise.
    let fresh = TimeSteps::new(&path, Default::default())
        .prepare(Some(1), &options(), QUIET)
        .expect("step 1 from scratch");
    assert_ne!(fresh.camera, first);
}

#[test]
fn a_bad_field_in_a_later_step_is_an_error_and_changes_nothing() {
    let path = series("bad", &[(1.0, 1.0, false), (2.0, 1.0, true)]);
    let mut steps = TimeSteps::new(&path, Default::default());
    let mut setup = steps.prepare(Some(0), &options(), QUIET).expect("step 0");
    let before = setup.scene().expect("scene").scalar.clone();
    let error = steps.advance(&mut setup, 1, &options(), QUIET);
    let message = tetray_engine::error_chain(&error.expect_err("a NaN is refused"));
    assert!(message.contains("s1.vtk"), "{message}");
    assert!(message.to_lowercase().contains("nan"), "{message}");
    assert_eq!(setup.scene().expect("scene").scalar, before);
    assert_eq!(setup.extent.range, (0.0, 6.0));
}

/// Points that move over the same cells: the first such step builds its
/// topology, the next takes it from the step before, and the setup it
/// makes is the one made from scratch for that step (same tetrahedra,
/// neighbours, boundary faces, field), from the first step's view.
#[test]
fn moving_points_take_the_topology_of_the_step_before() {
    let path = series(
        "topology",
        &[(1.0, 1.0, false), (1.0, 1.5, false), (1.0, 2.0, false)],
    );
    let mut steps = TimeSteps::new(&path, Default::default());
    let mut setup = steps.prepare(Some(0), &options(), QUIET).expect("step 0");
    let first = setup.camera;
    let one = steps
        .advance(&mut setup, 1, &options(), QUIET)
        .expect("step 1");
    assert!(!one.kept && !one.topology_kept, "{one:?}");
    let two = steps
        .advance(&mut setup, 2, &options(), QUIET)
        .expect("step 2");
    assert!(!two.kept && two.topology_kept, "{two:?}");
    assert_eq!(setup.camera, first);
    let fresh = TimeSteps::new(&path, Default::default())
        .prepare(Some(2), &options(), QUIET)
        .expect("step 2 from scratch");
    let (a, b) = (setup.scene().expect("scene"), fresh.scene().expect("scene"));
    assert_eq!(a.mesh.tets, b.mesh.tets);
    assert_eq!(a.topology, b.topology);
    assert_eq!(a.point_records(), b.point_records());
    assert_eq!(setup.extent, fresh.extent);
}

/// A mesh far from the file's origin is stored relative to each step's
/// centre; when its points move, a step made anew keeps the first step's
/// camera in the file's coordinates (moved to the new step's origin), and
/// the first step's opacity unit distance.
#[test]
fn a_moving_mesh_far_away_keeps_the_view_in_file_coordinates() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("tetray-engine-steps-far");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    write_step_at(&dir.join("a.vtk"), 1.0, 1.0, false, 1.0e6);
    write_step_at(&dir.join("b.vtk"), 1.0, 1.5, false, 1.0e6);
    let path = dir.join("far.series");
    std::fs::write(
        &path,
        r#"{"file-series-version": "1.0", "files": [{"name": "a.vtk", "time": 0}, {"name": "b.vtk", "time": 1}]}"#,
    )
    .expect("write the series");
    let mut steps = TimeSteps::new(&path, Default::default());
    let mut setup = steps.prepare(Some(0), &options(), QUIET).expect("step 0");
    let (first, origin, unit) = (setup.camera, setup.extent.origin, setup.unit_distance);
    assert!(origin.x > 0.9e6, "centred: {origin}");
    steps
        .advance(&mut setup, 1, &options(), QUIET)
        .expect("step 1");
    assert_ne!(setup.extent.origin, origin);
    let world = |p: glam::Vec3, o: glam::DVec3| p.as_dvec3() + o;
    let moved = world(setup.camera.focal_point, setup.extent.origin);
    assert!(
        (moved - world(first.focal_point, origin)).length() < 1e-3,
        "{moved}"
    );
    let moved = world(setup.camera.position, setup.extent.origin);
    assert!(
        (moved - world(first.position, origin)).length() < 1e-3,
        "{moved}"
    );
    assert_eq!(setup.unit_distance, unit);
}
