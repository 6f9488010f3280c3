//! PLOT3D layouts and bad files: byte orders, Fortran records, a grid
//! count, IBLANK, trailing bytes; truncation at many offsets, wrong
//! dimensions, non-finite values. Each bad file is a specific error naming
//! the file; none panics.

use std::path::Path;

use tetray_io::{IoError, LoadOptions, Plot3dRead, load, load_plot3d_bytes, read_plot3d_bytes};
use tetray_mesh::MeshError;

/// How a synthetic file is written.
#[derive(Debug, Clone, Copy, Default)]
struct Enc {
    little: bool,
    records: bool,
    grid_count: bool,
}

fn int(v: i32, e: Enc) -> [u8; 4] {
    if e.little {
        v.to_le_bytes()
    } else {
        v.to_be_bytes()
    }
}

fn float(v: f32, e: Enc) -> [u8; 4] {
    if e.little {
        v.to_le_bytes()
    } else {
        v.to_be_bytes()
    }
}

/// Appends `body` as one Fortran record when `e.records`.
fn record(out: &mut Vec<u8>, body: &[u8], e: Enc) {
    let len = int(body.len() as i32, e);
    if e.records {
        out.extend(len);
    }
    out.extend(body);
    if e.records {
        out.extend(len);
    }
}

fn header(dims: [i32; 3], e: Enc) -> Vec<u8> {
    let mut out = Vec::new();
    if e.grid_count {
        record(&mut out, &int(1, e), e);
    }
    let dims: Vec<u8> = dims.iter().flat_map(|&d| int(d, e)).collect();
    record(&mut out, &dims, e);
    out
}

/// A 4 x 3 x 3 grid, gently sheared, coordinates in PLOT3D order.
const DIMS: [i32; 3] = [4, 3, 3];
const N: usize = 36;

fn coordinates() -> [Vec<f32>; 3] {
    let mut c = [Vec::new(), Vec::new(), Vec::new()];
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..4 {
                let (x, y, z) = (i as f32, j as f32, k as f32);
                c[0].push(x + 0.1 * y);
                c[1].push(y + 0.05 * z);
                c[2].push(z);
            }
        }
    }
    c
}

fn xyz_file(coords: &[Vec<f32>; 3], iblank: Option<&[i32]>, e: Enc) -> Vec<u8> {
    let mut out = header(DIMS, e);
    let mut body: Vec<u8> = coords.iter().flatten().flat_map(|&v| float(v, e)).collect();
    if let Some(ib) = iblank {
        body.extend(ib.iter().flat_map(|&v| int(v, e)));
    }
    record(&mut out, &body, e);
    out
}

/// Density 1 + x, momentum (1, 2, 2) (|m| = 3), energy 10.
fn q_arrays() -> [Vec<f32>; 5] {
    let x = &coordinates()[0];
    [
        x.iter().map(|x| 1.0 + x).collect(),
        vec![1.0; N],
        vec![2.0; N],
        vec![2.0; N],
        vec![10.0; N],
    ]
}

fn q_file(dims: [i32; 3], arrays: &[Vec<f32>; 5], e: Enc) -> Vec<u8> {
    let mut out = header(dims, e);
    let conditions: Vec<u8> = [0.5f32, 1.0, 1e5, 0.0]
        .iter()
        .flat_map(|&v| float(v, e))
        .collect();
    record(&mut out, &conditions, e);
    let body: Vec<u8> = arrays.iter().flatten().flat_map(|&v| float(v, e)).collect();
    record(&mut out, &body, e);
    out
}

fn read(xyz: &[u8], q: Option<&[u8]>) -> Result<Plot3dRead, IoError> {
    read_plot3d_bytes(xyz, q, "test grid")
}

#[test]
fn every_layout_reads_the_same_mesh() {
    let coords = coordinates();
    let plain = read(
        &xyz_file(&coords, None, Enc::default()),
        Some(&q_file(DIMS, &q_arrays(), Enc::default())),
    )
    .unwrap();
    assert_eq!(plain.mesh.tets.len(), 5 * 3 * 2 * 2);
    assert!(plain.warnings.is_empty(), "{:?}", plain.warnings);
    assert_eq!(plain.conditions, Some([0.5, 1.0, 1e5, 0.0]));
    for bits in 0..16 {
        let e = Enc {
            little: bits & 1 != 0,
            records: bits & 2 != 0,
            grid_count: bits & 4 != 0,
        };
        let iblank = (bits & 8 != 0).then(|| vec![1; N]);
        let xyz = xyz_file(&coords, iblank.as_deref(), e);
        let q = q_file(DIMS, &q_arrays(), e);
        let r =
            read(&xyz, Some(&q)).unwrap_or_else(|err| panic!("{e:?} iblank {}: {err}", bits & 8));
        assert_eq!(r.mesh, plain.mesh, "{e:?}");
    }
}

#[test]
fn derived_scalars() {
    let r = read(
        &xyz_file(&coordinates(), None, Enc::default()),
        Some(&q_file(DIMS, &q_arrays(), Enc::default())),
    )
    .unwrap();
    let names: Vec<&str> = r.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "density",
            "pressure",
            "velocity_magnitude",
            "stagnation_energy",
            "momentum_magnitude"
        ]
    );
    // Point 1: x = 1, density 2, |m| = 3, E = 10: p = 0.4 (10 - 9 / 4) =
    // 3.1, |v| = 1.5. f32 results of f64 math: tolerance 1 ulp-ish, 1e-6.
    let at = |name: &str| r.mesh.field(name).unwrap().values[1];
    assert!((at("density") - 2.0).abs() < 1e-6);
    assert!((at("pressure") - 3.1).abs() < 1e-6);
    assert!((at("velocity_magnitude") - 1.5).abs() < 1e-6);
    assert!((at("momentum_magnitude") - 3.0).abs() < 1e-6);
    assert!((at("stagnation_energy") - 10.0).abs() < 1e-6);
}

#[test]
fn iblank_zero_leaves_out_the_hexes_around_the_point() {
    let mut iblank = vec![1; N];
    // Point (1, 1, 1) is a corner of the 8 hexes (0|1, 0|1, 0|1).
    iblank[1 + 4 * (1 + 3)] = 0;
    let r = read(
        &xyz_file(&coordinates(), Some(&iblank), Enc::default()),
        None,
    )
    .unwrap();
    assert_eq!(r.blanked_hexahedra, 8);
    assert_eq!(r.mesh.tets.len(), 5 * (12 - 8));
    assert!(r.warnings.iter().any(|w| w.contains("IBLANK")));
}

#[test]
fn trailing_bytes_are_tolerated_and_reported() {
    let mut xyz = xyz_file(&coordinates(), None, Enc::default());
    // Float-looking padding (not small ints, so not a truncated IBLANK).
    xyz.extend(std::iter::repeat_n(0x40, 20));
    let mut q = q_file(DIMS, &q_arrays(), Enc::default());
    q.extend([0; 484]);
    let r = read(&xyz, Some(&q)).unwrap();
    assert_eq!(r.warnings.len(), 2, "{:?}", r.warnings);
    assert!(r.warnings[0].contains("20 bytes after the grid"));
    assert!(r.warnings[1].contains("484 bytes after the solution"));
}

fn expect_truncated(
    result: Result<Plot3dRead, IoError>,
    what: &str,
    expected_len: usize,
    found_len: usize,
) {
    match result {
        Err(IoError::Plot3dTruncated {
            file,
            what: w,
            expected,
            found,
            ..
        }) => {
            assert!(
                file.starts_with("test grid") || file.contains("bluntfin"),
                "{file}"
            );
            assert_eq!((w, expected, found), (what, expected_len, found_len));
        }
        Err(IoError::Plot3dHeader { .. }) if found_len < 12 => {}
        other => panic!("{what} cut to {found_len} bytes: expected truncation, got {other:?}"),
    }
}

#[test]
fn truncated_blunt_fin_never_panics() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let xyz = std::fs::read(dir.join("bluntfinxyz.bin")).unwrap();
    let q = std::fs::read(dir.join("bluntfinq.bin")).unwrap();
    let q_needed = 12 + 16 + 20 * 40 * 32 * 32;
    assert_eq!(q.len(), q_needed + 484);
    // Every offset of the header, then a spread through the data.
    let cuts = |len: usize| (0..64).chain((64..len).step_by(997)).chain(len - 8..len);
    for cut in cuts(xyz.len()) {
        expect_truncated(
            read_plot3d_bytes(&xyz[..cut], None, "bluntfin"),
            "grid",
            xyz.len(),
            cut,
        );
    }
    // The grid is fine; the solution is cut. Within its 484 spare bytes it
    // still reads (checked once: each success splits the whole grid).
    for cut in cuts(q_needed) {
        expect_truncated(
            read_plot3d_bytes(&xyz, Some(&q[..cut]), "bluntfin"),
            "solution",
            q_needed,
            cut,
        );
    }
    assert!(read_plot3d_bytes(&xyz, Some(&q[..q_needed]), "bluntfin").is_ok());
}

#[test]
fn truncated_iblank_is_not_mistaken_for_padding() {
    let iblank = vec![1; N];
    let full = xyz_file(&coordinates(), Some(&iblank), Enc::default());
    for cut in [12 + 12 * N + 4, 12 + 14 * N, full.len() - 1] {
        match read(&full[..cut], None) {
            Err(IoError::Plot3dTruncated {
                layout, expected, ..
            }) => {
                assert!(layout.contains("IBLANK"), "{layout}");
                assert_eq!(expected, full.len());
            }
            other => panic!("cut {cut}: {other:?}"),
        }
    }
    // Cut exactly after z it is a valid grid without IBLANK: nothing in
    // the bytes can tell otherwise.
    assert!(read(&full[..12 + 12 * N], None).is_ok());
}

#[test]
fn wrong_dimensions() {
    let coords = coordinates();
    let xyz = xyz_file(&coords, None, Enc::default());
    // A solution for another grid.
    let q = q_file(
        [4, 3, 2],
        &q_arrays().map(|a| a[..24].to_vec()),
        Enc::default(),
    );
    let e = read(&xyz, Some(&q)).unwrap_err();
    assert!(
        matches!(&e, IoError::Plot3dDimsMismatch { xyz_dims: [4, 3, 3], q_dims: [4, 3, 2], q_file, .. } if q_file == "test grid (q)"),
        "{e}"
    );
    // Dimensions that are no grid: 1 point thick, negative, zero.
    for dims in [[4, 3, 1], [4, -3, 3], [0, 3, 3]] {
        let mut bad = xyz.clone();
        bad[..12].copy_from_slice(&header(dims, Enc::default()));
        let e = read(&bad, None).unwrap_err();
        assert!(
            matches!(&e, IoError::Plot3dHeader { what: "grid", .. }),
            "{dims:?}: {e}"
        );
        assert!(e.to_string().starts_with("test grid"), "{e}");
    }
    // A plausible header far larger than the file.
    let mut bad = xyz.clone();
    bad[..12].copy_from_slice(&header([1000, 1000, 1000], Enc::default()));
    let e = read(&bad, None).unwrap_err();
    assert!(
        matches!(
            e,
            IoError::Plot3dTruncated {
                expected: 12_000_000_012,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn non_finite_values_are_named() {
    let mut coords = coordinates();
    coords[0][3] = f32::NAN;
    let xyz = xyz_file(&coords, None, Enc::default());
    let e = load_plot3d_bytes(&xyz, None, "nan grid").unwrap_err();
    assert!(e.to_string().starts_with("nan grid: "), "{e}");
    assert!(
        matches!(
            e.mesh_root(),
            Some(MeshError::NonFiniteCoordinate {
                point: 3,
                axis: 'x',
                ..
            })
        ),
        "{e}"
    );

    let xyz = xyz_file(&coordinates(), None, Enc::default());
    let mut arrays = q_arrays();
    arrays[0][5] = f32::NAN;
    let e =
        load_plot3d_bytes(&xyz, Some(&q_file(DIMS, &arrays, Enc::default())), "nan q").unwrap_err();
    assert!(
        matches!(e.mesh_root(), Some(MeshError::NonFiniteScalar { field, point: 5, .. }) if field == "density"),
        "{e}"
    );
    // Zero density: the derived pressure is not finite there.
    let mut arrays = q_arrays();
    arrays[0][7] = 0.0;
    let e = load_plot3d_bytes(&xyz, Some(&q_file(DIMS, &arrays, Enc::default())), "zero q")
        .unwrap_err();
    assert!(
        matches!(e.mesh_root(), Some(MeshError::NonFiniteScalar { field, point: 7, .. }) if field == "pressure"),
        "{e}"
    );
}

#[test]
fn load_dispatches_by_name() {
    let dir = std::env::temp_dir().join(format!("tetray-mesh-load-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let xyz = dir.join("boxxyz.bin");
    std::fs::write(
        &xyz,
        xyz_file(
            &coordinates(),
            None,
            Enc {
                little: true,
                ..Enc::default()
            },
        ),
    )
    .unwrap();
    // No sibling q: loads without fields, with a warning.
    let loaded = load(&xyz, &LoadOptions::default()).unwrap();
    assert!(loaded.mesh.fields.is_empty());
    assert!(
        loaded
            .report
            .warnings
            .iter()
            .any(|w| w.contains("boxq.bin not found")),
        "{:?}",
        loaded.report.warnings
    );
    // The sibling is found.
    std::fs::write(
        dir.join("boxq.bin"),
        q_file(
            DIMS,
            &q_arrays(),
            Enc {
                little: true,
                ..Enc::default()
            },
        ),
    )
    .unwrap();
    let loaded = load(&xyz, &LoadOptions::default()).unwrap();
    assert_eq!(loaded.mesh.fields.len(), 5);
    assert_eq!(loaded.report.format, "PLOT3D");
    assert_eq!(loaded.report.cells_split, 12);
    // An explicit q that does not exist is an error naming it.
    let options = LoadOptions {
        plot3d_q: Some(dir.join("missing.q")),
        ..LoadOptions::default()
    };
    assert!(
        matches!(load(&xyz, &options), Err(IoError::Io { file, .. }) if file.contains("missing.q"))
    );
    // A legacy VTK file with an explicit flat tetrahedron: once an error,
    // now dropped and reported (a few bad cells never stop a render; only
    // a file with nothing left, or broken data, is rejected).
    let vtk = dir.join("flat.vtk");
    std::fs::write(
        &vtk,
        "# vtk DataFile Version 3.0\nflat\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n\
         0 0 0 1 0 0 0 1 0 0 0 1 0.5 0.5 0\nCELLS 2 10\n4 0 1 2 3\n4 0 1 2 4\nCELL_TYPES 2\n10\n10\n",
    )
    .unwrap();
    let loaded = load(&vtk, &LoadOptions::default()).unwrap();
    assert_eq!(loaded.report.excluded.flat_tets, 1);
    assert_eq!(loaded.mesh.tets, [[0, 1, 2, 3]]);
    assert!(
        loaded
            .report
            .changes()
            .unwrap()
            .contains("1 flat tetrahedra dropped")
    );
    // Unknown names: the content decides; a file it does not name either
    // is an error saying what the file starts with, a missing one an I/O
    // error.
    let obj = dir.join("mesh.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\n").unwrap();
    let e = load(&obj, &LoadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::UnknownFormat { .. }), "{e}");
    assert!(e.to_string().contains("it starts with \"v 0 0 0"), "{e}");
    let e = load(&dir.join("none.obj"), &LoadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::Io { .. }), "{e}");
    // A legacy file under another name is read by its content.
    let renamed = dir.join("mesh.dat");
    std::fs::copy(&vtk, &renamed).unwrap();
    let by_content = load(&renamed, &LoadOptions::default()).unwrap();
    assert_eq!(by_content.mesh.tets, loaded.mesh.tets);
    std::fs::remove_dir_all(&dir).unwrap();
}
