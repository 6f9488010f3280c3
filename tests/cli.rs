//! End-to-end tests of the `tetray` binary: every command run as a user runs
//! it, outputs read back, bad inputs rejected with one line and exit code 1.
//! Images are small to keep the suite fast; only the default invocation
//! renders at full size, because that is what it promises.

use std::path::{Path, PathBuf};

use serde_json::Value;

mod support;
use support::{run as run_in, text};

/// The PLOT3D datasets of the repository (`data/plot3d`).
fn plot3d(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/plot3d")
        .join(name)
}

/// A fresh folder under the target directory for one test.
fn scratch(test: &str) -> PathBuf {
    support::scratch("cli", test)
}

/// Runs a command that must succeed; returns its stdout.
fn ok(dir: &Path, args: &[&str]) -> String {
    let out = run_in(dir, args);
    assert!(
        out.status.success(),
        "tetray {args:?} failed ({:?}):\n{}",
        out.status.code(),
        text(&out.stderr)
    );
    text(&out.stdout)
}

fn json(dir: &Path, args: &[&str]) -> Value {
    let stdout = ok(dir, args);
    serde_json::from_str(&stdout)
        .unwrap_or_else(|e| panic!("tetray {args:?}: stdout is not JSON ({e}):\n{stdout}"))
}

fn f(value: &Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("{value} is not a number"))
}

fn rgb(value: &Value) -> [f64; 3] {
    let a = value.as_array().expect("an array");
    [f(&a[0]), f(&a[1]), f(&a[2])]
}

/// A hexahedron in the unit cube with a scalar rising along x, y and z:
/// VTK legacy ASCII, split into tetrahedra on load.
const CUBE_VTK: &str = "# vtk DataFile Version 3.0
cube
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 8 float
0 0 0  1 0 0  1 1 0  0 1 0  0 0 1  1 0 1  1 1 1  0 1 1
CELLS 1 9
8 0 1 2 3 4 5 6 7
CELL_TYPES 1
12
POINT_DATA 8
SCALARS temperature float 1
LOOKUP_TABLE default
0 1 2 3 4 5 6 7
";

#[test]
fn default_invocation_renders_the_embedded_blunt_fin() {
    let dir = scratch("default");
    let stdout = ok(&dir, &[]);
    assert!(stdout.contains("187318 tetrahedra"), "{stdout}");
    assert!(stdout.contains("M segments/s"), "{stdout}");
    let png = dir.join("tetray.png");
    let wrote = stdout
        .lines()
        .find_map(|l| l.strip_prefix("wrote "))
        .expect("says where it wrote the image");
    assert_eq!(
        Path::new(wrote).canonicalize().unwrap(),
        png.canonicalize().unwrap()
    );
    let image = image::open(&png).expect("a PNG").to_rgb8();
    assert_eq!(image.dimensions(), (512, 512));
    let lit = image
        .pixels()
        .filter(|p| p.0.iter().any(|&c| c > 0))
        .count();
    // The fin covers a good part of the frame; a blank or nearly blank
    // image means the walk or the integration broke.
    assert!(lit > 512 * 512 / 10, "only {lit} pixels are not black");
}

#[test]
fn exr_round_trips_and_agrees_with_the_png() {
    let dir = scratch("exr");
    let common = [
        "render",
        "--size",
        "48x32",
        "--azimuth",
        "30",
        "--elevation",
        "20",
        "--integrator",
        "exact",
    ];
    let exr_args: Vec<&str> = common.iter().copied().chain(["-o", "f.exr"]).collect();
    ok(&dir, &exr_args);
    let png_args: Vec<&str> = common
        .iter()
        .copied()
        .chain(["-o", "f.png", "--background", "0.2,0.4,0.6"])
        .collect();
    ok(&dir, &png_args);

    let exr = image::open(dir.join("f.exr")).expect("an EXR").to_rgba32f();
    let png = image::open(dir.join("f.png")).expect("a PNG").to_rgb8();
    assert_eq!(exr.dimensions(), (48, 32));
    assert_eq!(png.dimensions(), (48, 32));
    let background = [0.2f32, 0.4, 0.6];
    let (mut covered, mut empty) = (0, 0);
    for (x, y, p) in exr.enumerate_pixels() {
        let [r, g, b, a] = p.0;
        assert!((0.0..=1.0).contains(&a), "alpha {a} at ({x}, {y})");
        // Premultiplied colour with a = 1 - T: no light where nothing is.
        if a == 0.0 {
            assert_eq!([r, g, b], [0.0; 3], "colour without alpha at ({x}, {y})");
            empty += 1;
        } else {
            covered += 1;
        }
        // The PNG is the same pixel over the background, 8-bit.
        let q = png.get_pixel(x, y).0;
        for c in 0..3 {
            let over = ([r, g, b][c] + (1.0 - a) * background[c]).clamp(0.0, 1.0);
            let stored = f32::from(q[c]) / 255.0;
            assert!(
                (over - stored).abs() <= 0.5 / 255.0 + 1e-6,
                "pixel ({x}, {y}) channel {c}: EXR over background {over}, PNG {stored}"
            );
        }
    }
    assert!(
        covered > 100 && empty > 100,
        "{covered} covered, {empty} empty"
    );
}

#[test]
fn info_prints_the_tet_counts() {
    let dir = scratch("info");
    // Blunt Fin: 37,479 hexahedra into 5 tets each is the dissertation's
    // 187,395; the 77 flat ones from collapsed cells are dropped.
    let text = ok(&dir, &["info"]);
    assert!(text.contains("187318"), "{text}");
    assert!(text.contains("flat dropped:    77"), "{text}");
    assert!(text.contains("density"), "{text}");
    let blunt = json(&dir, &["info", "--json"]);
    assert_eq!(blunt["tets"], 187_318);
    assert_eq!(blunt["input_cells"], 37_479);
    assert_eq!(blunt["components"], 1);
    let asset = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/plot3d/bluntfinxyz.bin");
    let from_file = json(&dir, &["info", "--json", asset.to_str().unwrap()]);
    assert_eq!(from_file["tets"], blunt["tets"]);
    assert_eq!(from_file["fields"], blunt["fields"]);

    let post = plot3d("postxyz.bin");
    let post = json(&dir, &["info", "--json", post.to_str().unwrap()]);
    assert_eq!(post["tets"], 513_375, "{post}");
    assert_eq!(post["points"], 109_744);
    let post_text = ok(&dir, &["info", plot3d("postxyz.bin").to_str().unwrap()]);
    assert!(post_text.contains("513375"), "{post_text}");

    std::fs::write(dir.join("cube.vtk"), CUBE_VTK).unwrap();
    let cube = json(&dir, &["info", "--json", "cube.vtk"]);
    assert_eq!(cube["format"], "VTK legacy");
    assert_eq!(cube["cells_split"], 1);
    assert_eq!(cube["bounds"]["max"], serde_json::json!([1.0, 1.0, 1.0]));
    assert_eq!(cube["fields"][0]["name"], "temperature");
}

#[test]
fn renders_a_vtk_file_with_a_named_scalar() {
    let dir = scratch("vtk");
    std::fs::write(dir.join("cube.vtk"), CUBE_VTK).unwrap();
    let stdout = ok(
        &dir,
        &[
            "render",
            "cube.vtk",
            "--scalar",
            "temperature",
            "--size",
            "24x24",
            "--parallel-scale",
            "1",
            "--opacity-mode",
            "vtk",
            "--unit-distance",
            "0.5",
            "-o",
            "cube.exr",
        ],
    );
    assert!(stdout.contains("576 rays"), "{stdout}");
    let exr = image::open(dir.join("cube.exr")).unwrap().to_rgba32f();
    // Orthographic, half height 1 around the centre: the cube's face fills
    // the middle half of the image.
    assert!(exr.get_pixel(12, 12).0[3] > 0.0);
    assert_eq!(exr.get_pixel(0, 0).0[3], 0.0);
}

#[test]
fn constant_segments_follow_beer_lambert_with_every_method() {
    let dir = scratch("segment");
    let (lum, incoming, length): ([f64; 3], [f64; 3], f64) =
        ([0.8, 0.5, 0.2], [0.1, 0.2, 0.3], 0.7);
    for tau in [[1.5f64; 3], [0.5, 1.0, 2.0]] {
        let tau_arg = format!("{},{},{}", tau[0], tau[1], tau[2]);
        let out = json(
            &dir,
            &[
                "segment",
                "--integrator",
                "all",
                "--lb",
                "0.8,0.5,0.2",
                "--lf",
                "0.8,0.5,0.2",
                "--tau-b",
                &tau_arg,
                "--tau-f",
                &tau_arg,
                "--length",
                "0.7",
                "--incoming",
                "0.1,0.2,0.3",
            ],
        );
        let methods = out["methods"].as_array().expect("a list of methods");
        assert_eq!(methods.len(), 10, "{out}");
        for m in methods {
            let name = m["method"].as_str().unwrap();
            let colour = rgb(&m["colour"]);
            let transmittance = rgb(&m["transmittance"]);
            let mut mean_t = 0.0;
            for c in 0..3 {
                let t = (-tau[c] * length).exp();
                mean_t += t / 3.0;
                let expected = incoming[c] * t + lum[c] * (1.0 - t);
                // f32 arithmetic; the tables are exact at their nodes here.
                assert!(
                    (colour[c] - expected).abs() < 2e-5,
                    "{name} channel {c}: colour {} vs Beer-Lambert {expected}",
                    colour[c]
                );
                assert!(
                    (transmittance[c] - t).abs() < 2e-5,
                    "{name}: T {transmittance:?}"
                );
            }
            assert!(
                (f(&m["alpha"]) - (1.0 - mean_t)).abs() < 2e-5,
                "{name}: {m}"
            );
            assert!(f(&m["abs_error"]) < 2e-5, "{name}: {m}");
        }
    }
    // One method alone: the same numbers, without the comparison.
    let one = json(
        &dir,
        &[
            "segment",
            "--integrator",
            "exact",
            "--lb",
            "1,0,0",
            "--lf",
            "0,0,1",
            "--tau-b",
            "2",
            "--tau-f",
            "0.5",
            "--length",
            "1",
        ],
    );
    assert_eq!(one["method"], "exact");
    let alpha = f(&one["alpha"]);
    assert!(alpha > 0.0 && alpha < 1.0, "{one}");
}

#[test]
fn psi_table_matches_its_f64_value() {
    let dir = scratch("psi");
    for (gb, gf) in [("0.3", "0.9"), ("0", "0"), ("0.99", "0.01"), ("0.5", "0.5")] {
        let out = json(&dir, &["psi", "--gamma-b", gb, "--gamma-f", gf]);
        let error = f(&out["error_bilinear"]);
        assert!(error < 1e-5, "gamma ({gb}, {gf}): {out}");
        assert!((f(&out["table_bilinear"]) - f(&out["f64"])).abs() < 1e-5);
        let g: f64 = gb.parse::<f32>().unwrap().into();
        assert!((f(&out["tau_b_d"]) - g / (1.0 - g)).abs() < 1e-9, "{out}");
        assert!(out["table_nearest"].is_number() && out["error_nearest"].is_number());
    }
    let origin = json(&dir, &["psi", "--gamma-b", "0", "--gamma-f", "0"]);
    assert_eq!(f(&origin["f64"]), 1.0);
}

#[test]
fn bench_prints_positive_rates() {
    let dir = scratch("bench");
    let out = json(
        &dir,
        &[
            "bench",
            "--frames",
            "2",
            "--size",
            "64x64",
            "--azimuth",
            "30",
            "--elevation",
            "20",
        ],
    );
    assert_eq!(out["frames"], 2);
    assert_eq!(out["size"], "64x64");
    assert_eq!(out["renderer"], "cpu");
    assert_eq!(out["integrator"], "ppi");
    // The walk's build is named where the CPU runs its x86-64-v3 copy.
    let adapter = out["adapter"].as_str().unwrap();
    assert!(
        adapter.starts_with("cpu (rayon), ") || adapter.starts_with("cpu (rayon, x86-64-v3), "),
        "{adapter}"
    );
    assert_eq!(out["tets"], 187_318);
    for key in [
        "ms_per_frame_median",
        "ms_per_frame_min",
        "ms_per_frame_max",
        "rays_per_s",
        "segments_per_s",
        "segments_per_frame",
        "tets_per_s",
    ] {
        assert!(f(&out[key]) > 0.0, "{key}: {out}");
    }
    assert!(f(&out["ms_per_frame_min"]) <= f(&out["ms_per_frame_max"]));
    assert!(f(&out["ms_per_frame_mad"]) >= 0.0);
    assert_eq!(out["steps_bound_hits"], 0);
    assert_eq!(out["walk_failures"], 0);
    // 64 x 64 pixels for 13 514 boundary faces (0.30 per face): the BVH
    // answers entries.
    assert_eq!(out["entry_lists_frames"], 0);
}

/// With enough pixels per boundary face (1.5 here), the CPU ray caster
/// takes its entries from per-pixel lists, and says so.
#[test]
fn bench_reports_entry_lists() {
    let dir = scratch("bench-lists");
    let args = [
        "bench",
        "--frames",
        "2",
        "--size",
        "160x128",
        "--renderer",
        "cpu",
    ];
    let out = json(&dir, &args);
    assert_eq!(out["boundary_faces"], 13_514);
    assert_eq!(out["entry_lists_frames"], 2, "{out}");
}

/// Each bad input: exit code 1, no panic, one error line naming the problem.
#[test]
fn bad_inputs_fail_with_one_line() {
    let dir = scratch("bad");
    let bytes = std::fs::read(plot3d("bluntfinxyz.bin")).unwrap();
    std::fs::write(dir.join("truncxyz.bin"), &bytes[..1000]).unwrap();
    std::fs::write(
        dir.join("empty.json"),
        r#"[{"Name": "empty", "RGBPoints": []}]"#,
    )
    .unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["render", "missing.vtk"], "missing.vtk"),
        (&["info", "truncxyz.bin"], "too short"),
        (&["render", "--size", "0x64"], "--size"),
        (&["render", "--integrator", "simpson"], "simpson"),
        (
            &["render", "--scalar", "vorticity", "--size", "8x8"],
            "vorticity",
        ),
        (
            &["render", "--tf", "empty.json", "--size", "8x8"],
            "RGBPoints",
        ),
        (&["render", "--tf", "nope.json"], "nope.json"),
        (
            &[
                "render",
                "--camera-position",
                "1,1,1",
                "--focal-point",
                "1,1,1",
            ],
            "camera",
        ),
        (&["render", "--camera-position", "1,2"], "--camera-position"),
        (&["render", "-o", "image.jpg"], ".png, .exr or .npy"),
        (&["render", "--unit-distance", "-1"], "--unit-distance"),
        (
            &["render", "--early-termination", "0"],
            "--early-termination",
        ),
        (
            &[
                "segment", "--lb", "1", "--lf", "1", "--tau-b", "-1", "--tau-f", "1", "--length",
                "1",
            ],
            "--tau-b",
        ),
        (&["segment", "--lb", "1"], "--lf"),
        (&["psi", "--gamma-b", "2", "--gamma-f", "0"], "--gamma-b"),
        (&["bench", "--frames", "0"], "--frames"),
        (&["export-html", "-o", "p.html", "--bench", "0"], "--bench"),
        (
            &["export-html", "-o", "p.html", "--bench", "2,3,4"],
            "FRAMES[,VIEWS]",
        ),
        (
            &["export-html", "-o", "p.html", "--early-termination", "2"],
            "--early-termination",
        ),
        (
            &["export-html", "-o", "p.html", "--max-steps", "0"],
            "--max-steps",
        ),
        (
            &["export-html", "-o", "no/such/folder/p.html"],
            "no/such/folder/p.html",
        ),
        (&["frobnicate"], "frobnicate"),
    ];
    for (args, named) in cases {
        let out = run_in(&dir, args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "tetray {args:?}:\n{stderr}");
        assert!(
            !stderr.contains("panicked"),
            "tetray {args:?} panicked:\n{stderr}"
        );
        let errors: Vec<&str> = stderr
            .lines()
            .filter(|l| !l.starts_with("warning:"))
            .collect();
        assert_eq!(
            errors.len(),
            1,
            "tetray {args:?}: not one error line:\n{stderr}"
        );
        assert!(errors[0].starts_with("error: "), "{}", errors[0]);
        assert!(
            errors[0].contains(named),
            "tetray {args:?}: the error does not name {named:?}: {}",
            errors[0]
        );
    }
}

/// A reader that closes the pipe early (`tetray info mesh | head -1`):
/// the process ends as one killed by SIGPIPE would (exit code 141),
/// without a panic message. The pipe is closed before the mesh has loaded,
/// so the first line written meets it closed.
#[test]
fn a_closed_pipe_ends_quietly() {
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/real/can.vtu");
    let mut child = std::process::Command::new(support::BIN)
        .arg("info")
        .arg(&mesh)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run tetray");
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = text(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(141), "{stderr}");
}

/// Found by the `hdf5_formats` fuzz target: a 7 kB VTKHDF image whose
/// extent claims 18 M points (and no arrays) was made into 37 M
/// tetrahedra however little memory there was; an image's size is now
/// held to the memory it takes before its points are made.
#[test]
fn an_image_larger_than_memory_is_refused_before_it_is_made() {
    let file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/fuzz/vtkhdf-image-18m-points.vtkhdf");
    let out = std::process::Command::new(support::BIN)
        .arg("info")
        .arg(&file)
        .env("TETRAY_MEMORY_LIMIT", (512u64 << 20).to_string())
        .output()
        .expect("run tetray");
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("the image (3080196 x 3 x 2 points)"),
        "{stderr}"
    );
    assert!(stderr.contains("TETRAY_MEMORY_LIMIT"), "{stderr}");
}

/// The same for the VTK readers' image data and rectilinear grids (found
/// by the `render` fuzz target: a 94-byte legacy file whose DIMENSIONS
/// claim 22 M points took the time and memory of making them).
#[test]
fn vtk_grids_larger_than_memory_are_refused_before_they_are_made() {
    let dir = support::scratch("cli", "grid-preflight");
    let files = [
        (
            "image.vtk",
            "# vtk DataFile Version 2.0\nfuzz\nASCII\nDATASET STRUCTURED_POINTS\n\
             DIMENSIONS 9 491884 5\n",
            "the grid (9 x 491884 x 5 points)",
        ),
        (
            "image.vti",
            "<VTKFile type=\"ImageData\" version=\"1.0\"><ImageData WholeExtent=\"0 8 0 491883 0 4\" \
             Origin=\"0 0 0\" Spacing=\"1 1 1\"><Piece Extent=\"0 8 0 491883 0 4\"></Piece>\
             </ImageData></VTKFile>\n",
            "the ImageData (22134780 points, 15740256 cells)",
        ),
        (
            "grid.vtr",
            "<VTKFile type=\"RectilinearGrid\" version=\"1.0\"><RectilinearGrid WholeExtent=\"0 8 0 491883 0 4\">\
             <Piece Extent=\"0 8 0 491883 0 4\"></Piece></RectilinearGrid></VTKFile>\n",
            "the RectilinearGrid (22134780 points, 15740256 cells)",
        ),
    ];
    for (name, content, said) in files {
        std::fs::write(dir.join(name), content).expect("write");
        let out = std::process::Command::new(support::BIN)
            .arg("info")
            .arg(dir.join(name))
            .env("TETRAY_MEMORY_LIMIT", (512u64 << 20).to_string())
            .output()
            .expect("run tetray");
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {stderr}");
        assert!(stderr.contains(said), "{name}: {stderr}");
        assert!(stderr.contains("TETRAY_MEMORY_LIMIT"), "{name}: {stderr}");
    }
}

/// Found by the `hdf5_formats` fuzz target: an image of long thin cells
/// (11012 x 3 x 2 points, spacing 1.5e-4 x 0.25 x 1) whose conformity
/// check visited most boundary faces for every point (90 s for 22 k
/// cells; the face tree's splits now separate such faces, see
/// `tetray_mesh::conform`'s test, which counts the visits). It loads, whole.
#[test]
fn an_image_of_thin_cells_loads() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/fuzz/vtkhdf-thin-image.vtkhdf");
    let out = std::process::Command::new(support::BIN)
        .args(["info", "--json"])
        .arg(&file)
        .output()
        .expect("run tetray");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let info: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(info["points"], 66072, "{info}");
    assert_eq!(info["tets"], 132132, "{info}");
}
