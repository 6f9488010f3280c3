//! The CGNS reader on VTK's multi-zone CFL3D solution (`multi.cgns` in its
//! ADF storage, and its HDF5 twin converted by CGNS's `adf2hdf`) and on
//! small files written for each part of the standard in both storages
//! (`data/cgns`, made by the script beside them).

use std::path::PathBuf;

use tetray_io::{LoadOptions, LoadedMesh, load};

mod formats_common;

use formats_common::{at_step, data, field, volume};

fn loaded(path: &str) -> LoadedMesh {
    at_step(&data(path), None)
}

/// Four structured zones of 6150, 24750, 16762 and 10914 vertices and
/// 2928, 12056, 8064 and 5120 cells, as VTK 9.1's vtkCGNSReader counts
/// them in the ADF original; 1010 vertices the zones share are welded.
/// The cell-centred solution is read inside its rind layers.
#[test]
fn the_multi_zone_solution_reads_with_vtks_counts() {
    let m = loaded("real/multi-hdf5.cgns");
    assert_eq!(m.report.format, "CGNS");
    assert_eq!(m.report.pieces.pieces, 4);
    assert_eq!(m.report.cells_split, 2928 + 12056 + 8064 + 5120);
    assert_eq!(m.mesh.points.len(), 6150 + 24750 + 16762 + 10914 - 1010);
    for name in [
        "Density",
        "MomentumX",
        "EnergyStagnationDensity",
        "TurbulentSANuTilde",
        // MomentumX, Y and Z also make the vector Momentum, as VTK reads
        // them.
        "Momentum_magnitude",
    ] {
        field(&m, name);
    }
    // Free-stream density 1, compressed and expanded around the body.
    let d = field(&m, "Density");
    let (lo, hi) = d
        .iter()
        .fold((f32::MAX, f32::MIN), |(l, h), &v| (l.min(v), h.max(v)));
    assert!(lo > 0.5 && lo < 1.0 && hi > 1.0 && hi < 1.5, "{lo} {hi}");
}

/// A structured zone: points x = i, y = j, z = k; f = x + 2y + 3z at the
/// vertices (exact), and Velocity X, Y, Z joined into a vector; a cell-centred array with one rind layer on every
/// side whose interior holds 0 .. 5 and rind -1: averaged at the points,
/// no rind value shows (all within 0 .. 5; a corner point has its one
/// cell's value).
#[test]
fn a_structured_zone_strips_its_rind() {
    let m = loaded("cgns/structured.cgns");
    assert_eq!(m.mesh.points.len(), 24);
    assert_eq!(m.report.cells_split, 6);
    let origin = m.origin().as_vec3();
    let f = field(&m, "f");
    let cell = field(&m, "cell");
    for (k, p) in m.mesh.points.iter().enumerate() {
        let q = *p + origin;
        assert_eq!(f[k], q.x + 2.0 * q.y + 3.0 * q.z, "at {q}");
        assert!((0.0..=5.0).contains(&cell[k]), "at {q}: {}", cell[k]);
        // VelocityX, Y, Z = (3, 4, 0) at every vertex: the vector's
        // magnitude is 5.
        assert_eq!(field(&m, "Velocity_magnitude")[k], 5.0);
        if q.x == 3.0 && q.y == 2.0 {
            // Only cell (2, 1): index 2 + 3 = 5.
            assert_eq!(cell[k], 5.0);
        }
    }
}

/// An unstructured zone: a HEXA_8 section of two cubes, a MIXED section
/// (with start offsets) of a pyramid and a tetrahedron, a QUAD_4 boundary
/// face that is skipped; volume 2 + 1/6 + 1/12; f exact at every vertex.
#[test]
fn an_unstructured_zone_reads_every_section() {
    let m = loaded("cgns/unstructured.cgns");
    assert_eq!(m.mesh.points.len(), 14);
    let origin = m.origin();
    let volume = volume(&m);
    assert!(
        (volume - (2.0 + 1.0 / 6.0 + 1.0 / 12.0)).abs() < 1e-6,
        "{volume}"
    );
    assert!(
        m.report.warnings.iter().any(|w| w.contains("1 quad")),
        "{:?}",
        m.report.warnings
    );
    let f = field(&m, "f");
    for (k, p) in m.mesh.points.iter().enumerate() {
        let q = p.as_dvec3() + origin;
        assert!(
            (f64::from(f[k]) - (q.x + 2.0 * q.y + 3.0 * q.z)).abs() < 1e-6,
            "at {q}"
        );
    }
}

/// NGON_n faces and NFACE_n cells (a cube and a pyramid on its top, the
/// shared face named with a minus sign by the pyramid): volume 1 + 1/6, f
/// = x + 2y + 3z exact at every point (the centres the polyhedron split
/// adds included: f is linear), and the cell values 1 and 2 averaged at
/// the points (1 on the cube's base, 1.5 on the shared face, 2 at the
/// apex).
#[test]
fn ngon_and_nface_sections_read_as_polyhedra() {
    let m = loaded("cgns/polyhedral.cgns");
    let origin = m.origin().as_vec3();
    let volume = volume(&m);
    assert!((volume - 7.0 / 6.0).abs() < 1e-6, "{volume}");
    assert_eq!(m.report.cells_split, 2);
    let (f, cell) = (field(&m, "f"), field(&m, "cell"));
    for (k, p) in m.mesh.points.iter().enumerate() {
        let q = (*p + origin).as_dvec3();
        assert!(
            (f64::from(f[k]) - (q.x + 2.0 * q.y + 3.0 * q.z)).abs() < 1e-5,
            "f at {q}"
        );
        let expected = if q.z == 0.0 {
            1.0
        } else if q.z == 1.0 {
            1.5
        } else if q.z == 1.5 {
            2.0
        } else {
            continue;
        };
        assert_eq!(cell[k], expected, "cell at {q}");
    }
}

/// The quadratic cells whose node order differs from VTK's (HEXA_27,
/// PENTA_18, PYRA_14, HEXA_20, PENTA_15), every node at its exact place:
/// reordered, subdivided and split, they fill their volumes 1, 1/2, 1/3,
/// 1 and 1/2 with no cell left out (a node in the wrong slot folds the
/// subdivision), and f = x + 2y + 3z is exact at every point. Both
/// storages.
#[test]
fn quadratic_cells_take_vtks_node_order() {
    for name in ["cgns/quadratic.cgns", "cgns/quadratic-adf.cgns"] {
        let m = loaded(name);
        assert_eq!(m.report.cells_split, 5, "{name}");
        assert_eq!(m.report.excluded.tets, 0, "{name}");
        let origin = m.origin();
        let volume: f64 = m
            .mesh
            .tets
            .iter()
            .map(|t| {
                let [a, b, c, d] = t.map(|i| m.mesh.points[i as usize].as_dvec3() + origin);
                (b - a).cross(c - a).dot(d - a) / 6.0
            })
            .sum();
        assert!((volume - 10.0 / 3.0).abs() < 1e-5, "{name}: {volume}");
        let f = field(&m, "f");
        for (k, p) in m.mesh.points.iter().enumerate() {
            let q = p.as_dvec3() + origin;
            assert!(
                (f64::from(f[k]) - (q.x + 2.0 * q.y + 3.0 * q.z)).abs() < 1e-5,
                "{name}: f at {q}"
            );
        }
    }
}

/// Iterative data: two steps at times 0.5 and 1.5, each naming its
/// coordinates and its solution. Step 0 has the vertices (i, j, k) and f
/// = i; step 1 (asked for by number, or by the nearest time) has them at
/// (i + 10, j, k) and f = 2 i. Both storages.
#[test]
fn iterative_data_reads_as_time_steps() {
    for name in ["cgns/temporal.cgns", "cgns/temporal-adf.cgns"] {
        for (opts, step) in [
            (LoadOptions::default(), 0),
            (
                LoadOptions {
                    time_step: Some(1),
                    ..LoadOptions::default()
                },
                1,
            ),
            (
                LoadOptions {
                    time: Some(1.4),
                    ..LoadOptions::default()
                },
                1,
            ),
        ] {
            let m = load(&data(name), &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(m.report.times, [0.5, 1.5], "{name}");
            assert_eq!(m.report.time_step, Some(step), "{name}");
            let origin = m.origin();
            let f = field(&m, "f");
            for (k, p) in m.mesh.points.iter().enumerate() {
                let q = p.as_dvec3() + origin;
                let i = q.x - 10.0 * step as f64;
                assert!((0.0..=2.0).contains(&i), "{name} step {step}: {q}");
                assert_eq!(
                    f64::from(f[k]),
                    (step + 1) as f64 * i,
                    "{name} step {step}: {q}"
                );
            }
        }
        let e = load(
            &data(name),
            &LoadOptions {
                time_step: Some(2),
                ..LoadOptions::default()
            },
        )
        .expect_err("step 2");
        assert!(e.to_string().contains("out of range"), "{e}");
    }
}

/// The same mesh and fields, bit for bit.
fn assert_same(a: &LoadedMesh, b: &LoadedMesh, what: &str) {
    assert_eq!(a.report.format, b.report.format, "{what}");
    assert!(!a.mesh.fields.is_empty(), "{what}: no field");
    assert_eq!(a.mesh.points, b.mesh.points, "{what}: points");
    assert_eq!(a.mesh.tets, b.mesh.tets, "{what}: tetrahedra");
    let names = |m: &LoadedMesh| {
        m.mesh
            .fields
            .iter()
            .map(|f| f.name.clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(names(a), names(b), "{what}: fields");
    for (fa, fb) in a.mesh.fields.iter().zip(&b.mesh.fields) {
        assert_eq!(fa.values, fb.values, "{what}: {}", fa.name);
    }
}

/// VTK's `multi.cgns` in its original ADF storage reads as its HDF5 twin
/// (converted by CGNS's `adf2hdf`, whose counts VTK's reader confirms in
/// the test above): the same points, tetrahedra and arrays, bit for bit.
#[test]
fn the_adf_original_reads_as_its_hdf5_twin() {
    let adf = loaded("real/multi.cgns");
    assert_eq!(adf.report.pieces.pieces, 4);
    // Its one step's solution, named by each zone's iterative data.
    assert_eq!(adf.report.times.len(), 1);
    field(&adf, "Density");
    assert_same(&adf, &loaded("real/multi-hdf5.cgns"), "multi.cgns");
}

/// The fixtures in the ADF storage, written by CGNS's `hdf2adf`, read as
/// the HDF5 files they were converted from.
#[test]
fn the_adf_fixtures_read_as_their_hdf5_twins() {
    for name in ["structured", "unstructured", "polyhedral", "temporal"] {
        assert_same(
            &loaded(&format!("cgns/{name}-adf.cgns")),
            &loaded(&format!("cgns/{name}.cgns")),
            name,
        );
    }
}

/// An ADF header of another version or numeric format, or one cut short,
/// is one line naming the file and what is wrong.
#[test]
fn an_adf_header_that_is_not_read_says_why() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cgns");
    std::fs::create_dir_all(&dir).unwrap();
    let bytes = std::fs::read(data("cgns/structured-adf.cgns")).unwrap();
    for (at, value, expected) in [
        (25, b'C', "database version 'C'"),
        (100, b'C', "numeric format 'C'"),
        (130, b'x', "AdF4"),
    ] {
        let mut copy = bytes.clone();
        copy[at] = value;
        let path = dir.join("header.cgns");
        std::fs::write(&path, &copy).unwrap();
        let e = load(&path, &LoadOptions::default()).expect_err("a bad header");
        let message = e.to_string();
        assert!(
            message.contains("header.cgns") && message.contains(expected),
            "{message}"
        );
        assert!(!message.contains('\n'));
    }
}

/// Prefixes of the small files (every 16th length), and their bytes
/// overwritten with 0xff (every 8th; a load takes about 2 ms here): an
/// error naming the file or a read; never a panic. A prefix reads only
/// when it holds every byte the file's writer used, and then it reads as
/// the whole file.
#[test]
fn every_truncation_and_corruption_is_an_error_or_a_read() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cgns-corpus");
    std::fs::create_dir_all(&dir).unwrap();
    for name in [
        "structured.cgns",
        "unstructured.cgns",
        "polyhedral.cgns",
        "structured-adf.cgns",
        "unstructured-adf.cgns",
        "polyhedral-adf.cgns",
    ] {
        let bytes = std::fs::read(data(&format!("cgns/{name}"))).unwrap();
        let path = dir.join(name);
        // An ADF file ends in unused bytes up to the end of its last
        // block; its header says where the data ends (block and offset in
        // hexadecimal), and a prefix that holds it is the whole file.
        let whole = if name.contains("adf") {
            let hex = |r: std::ops::Range<usize>| {
                usize::from_str_radix(std::str::from_utf8(&bytes[r]).unwrap(), 16).unwrap()
            };
            hex(146..154) * 4096 + hex(154..158) + 1
        } else {
            bytes.len()
        };
        let full = load(&data(&format!("cgns/{name}")), &LoadOptions::default()).unwrap();
        for len in (0..bytes.len()).step_by(16) {
            std::fs::write(&path, &bytes[..len]).unwrap();
            match load(&path, &LoadOptions::default()) {
                Err(e) => assert!(e.to_string().contains(name), "{len}: {e}"),
                Ok(m) => {
                    assert!(len >= whole, "{len}: a prefix read");
                    assert_same(&m, &full, name);
                }
            }
        }
        // ADF writes its pointers, counts and sizes as hexadecimal text: a
        // digit changed to another digit points elsewhere, which is the
        // deeper test there.
        let values: &[u8] = if name.contains("adf") {
            &[0xff, b'9']
        } else {
            &[0xff]
        };
        let mut copy = bytes.clone();
        for &value in values {
            for at in (0..bytes.len()).step_by(8) {
                copy[at] = value;
                std::fs::write(&path, &copy).unwrap();
                if let Err(e) = load(&path, &LoadOptions::default()) {
                    assert!(e.to_string().contains(name), "{at}: {e}");
                }
                copy[at] = bytes[at];
            }
        }
    }
}
