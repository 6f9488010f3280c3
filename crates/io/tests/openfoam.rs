//! The OpenFOAM reader on OpenFOAM's lid-driven cavity tutorial case (as
//! OpenFOAM wrote it) and on small cases written by these tests in ASCII
//! and binary, 32- and 64-bit labels, compressed or not.

use std::path::Path;

use tetray_io::{LoadOptions, LoadedMesh, load};

mod formats_common;

use formats_common::{at_step, data, field, scratch, volume};

/// The cavity: 882 points and 400 hexahedra, as VTK's vtkOpenFOAMReader
/// and the `owner` file's note ("nPoints: 882 nCells: 400") count them;
/// six time folders 0 .. 2.5; p and U per cell. Opened by its folder,
/// its `case.foam` marker and its `system/controlDict` alike.
#[test]
fn the_cavity_case_opens_every_way_with_its_times() {
    let case = data("real/openfoam/cavity");
    let by_folder = at_step(&case, Some(1));
    assert_eq!(by_folder.report.format, "OpenFOAM");
    assert_eq!(by_folder.mesh.points.len(), 882);
    assert_eq!(by_folder.report.cells_split, 400);
    assert_eq!(by_folder.report.times, vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5]);
    assert_eq!(by_folder.report.time_step, Some(1));
    for path in [case.join("case.foam"), case.join("system/controlDict")] {
        let other = at_step(&path, Some(1));
        assert!(other.mesh.tets == by_folder.mesh.tets, "{}", path.display());
        assert!(
            other.mesh.fields == by_folder.mesh.fields,
            "{}",
            path.display()
        );
    }
    // At time 0 the pressure is uniform 0 and the velocity too.
    let first = at_step(&case, None);
    assert!(field(&first, "p").iter().all(|&v| v == 0.0));
    // At 0.5 the cell pressures of the file (-4.98 .. 4.88 here, by the
    // file) bound their averages at the points.
    let p = field(&by_folder, "p");
    let (lo, hi) = p
        .iter()
        .fold((f32::MAX, f32::MIN), |(l, h), &v| (l.min(v), h.max(v)));
    assert!(lo < 0.0 && hi > 0.0 && lo >= -5.0 && hi <= 5.0, "{lo} {hi}");
    assert!(field(&by_folder, "U_magnitude").iter().any(|&v| v > 0.0));
}

/// Points, faces, owners and neighbours of a polyMesh.
type PolyMesh = (Vec<[f64; 3]>, Vec<Vec<i64>>, Vec<i64>, Vec<i64>);

/// A unit cube and a pyramid on its top face (apex at z = 1.5): the
/// internal face first, then the boundary, as OpenFOAM orders them.
fn hex_and_pyramid() -> PolyMesh {
    let points = vec![
        [0., 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.],
        [0., 1., 0.],
        [0., 0., 1.],
        [1., 0., 1.],
        [1., 1., 1.],
        [0., 1., 1.],
        [0.5, 0.5, 1.5],
    ];
    let faces = vec![
        vec![4, 5, 6, 7],
        vec![0, 3, 2, 1],
        vec![0, 1, 5, 4],
        vec![2, 3, 7, 6],
        vec![1, 2, 6, 5],
        vec![0, 4, 7, 3],
        vec![4, 5, 8],
        vec![5, 6, 8],
        vec![6, 7, 8],
        vec![7, 4, 8],
    ];
    let owner = vec![0, 0, 0, 0, 0, 0, 1, 1, 1, 1];
    (points, faces, owner, vec![1])
}

/// How a test case is written.
#[derive(Clone, Copy)]
struct Style {
    binary: bool,
    label64: bool,
    scalar32: bool,
    gzip_points: bool,
}

fn header(style: Style, class: &str) -> Vec<u8> {
    let format = if style.binary { "binary" } else { "ascii" };
    let arch = format!(
        "LSB;label={};scalar={}",
        if style.label64 { 64 } else { 32 },
        if style.scalar32 { 32 } else { 64 }
    );
    format!(
        "/* written by a test */\nFoamFile\n{{\n    version 2.0;\n    format {format};\n    \
         arch \"{arch}\";\n    class {class};\n    object x;\n}}\n// * * //\n\n"
    )
    .into_bytes()
}

fn list(style: Style, values: &[f64], integer: bool, width: usize) -> Vec<u8> {
    let n = values.len() / width;
    let mut out = format!("{n}\n(").into_bytes();
    if style.binary {
        for &v in values {
            match (integer, style.label64, style.scalar32) {
                (true, true, _) => out.extend((v as i64).to_le_bytes()),
                (true, false, _) => out.extend((v as i32).to_le_bytes()),
                (false, _, true) => out.extend((v as f32).to_le_bytes()),
                (false, _, false) => out.extend(v.to_le_bytes()),
            }
        }
    } else {
        for item in values.chunks(width) {
            let text: Vec<String> = item.iter().map(|v| v.to_string()).collect();
            if width == 1 {
                out.extend(format!("\n{}", text[0]).bytes());
            } else {
                out.extend(format!("\n({})", text.join(" ")).bytes());
            }
        }
        out.push(b'\n');
    }
    out.extend(b")\n");
    out
}

fn write_case(dir: &Path, style: Style) {
    write_mesh_and_fields(
        dir,
        style,
        hex_and_pyramid(),
        &[3.0, 5.0],
        &[3., 4., 0., 0., 0., 1.],
    );
}

/// A case (or a processor folder of one) holding `mesh`, p and U at time
/// 1 (per cell) and uniform values at time 0.
fn write_mesh_and_fields(dir: &Path, style: Style, mesh: PolyMesh, p1: &[f64], u1: &[f64]) {
    let (points, faces, owner, neighbour) = mesh;
    let mesh = dir.join("constant/polyMesh");
    std::fs::create_dir_all(&mesh).unwrap();
    std::fs::create_dir_all(dir.join("system")).unwrap();
    std::fs::write(dir.join("system/controlDict"), header(style, "dictionary")).unwrap();
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    let mut bytes = header(style, "vectorField");
    bytes.extend(list(style, &flat, false, 3));
    if style.gzip_points {
        use std::io::Write;
        let file = std::fs::File::create(mesh.join("points.gz")).unwrap();
        let mut gz = flate2::write::GzEncoder::new(file, flate2::Compression::default());
        gz.write_all(&bytes).unwrap();
        gz.finish().unwrap();
    } else {
        std::fs::write(mesh.join("points"), bytes).unwrap();
    }
    // Binary faces are a compact list: offsets, then the labels.
    let mut bytes = header(
        style,
        if style.binary {
            "faceCompactList"
        } else {
            "faceList"
        },
    );
    if style.binary {
        let mut offsets = vec![0.0];
        for f in &faces {
            offsets.push(offsets.last().unwrap() + f.len() as f64);
        }
        let labels: Vec<f64> = faces.iter().flatten().map(|&l| l as f64).collect();
        bytes.extend(list(style, &offsets, true, 1));
        bytes.extend(list(style, &labels, true, 1));
    } else {
        bytes.extend(format!("{}\n(\n", faces.len()).bytes());
        for f in &faces {
            let labels: Vec<String> = f.iter().map(|l| l.to_string()).collect();
            bytes.extend(format!("{}({})\n", f.len(), labels.join(" ")).bytes());
        }
        bytes.extend(b")\n");
    }
    std::fs::write(mesh.join("faces"), bytes).unwrap();
    for (name, values) in [("owner", &owner), ("neighbour", &neighbour)] {
        let mut bytes = header(style, "labelList");
        let v: Vec<f64> = values.iter().map(|&l| l as f64).collect();
        bytes.extend(list(style, &v, true, 1));
        std::fs::write(mesh.join(name), bytes).unwrap();
    }
    // Time 0: p uniform 2; time 1: p 3 in the cube and 5 in the pyramid,
    // U (3, 4, 0) and (0, 0, 1); a surface field that is passed over.
    for (time, p, u) in [("0", None, None), ("1", Some(p1), Some(u1))] {
        let folder = dir.join(time);
        std::fs::create_dir_all(&folder).unwrap();
        let mut bytes = header(style, "volScalarField");
        bytes.extend(b"dimensions [0 2 -2 0 0 0 0];\n\ninternalField   ");
        match p {
            None => bytes.extend(b"uniform 2;\n"),
            Some(p) => {
                bytes.extend(b"nonuniform List<scalar> ");
                bytes.extend(list(style, p, false, 1));
                bytes.extend(b";\n");
            }
        }
        bytes.extend(b"boundaryField\n{\n    walls { type zeroGradient; }\n}\n");
        std::fs::write(folder.join("p"), bytes).unwrap();
        let mut bytes = header(style, "volVectorField");
        bytes.extend(b"internalField   ");
        match u {
            None => bytes.extend(b"uniform (0 0 0);\n"),
            Some(u) => {
                bytes.extend(b"nonuniform List<vector> ");
                bytes.extend(list(style, u, false, 3));
                bytes.extend(b";\n");
            }
        }
        std::fs::write(folder.join("U"), bytes).unwrap();
        std::fs::write(folder.join("phi"), header(style, "surfaceScalarField")).unwrap();
    }
}

/// The same two cells in every encoding: a hexahedron and a pyramid
/// recognised as such (volume 1 + 1/6), fields averaged from the cells to
/// the points (3 where only the cube reaches, 5 at the apex, 4 on the
/// shared face; |U| = 5 and 1).
#[test]
fn every_encoding_reads_the_same_cells_and_fields() {
    let styles = [
        Style {
            binary: false,
            label64: false,
            scalar32: false,
            gzip_points: false,
        },
        Style {
            binary: true,
            label64: false,
            scalar32: false,
            gzip_points: false,
        },
        Style {
            binary: true,
            label64: true,
            scalar32: true,
            gzip_points: true,
        },
    ];
    for (i, style) in styles.into_iter().enumerate() {
        let dir = scratch("openfoam", &format!("encoding{i}"));
        write_case(&dir, style);
        let first = at_step(&dir, None);
        assert_eq!(first.report.times, vec![0.0, 1.0], "case {i}");
        assert!(field(&first, "p").iter().all(|&v| v == 2.0), "case {i}");
        let loaded = at_step(&dir, Some(1));
        assert!(
            (volume(&loaded) - 7.0 / 6.0).abs() < 1e-6,
            "case {i}: {}",
            volume(&loaded)
        );
        // A hexahedron and a pyramid split, nothing added at centres.
        assert_eq!(loaded.report.cells_split, 2, "case {i}");
        assert_eq!(loaded.mesh.points.len(), 9, "case {i}");
        let p = field(&loaded, "p");
        let u = field(&loaded, "U_magnitude");
        for (k, point) in loaded.mesh.points.iter().enumerate() {
            let z = point.z + loaded.origin().z as f32;
            let (want_p, want_u) = if z < 0.5 {
                (3.0, 5.0)
            } else if z > 1.25 {
                (5.0, 1.0)
            } else {
                (4.0, 3.0)
            };
            assert!(
                (p[k] - want_p).abs() < 1e-6,
                "case {i} point {point}: p {}",
                p[k]
            );
            assert!(
                (u[k] - want_u).abs() < 1e-6,
                "case {i} point {point}: |U| {}",
                u[k]
            );
        }
    }
}

/// Every prefix of each file of a case: an error naming the file, or
/// (where only trailing comments were cut) the same mesh; never a panic.
#[test]
fn every_truncation_is_an_error_or_the_same_mesh() {
    let style = Style {
        binary: true,
        label64: false,
        scalar32: false,
        gzip_points: false,
    };
    let whole = scratch("openfoam", "whole");
    write_case(&whole, style);
    let want = at_step(&whole, Some(1));
    for file in [
        "constant/polyMesh/points",
        "constant/polyMesh/faces",
        "constant/polyMesh/owner",
        "1/p",
        "1/U",
    ] {
        let bytes = std::fs::read(whole.join(file)).unwrap();
        let dir = scratch("openfoam", "cut");
        write_case(&dir, style);
        for len in 0..bytes.len() {
            std::fs::write(dir.join(file), &bytes[..len]).unwrap();
            let opts = LoadOptions {
                time_step: Some(1),
                ..LoadOptions::default()
            };
            match load(&dir, &opts) {
                Err(e) => assert!(e.to_string().contains("cut"), "{file} at {len}: {e}"),
                Ok(m) => assert!(
                    m.mesh.tets == want.mesh.tets && m.mesh.fields == want.mesh.fields,
                    "{file} at {len}: read differently"
                ),
            }
        }
    }
}

/// The same two cells decomposed: the cube in `processor0`, the pyramid in
/// `processor1` (each with its own points and the shared face as a
/// boundary), no reconstructed mesh: welded into the same 9 points with
/// the same fields at the same places.
#[test]
fn a_decomposed_case_is_welded() {
    let style = Style {
        binary: false,
        label64: false,
        scalar32: false,
        gzip_points: false,
    };
    let whole = scratch("openfoam", "reconstructed");
    write_case(&whole, style);
    let dir = scratch("openfoam", "decomposed");
    std::fs::create_dir_all(dir.join("system")).unwrap();
    std::fs::write(dir.join("system/controlDict"), header(style, "dictionary")).unwrap();
    let (points, _, _, _) = hex_and_pyramid();
    let cube = (
        points[..8].to_vec(),
        vec![
            vec![4, 5, 6, 7],
            vec![0, 3, 2, 1],
            vec![0, 1, 5, 4],
            vec![2, 3, 7, 6],
            vec![1, 2, 6, 5],
            vec![0, 4, 7, 3],
        ],
        vec![0; 6],
        vec![],
    );
    let pyramid = (
        points[4..].to_vec(),
        vec![
            vec![0, 3, 2, 1],
            vec![0, 1, 4],
            vec![1, 2, 4],
            vec![2, 3, 4],
            vec![3, 0, 4],
        ],
        vec![0; 5],
        vec![],
    );
    write_mesh_and_fields(&dir.join("processor0"), style, cube, &[3.0], &[3., 4., 0.]);
    write_mesh_and_fields(
        &dir.join("processor1"),
        style,
        pyramid,
        &[5.0],
        &[0., 0., 1.],
    );
    let want = at_step(&whole, Some(1));
    let got = at_step(&dir, Some(1));
    assert_eq!(got.report.pieces.pieces, 2);
    assert_eq!(got.mesh.points.len(), 9);
    assert_eq!(got.report.times, vec![0.0, 1.0]);
    assert!((volume(&got) - 7.0 / 6.0).abs() < 1e-6);
    let at = |m: &LoadedMesh, name: &str| {
        let mut v: Vec<(i64, i64, i64, u32)> = m
            .mesh
            .points
            .iter()
            .zip(field(m, name))
            .map(|(p, f)| {
                let q = p.as_dvec3() + m.origin();
                let key = |x: f64| (x * 1000.0).round() as i64;
                (key(q.x), key(q.y), key(q.z), f.to_bits())
            })
            .collect();
        v.sort_unstable();
        v
    };
    assert_eq!(at(&got, "p"), at(&want, "p"));
    assert_eq!(at(&got, "U_magnitude"), at(&want, "U_magnitude"));
}

/// Every byte of each file of a binary case overwritten in turn (0x00,
/// 0xff, a flipped bit): an error naming the case, or a read; never a
/// panic.
#[test]
fn every_corrupted_byte_is_an_error_or_a_read() {
    let style = Style {
        binary: true,
        label64: false,
        scalar32: false,
        gzip_points: false,
    };
    let dir = scratch("openfoam", "corrupt");
    write_case(&dir, style);
    let opts = LoadOptions {
        time_step: Some(1),
        ..LoadOptions::default()
    };
    for file in [
        "constant/polyMesh/points",
        "constant/polyMesh/faces",
        "constant/polyMesh/owner",
        "constant/polyMesh/neighbour",
        "1/p",
        "1/U",
    ] {
        let bytes = std::fs::read(dir.join(file)).unwrap();
        let mut copy = bytes.clone();
        for at in 0..bytes.len() {
            for value in [0x00, 0xff, bytes[at] ^ 0x01] {
                copy[at] = value;
                std::fs::write(dir.join(file), &copy).unwrap();
                if let Err(e) = load(&dir, &opts) {
                    assert!(e.to_string().contains("corrupt"), "{file} at {at}: {e}");
                }
            }
            copy[at] = bytes[at];
        }
        std::fs::write(dir.join(file), &bytes).unwrap();
    }
}

/// Tutorial cases set initial fields through macros: `$name` defined
/// above in the file is read; one defined in an `#include`d file (not
/// followed) leaves that field out with a warning naming it.
#[test]
fn macro_values_are_read_or_named() {
    let style = Style {
        binary: false,
        label64: false,
        scalar32: false,
        gzip_points: false,
    };
    let dir = scratch("openfoam", "macros");
    write_case(&dir, style);
    let mut u = header(style, "volVectorField");
    u.extend(b"flowVelocity (1 2 2);\ninternalField   uniform $flowVelocity;\n");
    std::fs::write(dir.join("0/U"), u).unwrap();
    let mut p = header(style, "volScalarField");
    p.extend(b"#include \"include/initialConditions\"\ninternalField   uniform $pressure;\n");
    std::fs::write(dir.join("0/p"), p).unwrap();
    let loaded = at_step(&dir, Some(0));
    assert!(
        field(&loaded, "U_magnitude")
            .iter()
            .all(|&v| (v - 3.0).abs() < 1e-6)
    );
    assert!(loaded.mesh.fields.iter().all(|f| f.name != "p"));
    assert!(
        loaded
            .report
            .warnings
            .iter()
            .any(|w| w.contains("$pressure")),
        "{:?}",
        loaded.report.warnings
    );
}
