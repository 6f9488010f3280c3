//! What the GPU command-line tests share: the binary, a scratch folder per
//! test, running it, and whether an adapter exists.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub const BIN: &str = env!("CARGO_BIN_EXE_tetray");

/// An empty folder for `test` under Cargo's scratch space for tests.
pub fn scratch(group: &str, test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(group)
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the scratch folder");
    dir
}

/// Runs tetray with `args` in `dir`.
pub fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run tetray")
}

pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Whether an adapter exists; panics when one is required and missing
/// (`TETRAY_REQUIRE_GPU=1`, as CI sets with lavapipe).
pub fn have_gpu() -> bool {
    let out = Command::new(BIN)
        .args(["info", "--gpu", "--json"])
        .output()
        .expect("run");
    if out.status.success() {
        return true;
    }
    let why = text(&out.stderr);
    if std::env::var("TETRAY_REQUIRE_GPU").as_deref() == Ok("1") {
        panic!("TETRAY_REQUIRE_GPU=1 but `tetray info --gpu` failed: {why}");
    }
    eprintln!("\n!!! SKIPPING GPU CLI TEST: {why} !!!\n");
    false
}

/// A convex, connected mesh for the projection: 2 x 2 x 2 hexahedra of the
/// unit cube (split into tetrahedra on load), a scalar rising along x, y, z.
pub fn grid_vtk() -> String {
    let n = 3;
    let mut points = String::new();
    let mut scalars = String::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let (x, y, z) = (i as f32 / 2.0, j as f32 / 2.0, k as f32 / 2.0);
                points += &format!("{x} {y} {z}\n");
                scalars += &format!("{}\n", x + 0.5 * y + 0.25 * z);
            }
        }
    }
    let id = |i: usize, j: usize, k: usize| i + n * (j + n * k);
    let mut cells = String::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                cells += &format!(
                    "8 {} {} {} {} {} {} {} {}\n",
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1)
                );
            }
        }
    }
    format!(
        "# vtk DataFile Version 3.0\ngrid\nASCII\nDATASET UNSTRUCTURED_GRID\n\
         POINTS 27 float\n{points}CELLS 8 72\n{cells}CELL_TYPES 8\n{}\
         POINT_DATA 27\nSCALARS s float 1\nLOOKUP_TABLE default\n{scalars}",
        "12\n".repeat(8)
    )
}
