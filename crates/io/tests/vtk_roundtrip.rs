//! Every writer mode reads back bit-exact (f32 points and scalars, tets,
//! field names).

mod vtk_common;

use tetray_io::vtk::{
    VtuEncoding, VtuOptions, read_legacy_bytes, read_vtu_bytes, write_legacy, write_vtu,
    write_vtu_with,
};
use vtk_common::{assert_bit_exact, sample_mesh};

const ENCODINGS: [VtuEncoding; 4] = [
    VtuEncoding::Ascii,
    VtuEncoding::Base64,
    VtuEncoding::AppendedRaw,
    VtuEncoding::AppendedBase64,
];

#[test]
fn legacy_ascii_and_binary_round_trip_bit_exact() {
    let mesh = sample_mesh();
    for binary in [false, true] {
        let mut bytes = Vec::new();
        write_legacy(&mesh, &mut bytes, binary).unwrap();
        let read = read_legacy_bytes(&bytes, "rt.vtk").unwrap();
        assert_bit_exact(&read.mesh, &mesh, &format!("legacy binary={binary}"));
        assert_eq!(read.cells.tetra, mesh.tets.len());
        assert_eq!(read.cells.tets_from_split, 0);
        assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    }
}

#[test]
fn vtu_every_encoding_with_and_without_zlib_round_trips_bit_exact() {
    let mesh = sample_mesh();
    for encoding in ENCODINGS {
        for zlib in [false, true] {
            let mut bytes = Vec::new();
            write_vtu(&mesh, &mut bytes, encoding, zlib).unwrap();
            let mode = format!("{encoding:?} zlib={zlib}");
            let read = read_vtu_bytes(&bytes, "rt.vtu").unwrap_or_else(|e| panic!("{mode}: {e}"));
            assert_bit_exact(&read.mesh, &mesh, &mode);
            assert!(read.warnings.is_empty(), "{mode}: {:?}", read.warnings);
            let text = String::from_utf8_lossy(&bytes);
            let compressed = zlib && encoding != VtuEncoding::Ascii;
            assert_eq!(text.contains("vtkZLibDataCompressor"), compressed, "{mode}");
        }
    }
}

#[test]
fn vtu_uint32_headers_big_endian_and_many_zlib_blocks_round_trip() {
    let mesh = sample_mesh();
    for encoding in ENCODINGS {
        for (header_u64, big_endian) in [(false, false), (false, true), (true, true)] {
            for zlib in [false, true] {
                let options = VtuOptions {
                    encoding,
                    zlib,
                    header_u64,
                    big_endian,
                    // Not a multiple of 4 or 8: blocks split values, and
                    // the last block is partial.
                    zlib_block_size: 37,
                };
                let mut bytes = Vec::new();
                write_vtu_with(&mesh, &mut bytes, &options).unwrap();
                let mode = format!("{options:?}");
                let read =
                    read_vtu_bytes(&bytes, "rt.vtu").unwrap_or_else(|e| panic!("{mode}: {e}"));
                assert_bit_exact(&read.mesh, &mesh, &mode);
            }
        }
    }
}

#[test]
fn a_mesh_without_fields_or_cells_round_trips() {
    let mut mesh = sample_mesh();
    mesh.fields.clear();
    mesh.tets.clear();
    let mut bytes = Vec::new();
    write_legacy(&mesh, &mut bytes, true).unwrap();
    assert_bit_exact(
        &read_legacy_bytes(&bytes, "e.vtk").unwrap().mesh,
        &mesh,
        "legacy",
    );
    for encoding in ENCODINGS {
        let mut bytes = Vec::new();
        write_vtu(&mesh, &mut bytes, encoding, true).unwrap();
        assert_bit_exact(&read_vtu_bytes(&bytes, "e.vtu").unwrap().mesh, &mesh, "vtu");
    }
}

#[test]
fn files_round_trip_through_the_path_readers() {
    let mesh = sample_mesh();
    let dir = std::env::temp_dir().join(format!("tetray-vtk-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let legacy = dir.join("m.vtk");
    let vtu = dir.join("m.vtu");
    write_legacy(&mesh, &mut std::fs::File::create(&legacy).unwrap(), true).unwrap();
    write_vtu(
        &mesh,
        &mut std::fs::File::create(&vtu).unwrap(),
        VtuEncoding::AppendedRaw,
        true,
    )
    .unwrap();
    assert_bit_exact(
        &tetray_io::vtk::read_legacy_file(&legacy).unwrap().mesh,
        &mesh,
        "file vtk",
    );
    assert_bit_exact(
        &tetray_io::vtk::read_vtu_file(&vtu).unwrap().mesh,
        &mesh,
        "file vtu",
    );
    let missing = dir.join("missing.vtu");
    let err = tetray_io::vtk::read_vtu_file(&missing).unwrap_err();
    assert!(err.to_string().contains("missing.vtu"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
