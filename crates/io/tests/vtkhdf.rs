//! The VTKHDF reader on VTK's own files and on small files written for
//! each part of the format (data/vtkhdf, made by the script beside them).

use std::path::{Path, PathBuf};

use tetray_io::{LoadOptions, load};

fn data(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(path)
}

/// `can-vtu.hdf`, written by VTK from the crushed-can Exodus model, holds
/// the same 4800 hexahedra and 6724 points as `can.vtu` (counts from VTK's
/// vtkHDFReader and the file's NumberOfCells / NumberOfPoints): it loads
/// to the same mesh.
#[test]
fn the_crushed_can_in_vtkhdf_is_the_crushed_can_in_vtu() {
    let hdf = load(&data("real/can-vtu.hdf"), &LoadOptions::default()).expect("VTKHDF");
    let vtu = load(&data("real/can.vtu"), &LoadOptions::default()).expect("VTU");
    assert_eq!(hdf.report.format, "VTKHDF");
    assert_eq!(hdf.report.cells_split, vtu.report.cells_split);
    assert_eq!(hdf.report.excluded, vtu.report.excluded);
    assert_eq!(hdf.mesh.points.len(), vtu.mesh.points.len());
    assert_eq!(hdf.mesh.tets.len(), vtu.mesh.tets.len());
    // Both files were written from the same model in the same order: the
    // points, tetrahedra and every point field agree exactly.
    assert_eq!(hdf.mesh.points, vtu.mesh.points);
    assert_eq!(hdf.mesh.tets, vtu.mesh.tets);
    assert_eq!(hdf.mesh.fields.len(), vtu.mesh.fields.len());
    for field in &vtu.mesh.fields {
        let same = hdf.mesh.fields.iter().find(|f| f.name == field.name);
        assert_eq!(
            same.map(|f| &f.values),
            Some(&field.values),
            "{}",
            field.name
        );
    }
}

fn field<'a>(mesh: &'a tetray_mesh::TetMesh, name: &str) -> &'a [f32] {
    &mesh
        .fields
        .iter()
        .find(|f| f.name == name)
        .expect(name)
        .values
}

fn at_step(path: &str, time_step: Option<usize>, time: Option<f64>) -> tetray_io::LoadedMesh {
    let opts = LoadOptions {
        time_step,
        time,
        ..LoadOptions::default()
    };
    load(&data(path), &opts).expect(path)
}

/// Two hexahedra in two partitions over two steps of the same geometry
/// (`make_fixtures.py`): the partitions weld into one grid of 12 points,
/// and each step's point array is its own (x, then 2x; stored as f32, and
/// x is exact in f32 here).
#[test]
fn temporal_partitions_weld_and_each_step_has_its_own_values() {
    let first = at_step("vtkhdf/cube_temporal.vtkhdf", None, None);
    assert_eq!(first.report.format, "VTKHDF");
    assert_eq!(first.report.times, vec![0.0, 0.5]);
    assert_eq!(first.report.time_step, Some(0));
    assert_eq!(first.report.pieces.pieces, 2);
    assert_eq!(first.mesh.points.len(), 12);
    assert_eq!(first.report.cells_split, 2);
    let second = at_step("vtkhdf/cube_temporal.vtkhdf", Some(1), None);
    let nearest = at_step("vtkhdf/cube_temporal.vtkhdf", None, Some(0.4));
    assert_eq!(nearest.report.time_step, Some(1));
    for (loaded, scale) in [(&first, 1.0), (&second, 2.0), (&nearest, 2.0)] {
        let s = field(&loaded.mesh, "s");
        for (p, v) in loaded.mesh.points.iter().zip(s) {
            let x = p.x + loaded.origin().x as f32;
            assert_eq!(*v, scale * x, "point {p}");
        }
    }
    assert_eq!(second.mesh.tets, first.mesh.tets);
    let past = load(
        &data("vtkhdf/cube_temporal.vtkhdf"),
        &LoadOptions {
            time_step: Some(2),
            ..LoadOptions::default()
        },
    )
    .expect_err("step 2 of 2");
    assert!(past.to_string().contains("time step 2"), "{past}");
}

/// Image data: the extent, origin and spacing of the attributes, arrays
/// shaped (z, y, x). f = x + 2y + 3z at every point (values exact in f32:
/// quarters and halves of small integers).
#[test]
fn image_data_has_its_geometry_and_array_order() {
    let (loaded, grid) =
        tetray_io::load_image_data(&data("vtkhdf/image.vtkhdf"), &LoadOptions::default())
            .expect("image");
    assert_eq!(grid.dims, [4, 3, 2]);
    assert_eq!(grid.origin, [1.0, 2.0, 3.0]);
    assert_eq!(grid.spacing, [0.5, 0.25, 1.0]);
    assert_eq!(loaded.mesh.points.len(), 24);
    let origin = loaded.origin().as_vec3();
    let f = field(&loaded.mesh, "f");
    for (p, v) in loaded.mesh.points.iter().zip(f) {
        let q = *p + origin;
        assert_eq!(*v, q.x + 2.0 * q.y + 3.0 * q.z, "point {q}");
    }
}

/// A temporal image replays its stored rows by the per-array step
/// offsets (0, 1, 0) from gzip-compressed chunks.
#[test]
fn temporal_image_rows_follow_the_step_offsets() {
    let step = |s| {
        let opts = LoadOptions {
            time_step: Some(s),
            ..LoadOptions::default()
        };
        tetray_io::load_image_data(&data("vtkhdf/image_temporal.vtkhdf"), &opts)
            .expect("temporal image")
    };
    let base = field(&step(0).0.mesh, "f").to_vec();
    let (loaded, grid) = step(1);
    assert_eq!(loaded.report.times, vec![0.0, 1.0, 2.0]);
    let ten: Vec<f32> = base.iter().map(|v| 10.0 * v).collect();
    assert_eq!(field(&loaded.mesh, "f"), &ten[..]);
    assert_eq!(grid.fields[0].values, ten);
    assert_eq!(field(&step(2).0.mesh, "f"), &base[..]);
    // The grid alone (shear-warp's read) is the same grid.
    let alone = tetray_io::load_image_grid(
        &data("vtkhdf/image_temporal.vtkhdf"),
        &LoadOptions {
            time_step: Some(1),
            ..LoadOptions::default()
        },
    )
    .expect("grid");
    assert_eq!(
        (alone.dims, alone.origin, alone.spacing),
        (grid.dims, grid.origin, grid.spacing)
    );
    assert_eq!(alone.fields[0].values, ten);
}

/// The unit cube as one polyhedron: split into tetrahedra of total volume
/// 1 (to f32 rounding), its linear point field interpolated exactly at the
/// points the split adds.
#[test]
fn a_polyhedron_is_split_with_its_field_interpolated() {
    let loaded = at_step("vtkhdf/polyhedron.vtkhdf", None, None);
    let mesh = &loaded.mesh;
    let volume: f64 = mesh
        .tets
        .iter()
        .map(|t| {
            let [a, b, c, d] = t.map(|i| mesh.points[i as usize].as_dvec3());
            (b - a).cross(c - a).dot(d - a).abs() / 6.0
        })
        .sum();
    assert!((volume - 1.0).abs() < 1e-6, "volume {volume}");
    assert!(mesh.points.len() > 8, "the split adds centres");
    let s = field(mesh, "s");
    for (p, v) in mesh.points.iter().zip(s) {
        assert!((v - (p.x + p.y + p.z)).abs() < 1e-6, "point {p}: {v}");
    }
}

#[test]
fn polydata_is_refused_in_one_line() {
    let err = load(&data("vtkhdf/polydata.vtkhdf"), &LoadOptions::default()).expect_err("surfaces");
    let message = err.to_string();
    assert!(
        message.contains("PolyData") && message.contains("surfaces"),
        "{message}"
    );
    assert!(!message.contains('\n'), "{message}");
}

/// A VTKHDF file under an HDF5 extension, or none, is told from Exodus by
/// its `/VTKHDF` group.
#[test]
fn vtkhdf_is_recognised_by_content() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("vtkhdf_content");
    std::fs::create_dir_all(&dir).expect("temp dir");
    for name in ["cube.h5", "cube.hdf5", "cube"] {
        let path = dir.join(name);
        std::fs::copy(data("vtkhdf/cube_temporal.vtkhdf"), &path).expect("copy");
        let loaded = load(&path, &LoadOptions::default()).expect(name);
        assert_eq!(loaded.report.format, "VTKHDF", "{name}");
    }
}

/// Every prefix of the small files is an error naming the file, never a
/// panic (the truncation corpus).
#[test]
fn every_truncation_is_a_clear_error() {
    for name in [
        "cube_temporal.vtkhdf",
        "polyhedron.vtkhdf",
        "image_temporal.vtkhdf",
    ] {
        let bytes = std::fs::read(data(&format!("vtkhdf/{name}"))).expect(name);
        let opts = tetray_io::VtkHdfOptions::default();
        tetray_io::read_vtkhdf_bytes(&bytes, name, &opts).expect("whole file");
        for len in 0..bytes.len() {
            match tetray_io::read_vtkhdf_bytes(&bytes[..len], name, &opts) {
                Err(e) => assert!(e.to_string().contains(name), "{len}: {e}"),
                Ok(_) => panic!("{name}: the first {len} of {} bytes read", bytes.len()),
            }
        }
    }
}

/// Every byte of a small file overwritten in turn: an error or a read,
/// never a panic (corrupt sizes, addresses and type codes inside the
/// container, past the superblock's length check).
#[test]
fn every_corrupted_byte_is_an_error_or_a_read() {
    for name in [
        "cube_temporal.vtkhdf",
        "polyhedron.vtkhdf",
        "image_temporal.vtkhdf",
    ] {
        let bytes = std::fs::read(data(&format!("vtkhdf/{name}"))).expect(name);
        let opts = tetray_io::VtkHdfOptions::default();
        let mut copy = bytes.clone();
        for at in 0..bytes.len() {
            for value in [0x00, 0xff, bytes[at] ^ 0x01] {
                copy[at] = value;
                if let Err(e) = tetray_io::read_vtkhdf_bytes(&copy, name, &opts) {
                    assert!(e.to_string().contains(name), "{at}: {e}");
                }
            }
            copy[at] = bytes[at];
        }
    }
}

/// Found by the `hdf5_formats` fuzz target: a 31 kB file whose `Steps`
/// group has no `Values` and declares `NSteps` = 2^32 + 2; the reader made
/// that many times (32 GB). A count that is not a whole number up to 2^32
/// is one error; a smaller one goes through the memory preflight.
#[test]
fn a_huge_step_count_is_one_error() {
    let e = load(
        &data("fuzz/vtkhdf-huge-step-count.vtkhdf"),
        &LoadOptions::default(),
    )
    .expect_err("no file has that many steps");
    let text = e.to_string();
    assert!(text.contains("vtkhdf-huge-step-count.vtkhdf"), "{text}");
    assert!(text.contains("NSteps is 4294967298"), "{text}");
}
