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

/// One volumetric sample: what VTK's own reader (VTK 9.1,
/// `vtkXMLGenericDataObjectReader`, `vtkUnstructuredGridReader`,
/// `vtkExodusIIReader`) counts in it, and what `info --json` must say.
struct Sample {
    name: &'static str,
    /// Points as VTK reads them.
    vtk_points: u64,
    /// Volume cells as VTK reads them (surface cells, lines and vertices
    /// not counted): `input_cells` must equal it.
    vtk_volume_cells: u64,
    /// Points after loading: VTK's, less the duplicates welded across
    /// pieces, plus the face and cell centres that quadratic hexahedra and
    /// wedges are split about.
    points: u64,
    /// Tetrahedra the walk uses (cells left out not counted).
    tets: u64,
}

const VOLUMES: [Sample; 16] = [
    // 7472 hexahedra, 6 tetrahedra each.
    Sample {
        name: "disk_out_ref.ex2",
        vtk_points: 8499,
        vtk_volume_cells: 7472,
        points: 8499,
        tets: 44_832,
    },
    // 39,353 voxels over 4 pieces: 6 tetrahedra each, 5 for the 191 whose
    // face diagonals (cut through each face's smallest point index) allow
    // it; 1382 points repeated on the pieces' shared faces are welded.
    Sample {
        name: "blood_vessels/T0000000500.pvtu",
        vtk_points: 48_823,
        vtk_volume_cells: 39_353,
        points: 47_441,
        tets: 235_927,
    },
    // 5 x 11 x 8 hexahedra, 6 tetrahedra each.
    Sample {
        name: "StructuredGrid.vts",
        vtk_points: 648,
        vtk_volume_cells: 440,
        points: 648,
        tets: 2640,
    },
    // 96 quadratic tetrahedra, 8 tetrahedra each on their own nodes.
    Sample {
        name: "QuadraticTetra.vtu",
        vtk_points: 189,
        vtk_volume_cells: 96,
        points: 189,
        tets: 768,
    },
    // One quadratic tetrahedron; the file's two quadratic triangles are
    // surface cells.
    Sample {
        name: "tetra.vtu",
        vtk_points: 22,
        vtk_volume_cells: 1,
        points: 22,
        tets: 8,
    },
    // 16 quadratic wedges, 24 tetrahedra each about added face centres.
    Sample {
        name: "QuadraticWedge.vtu",
        vtk_points: 93,
        vtk_volume_cells: 16,
        points: 125,
        tets: 384,
    },
    // 2188 quadratic hexahedra and 4 quadratic wedges.
    Sample {
        name: "notch_disp.vtu",
        vtk_points: 12_717,
        vtk_volume_cells: 2192,
        points: 22_735,
        tets: 100_329,
    },
    // Two pyramids (2 tetrahedra each) and two polyhedra, split about a
    // centre point each.
    Sample {
        name: "polyhedron2pieces.vtu",
        vtk_points: 18,
        vtk_volume_cells: 4,
        points: 20,
        tets: 28,
    },
    // 4800 hexahedra, 39 of them folded: 6 split around an added point
    // (12 tetrahedra each), 33 left out of the walk (composited in their
    // holes): (4800 - 39) x 6 + 6 x 12.
    Sample {
        name: "can.vtu",
        vtk_points: 6724,
        vtk_volume_cells: 4800,
        points: 6730,
        tets: 28_638,
    },
    // The same model written by VTK as VTKHDF 1.0 (vtkHDFReader counts the
    // same 6724 points and 4800 cells).
    Sample {
        name: "can-vtu.hdf",
        vtk_points: 6724,
        vtk_volume_cells: 4800,
        points: 6730,
        tets: 28_638,
    },
    // OpenFOAM's cavity case, opened by its folder: 400 hexahedra one
    // cell thick (vtkOpenFOAMReader: 882 points, 400 cells), 6 each.
    Sample {
        name: "openfoam/cavity",
        vtk_points: 882,
        vtk_volume_cells: 400,
        points: 882,
        tets: 2400,
    },
    // EnSight Gold, every element type: 8 volume cells of 16 (VTK's
    // vtkGenericEnSightReader: 108 + 4 points in two parts, 16 cells);
    // the quadratic cells and the polyhedron add their centres (11
    // points), the linear tetrahedron is kept, 7 cells give 107.
    Sample {
        name: "ensight/elements.case",
        vtk_points: 112,
        vtk_volume_cells: 8,
        points: 123,
        tets: 108,
    },
    // CGNS, four structured zones of a CFL3D solution in the ADF storage
    // (vtkCGNSReader: 58,576 vertices, 28,168 cells), 1010 shared
    // vertices welded; 12 flat tetrahedra of collapsed cells left out of
    // 28,168 x 6; and its HDF5 twin converted by adf2hdf.
    Sample {
        name: "multi.cgns",
        vtk_points: 58_576,
        vtk_volume_cells: 28_168,
        points: 57_566,
        tets: 168_996,
    },
    Sample {
        name: "multi-hdf5.cgns",
        vtk_points: 58_576,
        vtk_volume_cells: 28_168,
        points: 57_566,
        tets: 168_996,
    },
    // A ParaView file series over three VTKHDF steps: the first step,
    // crushed less, has no tangled cell (4800 x 6).
    Sample {
        name: "series/can/can.hdf.series",
        vtk_points: 6724,
        vtk_volume_cells: 4800,
        points: 6724,
        tets: 28_800,
    },
    // 12 cells of which 4 are volume cells: two hexahedra (6 tetrahedra
    // each) and two tetrahedra.
    Sample {
        name: "uGridEx.vtk",
        vtk_points: 27,
        vtk_volume_cells: 4,
        points: 27,
        tets: 14,
    },
];

#[test]
fn every_volumetric_sample_loads_and_renders() {
    let dir = support::scratch("cli-real", "render");
    for sample in VOLUMES {
        let name = sample.name;
        let path = real(name);
        let file = path.to_str().expect("UTF-8 path");
        let out = run(&dir, &["info", "--json", file]);
        assert!(out.status.success(), "info {name}: {}", text(&out.stderr));
        let info: Value = serde_json::from_slice(&out.stdout).expect("JSON");
        let tets = info["tets"].as_u64().expect("tets");
        assert_eq!(tets, sample.tets, "{name}: {info}");
        assert_eq!(info["points"], sample.points, "{name}: {info}");
        // The volume cells as VTK counts them, those left out of the walk
        // included.
        assert_eq!(
            info["input_cells"], sample.vtk_volume_cells,
            "{name}: {info}"
        );
        // Where no point was added, the points are VTK's less those welded.
        let welded = info["welded_points"].as_u64().expect("welded_points");
        if sample.points <= sample.vtk_points {
            assert_eq!(sample.points + welded, sample.vtk_points, "{name}: {info}");
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
        if matches!(name, "can.vtu" | "can-vtu.hdf" | "uGridEx.vtk") {
            let summary: Vec<&str> = said
                .lines()
                .filter(|l| l.starts_with("mesh changed on load: "))
                .collect();
            assert_eq!(summary.len(), 1, "{name}:\n{said}");
            let want = if name != "uGridEx.vtk" {
                "33 cells left out"
            } else {
                "non-conforming faces made boundary"
            };
            assert!(summary[0].contains(want), "{name}: {}", summary[0]);
            // The can's left-out cells are drawn, and the render says so.
            let composited = said.contains("segments of left-out cells composited in their holes");
            assert_eq!(composited, name != "uGridEx.vtk", "{name}:\n{said}");
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

/// Time steps of an Exodus file and of a file series: `info` lists them; a
/// step the file does not store is one clear error naming the file and how
/// many it has, for a file without steps too.
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

#[test]
fn series_time_steps_are_listed_and_chosen() {
    let dir = support::scratch("cli-real", "series");
    let path = real("series/can/can.hdf.series");
    let file = path.to_str().expect("UTF-8");
    let out = run(&dir, &["info", file, "--time", "1.2"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let said = text(&out.stdout);
    assert!(
        said.contains("time steps:      3 (read step 1, time 1)"),
        "{said}"
    );
    let out = run(&dir, &["info", "--json", file, "--time-step", "2"]);
    let info: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(info["times"], serde_json::json!([0.0, 1.0, 2.0]), "{info}");
    assert_eq!(info["time_step"], 2, "{info}");
    let vtu = real("tetra.vtu");
    let out = run(
        &dir,
        &["info", vtu.to_str().expect("UTF-8"), "--time-step", "1"],
    );
    assert_eq!(out.status.code(), Some(1));
    let stderr = text(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("tetra.vtu: time step 1 is out of range: the file stores 0"),
        "{stderr}"
    );
}

/// A file whose sizes need more memory than the machine has is refused at
/// once with the estimate, before it is read: Exodus from its header,
/// VTKHDF from a compressed dataset's shape. `TETRAY_MEMORY_LIMIT` stands
/// for a small machine (the real case: a 17 GB Exodus file on 24 GB).
#[test]
fn files_larger_than_the_memory_are_refused_with_the_estimate() {
    let dir = support::scratch("cli-real", "memory");
    for (name, limit) in [("disk_out_ref.ex2", "1000000"), ("can-vtu.hdf", "1000")] {
        let path = real(name);
        let out = std::process::Command::new(support::BIN)
            .args(["info", path.to_str().expect("UTF-8")])
            .env("TETRAY_MEMORY_LIMIT", limit)
            .current_dir(&dir)
            .output()
            .expect("run tetray");
        assert_eq!(out.status.code(), Some(1), "{name}");
        let stderr = text(&out.stderr);
        assert_eq!(stderr.lines().count(), 1, "{name}: {stderr}");
        assert!(stderr.contains(name), "{stderr}");
        assert!(
            stderr.contains("needs about") && stderr.contains("available"),
            "{stderr}"
        );
    }
}
