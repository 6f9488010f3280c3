//! The CGNS reader (HDF5 storage) on VTK's multi-zone CFL3D solution
//! (`multi.cgns`, converted from its ADF storage by CGNS's `adf2hdf`) and
//! on small files written for each part of the standard (`data/cgns`,
//! made by the script beside them).

use std::path::{Path, PathBuf};

use tetray_io::{LoadOptions, LoadedMesh, load};

fn data(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(path)
}

fn loaded(path: &str) -> LoadedMesh {
    load(&data(path), &LoadOptions::default()).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn field<'a>(mesh: &'a LoadedMesh, name: &str) -> &'a [f32] {
    &mesh
        .mesh
        .fields
        .iter()
        .find(|f| f.name == name)
        .expect(name)
        .values
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
    let volume: f64 = m
        .mesh
        .tets
        .iter()
        .map(|t| {
            let [a, b, c, d] = t.map(|i| m.mesh.points[i as usize].as_dvec3() + origin);
            (b - a).cross(c - a).dot(d - a).abs() / 6.0
        })
        .sum();
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

/// The ADF storage, by name or by content, is refused in one line that
/// says how to convert it.
#[test]
fn the_adf_storage_is_refused_with_the_conversion() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cgns");
    std::fs::create_dir_all(&dir).unwrap();
    let mut head = vec![0xc0, 0xa8, 0xa3, 0xa9];
    head.extend(b"ADF Database Version A02011>AdF0");
    head.resize(4096, 0);
    for name in ["old.cgns", "old"] {
        let path = dir.join(name);
        std::fs::write(&path, &head).unwrap();
        let e = load(&path, &LoadOptions::default()).expect_err("ADF");
        let message = e.to_string();
        assert!(
            message.contains("ADF") && message.contains("adf2hdf"),
            "{message}"
        );
        assert!(!message.contains('\n'));
    }
}

/// Prefixes of the small files (every 16th length), and their bytes
/// overwritten with 0xff (every 8th; a load takes about 2 ms here): an
/// error naming the file or a read; never a panic.
#[test]
fn every_truncation_and_corruption_is_an_error_or_a_read() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cgns-corpus");
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["structured.cgns", "unstructured.cgns"] {
        let bytes = std::fs::read(data(&format!("cgns/{name}"))).unwrap();
        let path = dir.join(name);
        for len in (0..bytes.len()).step_by(16) {
            std::fs::write(&path, &bytes[..len]).unwrap();
            let e = load(&path, &LoadOptions::default()).expect_err("a prefix");
            assert!(e.to_string().contains(name), "{len}: {e}");
        }
        let mut copy = bytes.clone();
        for at in (0..bytes.len()).step_by(8) {
            copy[at] = 0xff;
            std::fs::write(&path, &copy).unwrap();
            if let Err(e) = load(&path, &LoadOptions::default()) {
                assert!(e.to_string().contains(name), "{at}: {e}");
            }
            copy[at] = bytes[at];
        }
    }
}
