//! End-to-end tests of `--renderer shear-warp`: `render` and `bench` read a
//! generated grid as its regular grid alone (no tetrahedra), `compare`
//! loads the tetrahedra for its reference and renders shear-warp beside
//! it; files that are not uniform grids are refused with one line.

use std::path::{Path, PathBuf};

use serde_json::Value;

mod support;
use support::{run, text};

fn scratch(test: &str) -> PathBuf {
    support::scratch("cli-shearwarp", test)
}

/// A 12^3 grid `g.vti` in `dir`.
fn grid(dir: &Path) {
    let out = run(
        dir,
        &["generate", "grid", "--dims", "12,12,12", "-o", "g.vti"],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
}

#[test]
fn render_and_bench_read_the_grid_alone() {
    let dir = scratch("render_and_bench");
    grid(&dir);
    let out = run(
        &dir,
        &[
            "render",
            "g.vti",
            "--renderer",
            "shear-warp",
            "--size",
            "64x64",
            "-o",
            "sw.png",
        ],
    );
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        stdout.contains("as its regular grid (no tetrahedra)"),
        "{stdout}"
    );
    assert!(!stdout.contains("tetrahedra,"), "{stdout}");
    assert!(stdout.contains("renderer: shear-warp"), "{stdout}");
    assert!(dir.join("sw.png").is_file());

    let out = run(
        &dir,
        &[
            "bench",
            "g.vti",
            "--renderer",
            "shear-warp",
            "--integrator",
            "riemann",
            "--size",
            "32x32",
            "--frames",
            "2",
        ],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: Value = serde_json::from_slice(&out.stdout).expect("bench JSON");
    assert_eq!(json["renderer"], "shear-warp");
    assert_eq!(json["tets"], 0);
    assert!(json["ms_per_frame_median"].as_f64().unwrap() > 0.0);
}

#[test]
fn compare_puts_shear_warp_beside_the_tetrahedral_reference() {
    let dir = scratch("compare");
    grid(&dir);
    let out = run(
        &dir,
        &[
            "compare",
            "g.vti",
            "--methods",
            "cpu:exact,shear-warp,shear-warp:riemann",
            "--size",
            "48x48",
            "--frames",
            "1",
            "-o",
            "cmp",
        ],
    );
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(stdout.contains("shear-warp pre-integrated"), "{stdout}");
    assert!(stdout.contains("shear-warp post-classified"), "{stdout}");
}

#[test]
fn other_files_are_refused_with_one_line() {
    let dir = scratch("refused");
    std::fs::write(dir.join("grid.vtk"), support::grid_vtk()).unwrap();
    for args in [
        &["render", "--renderer", "shear-warp", "-o", "a.png"][..],
        &[
            "render",
            "grid.vtk",
            "--renderer",
            "shear-warp",
            "-o",
            "a.png",
        ][..],
    ] {
        let out = run(&dir, args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{args:?}: {stderr}");
    }
}
