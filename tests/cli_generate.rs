//! End-to-end tests of `tetray generate`: small meshes generated, their
//! JSON summaries checked against the files, then loaded by `tetray info`;
//! bad arguments rejected with one line and exit code 1.

use std::path::{Path, PathBuf};

use serde_json::Value;

mod support;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/plot3d")
}

/// Runs tetray with `args` in `dir`, the PLOT3D datasets named by
/// TETRAY_DATA_DIR (a scratch folder has no data/plot3d, and the test's
/// executable may be built outside the checkout).
fn run_in(dir: &Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(support::BIN)
        .args(args)
        .current_dir(dir)
        .env("TETRAY_DATA_DIR", data_dir())
        .output()
        .expect("run tetray")
}

/// A fresh folder under the target directory for one test.
fn scratch(test: &str) -> PathBuf {
    support::scratch("cli-generate", test)
}

fn json(dir: &Path, args: &[&str]) -> Value {
    let out = run_in(dir, args);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "tetray {args:?} failed:\n{stderr}");
    serde_json::from_str(&stdout)
        .unwrap_or_else(|e| panic!("tetray {args:?}: stdout is not JSON ({e}):\n{stdout}"))
}

fn count(v: &Value) -> u64 {
    v.as_u64().unwrap_or_else(|| panic!("{v} is not a count"))
}

/// Each file of the summary (paths as given, relative to `dir`) exists
/// with the size it gives; returns the total.
fn check_files(dir: &Path, summary: &Value) -> u64 {
    let files = summary["files"].as_array().expect("files");
    let mut total = 0;
    for file in files {
        let path = file["path"].as_str().expect("path");
        let size = std::fs::metadata(dir.join(path)).expect(path).len();
        assert_eq!(count(&file["bytes"]), size, "{path}");
        total += size;
    }
    assert_eq!(count(&summary["bytes"]), total);
    total
}

#[test]
fn generate_solid_then_info() {
    let dir = scratch("solid");
    let summary = json(
        &dir,
        &["generate", "solid", "--tets", "20000", "-o", "shell.vtu"],
    );
    assert_eq!(summary["kind"], "solid");
    assert_eq!(count(&summary["requested_tets"]), 20_000);
    let tets = count(&summary["tets"]);
    assert!((20_000..21_000).contains(&tets), "{summary}");
    check_files(&dir, &summary);

    let info = json(&dir, &["info", "shell.vtu", "--json"]);
    assert_eq!(info["valid"], true);
    assert_eq!(count(&info["tets"]), tets);
    assert_eq!(info["points"], summary["points"]);
    assert_eq!(count(&info["components"]), 1);
    assert_eq!(count(&info["reoriented"]), 0);
    let names: Vec<&str> = info["fields"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["wave", "linear"]);

    // The same shell partitioned: 3 piece files welded back into it.
    let parts = json(
        &dir,
        &[
            "generate",
            "solid",
            "--tets",
            "20000",
            "--pieces",
            "3",
            "-o",
            "shell.pvtu",
        ],
    );
    assert_eq!(parts["files"].as_array().map(Vec::len), Some(4), "{parts}");
    check_files(&dir, &parts);
    let joined = json(&dir, &["info", "shell.pvtu", "--json"]);
    assert_eq!(joined["tets"], info["tets"]);
    assert_eq!(joined["points"], info["points"]);
    assert_eq!(joined["pieces"], 3);
    assert_eq!(count(&joined["components"]), 1);
    assert_eq!(count(&joined["seam_faces"]), 0);
}

/// `--steps 3` writes a series of three files sharing points and cells,
/// at times 0, 1/3, 2/3: "linear" grows as (1 + t)(x + 2y + 3z) (its
/// range scales by 1 + t, to f32 rounding) and "wave" travels.
#[test]
fn generate_solid_steps_make_a_series() {
    let dir = scratch("steps");
    let summary = json(
        &dir,
        &[
            "generate",
            "solid",
            "--tets",
            "2000",
            "--steps",
            "3",
            "-o",
            "run.series",
        ],
    );
    assert_eq!(
        summary["files"].as_array().map(Vec::len),
        Some(4),
        "{summary}"
    );
    check_files(&dir, &summary);
    let field = |info: &Value, name: &str| -> (f64, f64) {
        let f = info["fields"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["name"] == name)
            .unwrap_or_else(|| panic!("{name}"));
        (f["min"].as_f64().unwrap(), f["max"].as_f64().unwrap())
    };
    let first = json(&dir, &["info", "run.series", "--json"]);
    assert_eq!(
        first["times"].as_array().map(Vec::len),
        Some(3),
        "{}",
        first["times"]
    );
    let (lo, hi) = field(&first, "linear");
    for k in 1..3 {
        let step = k.to_string();
        let info = json(
            &dir,
            &["info", "run.series", "--time-step", &step, "--json"],
        );
        assert_eq!(info["tets"], first["tets"]);
        assert_eq!(info["points"], first["points"]);
        let scale = 1.0 + f64::from(k) / 3.0;
        let (a, b) = field(&info, "linear");
        assert!(
            (a - scale * lo).abs() < 1e-5 * scale * lo.abs(),
            "step {k}: {a} vs {lo}"
        );
        assert!(
            (b - scale * hi).abs() < 1e-5 * scale * hi.abs(),
            "step {k}: {b} vs {hi}"
        );
        assert_ne!(field(&info, "wave"), field(&first, "wave"), "step {k}");
    }
}

#[test]
fn generate_plot3d_then_info() {
    let dir = scratch("plot3d");
    // Below the dataset's own size: factors 1, the grid written back. No
    // --data-dir, run from a scratch folder: the dataset is found through
    // TETRAY_DATA_DIR (`json` sets it to the repository's data/plot3d).
    let summary = json(
        &dir,
        &[
            "generate",
            "plot3d",
            "--dataset",
            "bluntfin",
            "--tets",
            "20000",
            "-o",
            "out",
        ],
    );
    let source = PathBuf::from(summary["source"].as_str().expect("source"));
    assert_eq!(
        source.canonicalize().unwrap(),
        data_dir().join("bluntfinxyz.bin").canonicalize().unwrap()
    );
    assert_eq!(summary["factors"], serde_json::json!([1, 1, 1]));
    assert_eq!(count(&summary["tets"]), 187_395 - 77);
    assert_eq!(check_files(&dir, &summary), 491_532 + 819_228);
    // `info` finds the q file beside the grid.
    let info = json(&dir, &["info", "out/bluntfinxyz.bin", "--json"]);
    assert_eq!(info["tets"], summary["tets"]);
    assert_eq!(info["fields"].as_array().unwrap().len(), 5);

    // A level of doubling of a file written before (--grid): 8 times the
    // hexahedra, the q sibling refined with it.
    let summary = json(
        &dir,
        &[
            "generate",
            "plot3d",
            "--grid",
            "out/bluntfinxyz.bin",
            "--level",
            "1",
            "-o",
            "twice",
        ],
    );
    assert_eq!(summary["factors"], serde_json::json!([2, 2, 2]));
    assert_eq!(summary["dims"], serde_json::json!([79, 63, 63]));
    assert_eq!(count(&summary["hexahedra"]), 8 * 37_479);
    assert_eq!(summary["files"].as_array().unwrap().len(), 2);
    check_files(&dir, &summary);
}

#[test]
fn bad_arguments_are_one_line_and_exit_1() {
    let dir = scratch("bad");
    let data = data_dir();
    let data = data.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["generate", "solid", "--tets", "0", "-o", "a.vtu"],
            "--tets",
        ),
        (
            &["generate", "solid", "--tets", "ten", "-o", "a.vtu"],
            "--tets",
        ),
        (
            &["generate", "solid", "--tets", "2000000000", "-o", "a.vtu"],
            "at most",
        ),
        (
            &["generate", "solid", "--tets", "1000", "-o", "a.vtk"],
            ".vtu",
        ),
        (&["generate", "solid", "-o", "a.vtu"], "--tets"),
        (
            &["generate", "plot3d", "--dataset", "bluntfin", "-o", "x"],
            "--tets",
        ),
        (
            &[
                "generate",
                "plot3d",
                "--dataset",
                "wing",
                "--tets",
                "1M",
                "-o",
                "x",
            ],
            "wing",
        ),
        (
            &[
                "generate",
                "plot3d",
                "--dataset",
                "post",
                "--data-dir",
                "nowhere",
                "--tets",
                "1M",
                "-o",
                "x",
            ],
            "nowhere: no such folder (--data-dir)",
        ),
        (
            &[
                "generate",
                "plot3d",
                "--dataset",
                "comb",
                "--data-dir",
                data,
                "--tets",
                "1M",
                "-o",
                data,
            ],
            "overwrite",
        ),
        (
            &[
                "generate",
                "plot3d",
                "--dataset",
                "comb",
                "--tets",
                "1M",
                "--level",
                "1",
                "-o",
                "x",
            ],
            "--level",
        ),
    ];
    for (args, named) in cases {
        let out = run_in(&dir, args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "tetray {args:?}:\n{stderr}");
        let lines: Vec<&str> = stderr.lines().collect();
        assert_eq!(lines.len(), 1, "tetray {args:?}: not one line:\n{stderr}");
        assert!(lines[0].starts_with("error: "), "{}", lines[0]);
        assert!(
            lines[0].contains(named),
            "tetray {args:?}: {} lacks {named:?}",
            lines[0]
        );
    }
}
