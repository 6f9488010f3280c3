//! Malformed input: truncation at every offset never panics and is an
//! error wherever the format can tell; each kind of damage gives its own
//! error, naming the file and the place.

mod vtk_common;

use tetray_io::vtk::{
    VtkError, VtkRead, VtuEncoding, read_legacy_bytes, read_vtu_bytes, write_legacy, write_vtu,
};
use tetray_mesh::cells::CellError;
use vtk_common::sample_mesh;

/// Reads every prefix of `bytes`. Each must be an error unless `may_parse`
/// allows that length (a legacy file cut at a section boundary is a valid
/// shorter file; trailing closing tags after complete appended data are
/// not needed).
fn sweep(
    bytes: &[u8],
    read: fn(&[u8], &str) -> Result<VtkRead, VtkError>,
    may_parse: impl Fn(usize) -> bool,
) {
    let mut errors = 0;
    for len in 0..bytes.len() {
        match read(&bytes[..len], "cut") {
            Err(e) => {
                errors += 1;
                assert!(e.to_string().starts_with("cut: "), "{e}");
            }
            Ok(_) => assert!(
                may_parse(len),
                "prefix of {len} of {} bytes parsed",
                bytes.len()
            ),
        }
    }
    assert!(
        errors > bytes.len() * 9 / 10,
        "{errors} errors for {} prefixes",
        bytes.len()
    );
}

/// Whether a legacy file cut at `len` ends on a section boundary: after the
/// rest of a cut token and whitespace comes a keyword that may start a
/// section of a complete shorter file, or nothing.
fn legacy_boundary(bytes: &[u8], len: usize) -> bool {
    let skip_space = |r: &[u8]| r.iter().take_while(|b| b.is_ascii_whitespace()).count();
    let section_or_end = |r: &[u8]| {
        r.is_empty()
            || ["CELLS", "POINT_DATA", "SCALARS"]
                .iter()
                .any(|k| r.starts_with(k.as_bytes()))
    };
    let rest = &bytes[len..];
    let token = rest.iter().take_while(|b| !b.is_ascii_whitespace()).count();
    let after_token = &rest[token..];
    section_or_end(&rest[skip_space(rest)..])
        || section_or_end(&after_token[skip_space(after_token)..])
}

#[test]
fn truncated_legacy_files_are_errors() {
    let mesh = sample_mesh();
    for binary in [false, true] {
        let mut bytes = Vec::new();
        write_legacy(&mesh, &mut bytes, binary).unwrap();
        sweep(&bytes, read_legacy_bytes, |len| {
            legacy_boundary(&bytes, len)
        });
    }
}

#[test]
fn truncated_vtu_files_are_errors() {
    let mesh = sample_mesh();
    for encoding in [
        VtuEncoding::Ascii,
        VtuEncoding::Base64,
        VtuEncoding::AppendedRaw,
        VtuEncoding::AppendedBase64,
    ] {
        for zlib in [false, true] {
            let mut bytes = Vec::new();
            write_vtu(&mesh, &mut bytes, encoding, zlib).unwrap();
            let complete = match encoding {
                VtuEncoding::AppendedRaw | VtuEncoding::AppendedBase64 => {
                    let tail = b"\n  </AppendedData>";
                    let end = bytes.windows(tail.len()).rposition(|w| w == tail).unwrap();
                    // Base64 padding at the very end carries no data.
                    end - bytes[..end]
                        .iter()
                        .rev()
                        .take_while(|&&b| b == b'=')
                        .count()
                }
                _ => bytes.len() - 1,
            };
            sweep(&bytes, read_vtu_bytes, |len| len >= complete);
        }
    }
}

fn vtu(piece_body: &str, root_attributes: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" byte_order=\"LittleEndian\"{root_attributes}>\n\
         <UnstructuredGrid>\n<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">\n{piece_body}</Piece>\n\
         </UnstructuredGrid>\n</VTKFile>\n"
    )
}

const POINTS4: &str = "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>\n";

fn cells(conn: &str, offsets: &str, types: &str) -> String {
    format!(
        "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">{conn}</DataArray>\n\
         <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">{offsets}</DataArray>\n\
         <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">{types}</DataArray>\n</Cells>\n"
    )
}

fn vtu_err(text: &str) -> VtkError {
    let err = read_vtu_bytes(text.as_bytes(), "bad.vtu").expect_err(text);
    assert!(err.to_string().starts_with("bad.vtu: "), "{err}");
    err
}

#[test]
fn vtu_count_index_and_value_errors() {
    assert!(
        read_vtu_bytes(
            vtu(&format!("{POINTS4}{}", cells("0 1 2 3", "4", "10")), "").as_bytes(),
            "ok.vtu"
        )
        .is_ok()
    );
    let e = vtu_err(&vtu(
        &format!("{POINTS4}{}", cells("0 1 2 3", "4 4", "10")),
        "",
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::CountMismatch { expected: 1, found: 2, section, .. }) if section.contains("\"offsets\"")),
        "{e}"
    );
    let e = vtu_err(&vtu(
        &format!("{POINTS4}{}", cells("0 1 2 3 0", "4", "10")),
        "",
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::CountMismatch { expected: 4, found: 5, section, .. }) if section.contains("connectivity")),
        "{e}"
    );
    let e = vtu_err(&vtu(
        &format!("{POINTS4}{}", cells("0 1 2 4", "4", "10")),
        "",
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::BadIndex {
                cell: 0,
                index: 4,
                npoints: 4,
                ..
            })
        ),
        "{e}"
    );
    let short_points = POINTS4.replace(" 0 0 1<", "<");
    let e = vtu_err(&vtu(
        &format!("{short_points}{}", cells("0 1 2 3", "4", "10")),
        "",
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 12,
                found: 9,
                ..
            })
        ),
        "{e}"
    );
    let data = "<PointData><DataArray type=\"Float64\" Name=\"rho\" format=\"ascii\">1 2 3</DataArray></PointData>\n";
    let e = vtu_err(&vtu(
        &format!("{data}{POINTS4}{}", cells("0 1 2 3", "4", "10")),
        "",
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::CountMismatch { expected: 4, found: 3, section, .. }) if section.contains("\"rho\"")),
        "{e}"
    );
    let data = "<PointData><DataArray type=\"Float64\" Name=\"rho\" format=\"ascii\">1 NaN 3 4</DataArray></PointData>\n";
    let e = vtu_err(&vtu(
        &format!("{data}{POINTS4}{}", cells("0 1 2 3", "4", "10")),
        "",
    ));
    assert!(
        matches!(e, VtkError::Cell(CellError::NonFinite { index: 1, .. })),
        "{e}"
    );
    let e = vtu_err(&vtu(
        &format!("{POINTS4}{}", cells("0 1 2 3 0 1 2 3 0 1", "10", "78")),
        "",
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::UnsupportedCell {
                cell: 0,
                type_id: 78,
                ..
            })
        ),
        "{e}"
    );
    let e = vtu_err(&vtu(
        &format!(
            "{POINTS4}{}",
            cells("0 1 2 3", "4", "10").replace("\"types\"", "\"kinds\"")
        ),
        "",
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::Invalid { message, .. }) if message.contains("\"types\"")),
        "{e}"
    );
}

#[test]
fn vtu_format_errors() {
    let body = format!("{POINTS4}{}", cells("0 1 2 3", "4", "10"));
    let e = vtu_err(&vtu(&body, "").replace("\"UnstructuredGrid\"", "\"PolyData\""));
    assert!(
        matches!(&e, VtkError::UnsupportedDataset { found, .. } if found == "PolyData"),
        "{e}"
    );
    let e = vtu_err(&vtu(&body, " header_type=\"UInt16\""));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::Unsupported {
                what: "header_type",
                ..
            })
        ),
        "{e}"
    );
    let e = vtu_err(&vtu(&body, "").replace("LittleEndian", "MiddleEndian"));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::Unsupported {
                what: "byte_order",
                ..
            })
        ),
        "{e}"
    );
    let e = vtu_err(&vtu(
        &body.replacen("format=\"ascii\"", "format=\"hex\"", 1),
        "",
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::Unsupported {
                what: "DataArray format",
                ..
            })
        ),
        "{e}"
    );
    let e = vtu_err(&vtu(&body.replace("</Cells>", "</Cels>"), ""));
    assert!(matches!(e, VtkError::Xml { .. }), "{e}");
    let e = vtu_err("<Mesh></Mesh>");
    assert!(matches!(e, VtkError::Xml { .. }), "{e}");
    let appended = body.replacen(
        "format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 1</DataArray>",
        "format=\"appended\" offset=\"0\"/>",
        1,
    );
    let e = vtu_err(&vtu(&appended, ""));
    assert!(
        matches!(&e, VtkError::Cell(CellError::Invalid { message, .. }) if message.contains("AppendedData")),
        "{e}"
    );
}

/// A file written by our writer, then damaged.
fn written(encoding: VtuEncoding, zlib: bool) -> Vec<u8> {
    let mut bytes = Vec::new();
    write_vtu(&sample_mesh(), &mut bytes, encoding, zlib).unwrap();
    bytes
}

fn replace_once(bytes: &[u8], from: &str, to: &str) -> Vec<u8> {
    let at = bytes
        .windows(from.len())
        .position(|w| w == from.as_bytes())
        .expect(from);
    let mut out = bytes[..at].to_vec();
    out.extend_from_slice(to.as_bytes());
    out.extend_from_slice(&bytes[at + from.len()..]);
    out
}

#[test]
fn binary_payload_errors() {
    // Bad base64: a character outside the alphabet in the first array.
    let bytes = written(VtuEncoding::Base64, false);
    let open = b"format=\"binary\">\n";
    let at = bytes.windows(open.len()).position(|w| w == open).unwrap() + open.len() + 12;
    let mut bad = bytes.clone();
    bad[at] = b'*';
    let e = read_vtu_bytes(&bad, "b64.vtu").unwrap_err();
    assert!(
        matches!(&e, VtkError::Base64 { section, .. } if section.contains("\"density\"")),
        "{e}"
    );

    // Corrupt zlib: the first block's zlib header byte (after the 4 UInt64
    // header values of the first appended array).
    let bytes = written(VtuEncoding::AppendedRaw, true);
    let marker = bytes.windows(2).position(|w| w == b" _").unwrap() + 2;
    let mut bad = bytes.clone();
    bad[marker + 32] ^= 0xff;
    let e = read_vtu_bytes(&bad, "z.vtu").unwrap_err();
    assert!(
        matches!(&e, VtkError::Zlib { block: 0, blocks: 1, section, .. } if section.contains("\"density\"")),
        "{e}"
    );
    // A compressed size larger than the data left: truncated.
    let mut bad = bytes.clone();
    bad[marker + 24..marker + 32].copy_from_slice(&u64::MAX.to_le_bytes());
    let e = read_vtu_bytes(&bad, "z.vtu").unwrap_err();
    assert!(matches!(e, VtkError::Truncated { .. }), "{e}");

    let e = read_vtu_bytes(
        &replace_once(&bytes, "vtkZLibDataCompressor", "vtkLZ4DataCompressor"),
        "c.vtu",
    )
    .unwrap_err();
    assert!(
        matches!(&e, VtkError::Cell(CellError::Unsupported { what: "compressor", value, .. }) if value == "vtkLZ4DataCompressor"),
        "{e}"
    );
    let e = read_vtu_bytes(
        &replace_once(&bytes, "encoding=\"raw\"", "encoding=\"gzip\""),
        "c.vtu",
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::Unsupported {
                what: "AppendedData encoding",
                ..
            })
        ),
        "{e}"
    );
    let e = read_vtu_bytes(&replace_once(&bytes, "   _", "   X"), "c.vtu").unwrap_err();
    assert!(matches!(e, VtkError::Xml { .. }), "{e}");
    let e = read_vtu_bytes(
        &replace_once(
            &bytes,
            "type=\"Float32\" Name=\"Points\"",
            "type=\"Float16\" Name=\"Points\"",
        ),
        "c.vtu",
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::Unsupported {
                what: "DataArray type",
                ..
            })
        ),
        "{e}"
    );
}

/// Random byte damage (bytes chosen to hit numbers, tags and base64) must
/// give Ok or Err, never a panic, an overflow or a runaway allocation.
#[test]
fn random_damage_never_panics() {
    let mesh = sample_mesh();
    let mut files = Vec::new();
    for binary in [false, true] {
        let mut bytes = Vec::new();
        write_legacy(&mesh, &mut bytes, binary).unwrap();
        files.push((bytes, true));
    }
    for encoding in [
        VtuEncoding::Ascii,
        VtuEncoding::Base64,
        VtuEncoding::AppendedRaw,
        VtuEncoding::AppendedBase64,
    ] {
        for zlib in [false, true] {
            files.push((written(encoding, zlib), false));
        }
    }
    let palette = b"0123456789-+.eE \n<>/\"=_Aa*\xff\x00";
    let mut rng = vtk_common::Lcg(3);
    for (bytes, legacy) in &files {
        for _ in 0..1500 {
            let mut damaged = bytes.clone();
            for _ in 0..1 + rng.below(3) {
                let at = rng.below(damaged.len() as u32) as usize;
                damaged[at] = if rng.below(4) == 0 {
                    rng.next_u32() as u8
                } else {
                    palette[rng.below(palette.len() as u32) as usize]
                };
            }
            let _ = if *legacy {
                read_legacy_bytes(&damaged, "d")
            } else {
                read_vtu_bytes(&damaged, "d")
            };
        }
    }
}
