//! Time series of files: ParaView's JSON file series and `.pvd` data
//! collections, each step read by its own file's reader.

use std::path::{Path, PathBuf};

use tetray_io::{LoadOptions, LoadedMesh, load};

fn data(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(path)
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("series");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir.join(name)
}

fn step(path: &Path, time_step: Option<usize>, time: Option<f64>) -> LoadedMesh {
    let opts = LoadOptions {
        time_step,
        time,
        ..LoadOptions::default()
    };
    load(path, &opts).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn same_mesh(a: &LoadedMesh, b: &LoadedMesh) {
    // `assert!`, not `assert_eq!`: a difference would print whole meshes.
    assert!(a.mesh.points == b.mesh.points, "points differ");
    assert!(a.mesh.tets == b.mesh.tets, "tetrahedra differ");
    assert!(a.mesh.fields == b.mesh.fields, "fields differ");
}

/// The crushed can's three VTKHDF steps: each step of the series is its
/// file read alone, with the series' times; the points move between steps
/// while the cells stay.
#[test]
fn a_file_series_reads_the_chosen_steps_file() {
    let series = data("real/series/can/can.hdf.series");
    let first = step(&series, None, None);
    assert_eq!(first.report.times, vec![0.0, 1.0, 2.0]);
    assert_eq!(first.report.time_step, Some(0));
    assert_eq!(first.report.format, "VTKHDF");
    for (i, name) in ["can_0.hdf", "can_1.hdf", "can_2.hdf"].iter().enumerate() {
        let alone = step(&data(&format!("real/series/can/{name}")), None, None);
        same_mesh(&step(&series, Some(i), None), &alone);
    }
    let nearest = step(&series, None, Some(1.6));
    assert_eq!(nearest.report.time_step, Some(2));
    // The same hexahedra on moved points (which of them fold, and are
    // split around an added point or left out, changes with the crushing:
    // the file's points come first, the added ones after).
    assert_eq!(nearest.report.cells_split, first.report.cells_split);
    let file_points = |l: &LoadedMesh| l.mesh.points.len() - l.report.points_added;
    assert_eq!(file_points(&nearest), file_points(&first));
    let n = file_points(&first);
    assert!(
        nearest.mesh.points[..n] != first.mesh.points[..n],
        "the points move"
    );
    let past = load(
        &series,
        &LoadOptions {
            time_step: Some(3),
            ..LoadOptions::default()
        },
    )
    .expect_err("step 3 of 3");
    assert!(
        past.to_string().contains("time step 3 is out of range"),
        "{past}"
    );
}

/// A `.pvd` collection: a step of one file, and a step of four parts (the
/// blood-vessel pieces) welded into the same mesh as their `.pvtu`. The
/// steps are listed out of time order.
#[test]
fn a_data_collection_welds_the_parts_of_a_step() {
    let vessels = data("real/blood_vessels/T0000000500");
    let tetra = data("real/tetra.vtu");
    let mut text = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n",
    );
    for part in 0..4 {
        text += &format!(
            "<DataSet timestep=\"2.5\" part=\"{part}\" file=\"{}/00{part}.vtu\"/>\n",
            vessels.display()
        );
    }
    text += &format!(
        "<DataSet timestep=\"1\" part=\"0\" file=\"{}\"/>\n",
        tetra.display()
    );
    text += "</Collection>\n</VTKFile>\n";
    let pvd = scratch("mixed.pvd");
    std::fs::write(&pvd, text).expect("write pvd");

    let first = step(&pvd, None, None);
    assert_eq!(first.report.times, vec![1.0, 2.5]);
    same_mesh(&first, &step(&tetra, None, None));
    let parts = step(&pvd, Some(1), None);
    let whole = step(&data("real/blood_vessels/T0000000500.pvtu"), None, None);
    assert_eq!(parts.mesh.points.len(), whole.mesh.points.len());
    assert_eq!(parts.mesh.tets.len(), whole.mesh.tets.len());
    assert_eq!(
        parts.topology.boundary_faces.len(),
        whole.topology.boundary_faces.len()
    );
}

#[test]
fn broken_series_are_one_line_errors() {
    let cases = [
        (
            "missing.series",
            r#"{"files": [{"name": "nowhere.vtu", "time": 0}]}"#,
            "nowhere.vtu",
        ),
        (
            "empty.series",
            r#"{"file-series-version": "1.0", "files": []}"#,
            "names no file",
        ),
        (
            "self.series",
            r#"{"files": [{"name": "self.series", "time": 0}]}"#,
            "itself a series",
        ),
        (
            "bad.pvd",
            r#"<VTKFile type="Collection"><Collection><DataSet file="a.vtu" timestep="x"/>"#,
            "not a number",
        ),
    ];
    for (name, text, says) in cases {
        let path = scratch(name);
        std::fs::write(&path, text).expect("write");
        let err = load(&path, &LoadOptions::default()).expect_err(name);
        let message = err.to_string();
        assert!(
            message.contains(says) && !message.contains('\n'),
            "{name}: {message}"
        );
    }
}
