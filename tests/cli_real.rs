//! Every file of `data/real` (VTK's test-data collection, as their writers
//! made them) through the binary as a user runs it: `info --json` reads
//! the counts, `render` makes an image with something in it and says what
//! it had to change, and the one file with no volume cell is one clear
//! error.

use std::path::{Path, PathBuf};

use serde_json::Value;

mod support;
use support::{run, text};

fn real(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/real")
        .join(name)
}

/// The volumetric samples, with the tetrahedra each must give at least
/// (a lower bound from its cell count: one tetrahedron per linear cell, 8
/// per quadratic tetrahedron; exact counts are the mesh crate's tests).
const VOLUMES: [(&str, u64); 10] = [
    // 7472 HEX8 cells.
    ("disk_out_ref.ex2", 7472),
    // 39,353 cells over 4 pieces.
    ("blood_vessels/T0000000500.pvtu", 39_353),
    // 5 x 11 x 8 hexahedra.
    ("StructuredGrid.vts", 440),
    // 96 quadratic tetrahedra, 8 tetrahedra each.
    ("QuadraticTetra.vtu", 768),
    ("tetra.vtu", 8),
    ("QuadraticWedge.vtu", 48),
    ("notch_disp.vtu", 2192),
    ("polyhedron2pieces.vtu", 2),
    ("can.vtu", 1000),
    ("uGridEx.vtk", 4),
];

/// Cell counts read from the files' headers: `NumberOfCells` of the XML
/// files, `num_elem` of the Exodus file.
const FILE_CELLS: [(&str, u64); 4] = [
    ("disk_out_ref.ex2", 7472),
    ("QuadraticTetra.vtu", 96),
    // 39 of its cells are tangled and left out of the walk.
    ("can.vtu", 4800),
    ("StructuredGrid.vts", 440),
];

#[test]
fn every_volumetric_sample_loads_and_renders() {
    let dir = support::scratch("cli-real", "render");
    for (name, min_tets) in VOLUMES {
        let path = real(name);
        let file = path.to_str().expect("UTF-8 path");
        let out = run(&dir, &["info", "--json", file]);
        assert!(out.status.success(), "info {name}: {}", text(&out.stderr));
        let info: Value = serde_json::from_slice(&out.stdout).expect("JSON");
        let tets = info["tets"].as_u64().expect("tets");
        assert!(tets >= min_tets, "{name}: {tets} tetrahedra: {info}");
        // The cells as the file counts them (NumberOfCells / num_elem),
        // those left out of the walk included.
        if let Some(&(_, cells)) = FILE_CELLS.iter().find(|(n, _)| *n == name) {
            assert_eq!(info["input_cells"], cells, "{name}: {info}");
        }

        let image = dir.join("image.exr");
        let out = run(
            &dir,
            &[
                "render",
                file,
                "--size",
                "40x40",
                "--renderer",
                "cpu",
                "-o",
                image.to_str().expect("UTF-8"),
            ],
        );
        let said = format!("{}{}", text(&out.stdout), text(&out.stderr));
        assert!(out.status.success(), "render {name}:\n{said}");
        // What had to change is one summary line: the can's tangled cells
        // left out, uGridEx's faces split the other way made boundary.
        if matches!(name, "can.vtu" | "uGridEx.vtk") {
            let summary: Vec<&str> = said
                .lines()
                .filter(|l| l.starts_with("mesh changed on load: "))
                .collect();
            assert_eq!(summary.len(), 1, "{name}:\n{said}");
            let want = if name == "can.vtu" {
                "39 cells left out"
            } else {
                "non-conforming faces made boundary"
            };
            assert!(summary[0].contains(want), "{name}: {}", summary[0]);
        }
        let pixels = image::open(&image).expect("EXR").into_rgba32f().into_raw();
        // Something of the volume is in view: at least 1% of the pixels
        // have some opacity. The smallest in view is tetra.vtu (27 lit):
        // its one quadratic tetrahedron shares the file with two quadratic
        // triangles and unused points, which the fit of the bounds frames
        // too, as ParaView's ResetCamera does.
        let lit = pixels.chunks(4).filter(|p| p[3] > 1e-4).count();
        assert!(lit >= 16, "{name}: {lit} pixels lit:\n{said}");
        eprintln!("{name}: {tets} tetrahedra, {lit} of 1600 pixels lit");
    }
}

#[test]
fn a_multi_block_file_of_surfaces_is_one_clear_error() {
    let dir = support::scratch("cli-real", "surfaces");
    let path = real("ex-blow_5.vtm");
    for command in ["info", "render"] {
        let out = run(&dir, &[command, path.to_str().expect("UTF-8")]);
        assert_eq!(out.status.code(), Some(1), "{command}");
        let stderr = text(&out.stderr);
        let lines: Vec<&str> = stderr.lines().collect();
        assert_eq!(lines.len(), 1, "{command}: {stderr}");
        assert!(lines[0].starts_with("error: "), "{stderr}");
        assert!(lines[0].contains("ex-blow_5.vtm"), "{stderr}");
        assert!(lines[0].contains("surface"), "{stderr}");
    }
}

/// `--linearize corners` keeps the corner nodes only (VTK's volume mappers'
/// view of a quadratic cell): one tetrahedron per quadratic tetrahedron
/// instead of 8.
#[test]
fn quadratic_cells_subdivide_or_keep_their_corners() {
    let dir = support::scratch("cli-real", "linearize");
    let path = real("QuadraticTetra.vtu");
    let file = path.to_str().expect("UTF-8");
    let tets = |extra: &[&str]| {
        let mut args = vec!["info", "--json", file];
        args.extend_from_slice(extra);
        let out = run(&dir, &args);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let info: Value = serde_json::from_slice(&out.stdout).expect("JSON");
        info["tets"].as_u64().expect("tets")
    };
    assert_eq!(tets(&[]), 8 * 96);
    assert_eq!(tets(&["--linearize", "corners"]), 96);
}

/// Exodus time steps: `info` lists them; a step the file does not store is
/// one clear error naming the file and how many it has.
#[test]
fn exodus_time_steps_are_listed_and_checked() {
    let dir = support::scratch("cli-real", "time-steps");
    let path = real("disk_out_ref.ex2");
    let file = path.to_str().expect("UTF-8");
    let out = run(&dir, &["info", file]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let said = text(&out.stdout);
    assert!(said.contains("time steps:      1 (read step 0"), "{said}");
    let out = run(&dir, &["info", file, "--time-step", "1"]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = text(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("disk_out_ref.ex2"), "{stderr}");
    assert!(stderr.contains("time step 1 is out of range"), "{stderr}");
}
