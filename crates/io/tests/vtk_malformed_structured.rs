//! Malformed structured, parallel and multi-block files: truncation at
//! every offset never panics and is an error wherever the format can tell;
//! inconsistent and garbled files each give one error naming the file and
//! the problem.

mod structured_common;

use std::path::Path;
use tetray_mesh::cells::CellError;

use structured_common::{
    ENCODINGS, Enc, Piece, TempDir, array, extent_attr, section, unstructured_piece, warped_points,
    xml_file,
};
use tetray_io::vtk::{
    VtkError, read_legacy_bytes, read_multiblock_file, read_parallel_file, read_vtu_bytes,
};

/// Where a written file is complete: the rest is closing tags the reader
/// does not need (appended data), or the final newline.
fn complete_at(bytes: &[u8], enc: Enc) -> usize {
    match enc {
        Enc::AppendedRaw | Enc::AppendedBase64 => {
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
    }
}

fn sweep_xml(bytes: &[u8], complete: usize) {
    for len in 0..bytes.len() {
        match read_vtu_bytes(&bytes[..len], "cut") {
            Err(e) => assert!(e.to_string().starts_with("cut: "), "{e}"),
            Ok(_) => assert!(
                len >= complete,
                "prefix of {len} of {} bytes parsed",
                bytes.len()
            ),
        }
    }
}

fn small_files(enc: Enc) -> Vec<Vec<u8>> {
    let e = [0, 2, 0, 1, 0, 1];
    let data = || {
        vec![
            section(
                "PointData",
                "",
                vec![array("t", "Float64", 1, (0..12).map(f64::from).collect())],
            ),
            section("CellData", "", vec![array("c", "Int32", 1, vec![1.0, 2.0])]),
        ]
    };
    let mut vts = data();
    vts.push(section(
        "Points",
        "",
        vec![array("P", "Float64", 3, warped_points(e))],
    ));
    let mut vtr = data();
    vtr.push(section(
        "Coordinates",
        "",
        vec![
            array("x", "Float64", 1, vec![0.0, 1.0, 2.0]),
            array("y", "Float64", 1, vec![0.0, 1.0]),
            array("z", "Float32", 1, vec![0.0, 1.0]),
        ],
    ));
    let piece = |sections| Piece {
        attrs: extent_attr(e),
        sections,
    };
    let whole = "WholeExtent=\"0 2 0 1 0 1\"";
    vec![
        xml_file("StructuredGrid", whole, &[piece(vts)], enc),
        xml_file("RectilinearGrid", whole, &[piece(vtr)], enc),
        xml_file(
            "ImageData",
            &format!("{whole} Origin=\"0 0 0\" Spacing=\"1 1 1\""),
            &[piece(data())],
            enc,
        ),
    ]
}

#[test]
fn truncated_structured_xml_files_are_errors() {
    for enc in ENCODINGS {
        for bytes in small_files(enc) {
            read_vtu_bytes(&bytes, "whole").unwrap();
            sweep_xml(&bytes, complete_at(&bytes, enc));
        }
    }
}

#[test]
fn truncated_legacy_structured_files_are_errors() {
    let files = [
        "DATASET STRUCTURED_POINTS\nDIMENSIONS 3 2 2\nORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA 12\nSCALARS t float\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7 8 9 10 11\n",
        "DATASET RECTILINEAR_GRID\nDIMENSIONS 3 2 2\nX_COORDINATES 3 float\n0 1 2\nY_COORDINATES 2 float\n0 1\nZ_COORDINATES 2 float\n0 1\nCELL_DATA 2\nSCALARS c float\nLOOKUP_TABLE default\n1 2\n",
        "DATASET STRUCTURED_GRID\nDIMENSIONS 2 2 2\nPOINTS 8 float\n0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1\n",
    ];
    for body in files {
        let text = format!("# vtk DataFile Version 3.0\nt\nASCII\n{body}");
        let bytes = text.as_bytes();
        read_legacy_bytes(bytes, "whole").unwrap();
        let mut errors = 0;
        for len in 0..bytes.len() {
            if let Err(e) = read_legacy_bytes(&bytes[..len], "cut") {
                assert!(
                    e.to_string().starts_with("cut: ") || e.to_string().starts_with("cut holds"),
                    "{e}"
                );
                errors += 1;
            }
        }
        // A legacy file cut between sections (or inside a last number) is
        // a valid shorter file; most cuts are not.
        assert!(errors > bytes.len() * 8 / 10, "{errors} of {}", bytes.len());
    }
}

#[test]
fn truncated_parallel_and_multiblock_files_are_errors() {
    let dir = TempDir::new("cut-collections");
    let e = [0, 1, 0, 1, 0, 1];
    let piece = Piece {
        attrs: extent_attr(e),
        sections: vec![section(
            "Points",
            "",
            vec![array("P", "Float64", 3, warped_points(e))],
        )],
    };
    dir.write(
        "p/a.vts",
        &xml_file(
            "StructuredGrid",
            "WholeExtent=\"0 1 0 1 0 1\"",
            &[piece],
            Enc::Ascii,
        ),
    );
    let pvts = "<VTKFile type=\"PStructuredGrid\" version=\"1.0\">\n<PStructuredGrid WholeExtent=\"0 1 0 1 0 1\">\n<Piece Extent=\"0 1 0 1 0 1\" Source=\"p/a.vts\"/>\n</PStructuredGrid>\n</VTKFile>\n";
    let vtm = "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\">\n<vtkMultiBlockDataSet>\n<Block index=\"0\" name=\"a\">\n<DataSet index=\"0\" file=\"p/a.vts\"/>\n</Block>\n</vtkMultiBlockDataSet>\n</VTKFile>\n";
    type Reader = fn(&Path) -> Result<tetray_io::vtk::VtkRead, VtkError>;
    let readers: [(&str, &str, Reader); 2] = [
        ("cut.pvts", pvts, read_parallel_file),
        ("cut.vtm", vtm, |p| read_multiblock_file(p, None)),
    ];
    for (name, text, read) in readers {
        let complete = text.rfind("</VTKFile>").unwrap() + "</VTKFile>".len();
        for len in 0..text.len() {
            let path = dir.write(name, &text.as_bytes()[..len]);
            match read(&path) {
                Err(e) => assert!(
                    e.to_string().starts_with(&path.display().to_string()),
                    "{e}"
                ),
                Ok(_) => assert!(len >= complete, "{name}: prefix of {len} parsed"),
            }
        }
    }
}

fn vts_with(extent_text: &str, whole: &str, npoints: usize) -> Vec<u8> {
    let piece = Piece {
        attrs: format!("Extent=\"{extent_text}\""),
        sections: vec![section(
            "Points",
            "",
            vec![array(
                "P",
                "Float64",
                3,
                (0..3 * npoints).map(|v| v as f64).collect(),
            )],
        )],
    };
    xml_file("StructuredGrid", whole, &[piece], Enc::Ascii)
}

fn err(bytes: &[u8], name: &str) -> (VtkError, String) {
    let e = read_vtu_bytes(bytes, name).expect_err(name);
    let text = e.to_string();
    assert!(text.starts_with(&format!("{name}: ")), "{text}");
    (e, text)
}

#[test]
fn inconsistent_structured_xml_files_are_named_errors() {
    // An extent of 3 x 2 x 2 = 12 points, 11 given.
    let (e, text) = err(&vts_with("0 2 0 1 0 1", "", 11), "short.vts");
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 36,
                found: 33,
                ..
            })
        ),
        "{text}"
    );
    assert!(text.contains("Piece 0 Points"), "{text}");
    let (_, text) = err(&vts_with("0 2 0 x 0 1", "", 12), "garbled.vts");
    assert!(
        text.contains("extent \"0 2 0 x 0 1\" is not six integers"),
        "{text}"
    );
    let (_, text) = err(&vts_with("0 2 1 0 0 1", "", 12), "backwards.vts");
    assert!(text.contains("ends before it starts along y"), "{text}");
    let (_, text) = err(
        &vts_with("0 2 0 1 0 1", "WholeExtent=\"0 1 0 1 0 1\"", 12),
        "outside.vts",
    );
    assert!(text.contains("is not inside WholeExtent"), "{text}");
    let no_extent = xml_file(
        "StructuredGrid",
        "",
        &[Piece {
            attrs: String::new(),
            sections: vec![],
        }],
        Enc::Ascii,
    );
    let (_, text) = err(&no_extent, "noextent.vts");
    assert!(text.contains("no Extent attribute"), "{text}");

    let rect = |x: Vec<f64>, arrays: usize| {
        let mut coords = vec![
            array("x", "Float64", 1, x),
            array("y", "Float64", 1, vec![0.0, 1.0]),
            array("z", "Float64", 1, vec![0.0, 1.0]),
        ];
        coords.truncate(arrays);
        let piece = Piece {
            attrs: extent_attr([0, 2, 0, 1, 0, 1]),
            sections: vec![section("Coordinates", "", coords)],
        };
        xml_file("RectilinearGrid", "", &[piece], Enc::Base64)
    };
    let (e, text) = err(&rect(vec![0.0, 1.0], 3), "short.vtr");
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 3,
                found: 2,
                ..
            })
        ),
        "{text}"
    );
    assert!(text.contains("x coordinates"), "{text}");
    let (_, text) = err(&rect(vec![0.0, 1.0, 2.0], 2), "two.vtr");
    assert!(
        text.contains("<Coordinates> holds 2 DataArrays, not 3"),
        "{text}"
    );

    let image = |attrs: &str, values: usize| {
        let piece = Piece {
            attrs: extent_attr([0, 2, 0, 1, 0, 1]),
            sections: vec![section(
                "PointData",
                "",
                vec![array("t", "Float64", 1, vec![0.0; values])],
            )],
        };
        xml_file("ImageData", attrs, &[piece], Enc::AppendedRaw)
    };
    let (e, text) = err(&image("", 11), "short.vti");
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 12,
                found: 11,
                ..
            })
        ),
        "{text}"
    );
    assert!(text.contains("PointData DataArray \"t\""), "{text}");
    let (_, text) = err(&image("Spacing=\"1 x 1\"", 12), "spacing.vti");
    assert!(
        text.contains("<ImageData> Spacing: \"1 x 1\" is not 3 finite numbers"),
        "{text}"
    );
    let (_, text) = err(&image("Direction=\"1 0 0 0 1 0\"", 12), "direction.vti");
    assert!(text.contains("is not 9 finite numbers"), "{text}");

    // A ghost array that is not one flag per cell.
    let piece = unstructured_piece(
        &warped_points([0, 1, 0, 1, 0, 1]),
        &structured_common::block_hexes([2, 2, 2]),
        &[12],
        vec![],
        vec![array("vtkGhostType", "UInt8", 2, vec![0.0, 0.0])],
        "",
    );
    let (_, text) = err(
        &xml_file("UnstructuredGrid", "", &[piece], Enc::Ascii),
        "ghost.vtu",
    );
    assert!(text.contains("ghost flags"), "{text}");
    // A dataset element that does not match the file type.
    let text = String::from_utf8(vts_with("0 1 0 1 0 1", "", 8))
        .unwrap()
        .replacen("<StructuredGrid ", "<ImageData ", 1);
    let (_, text) = err(text.as_bytes(), "mixed.vts");
    assert!(
        text.contains("<VTKFile type=\"StructuredGrid\"> holds a <ImageData> element"),
        "{text}"
    );
}

const LEGACY: &str = "# vtk DataFile Version 3.0\nt\nASCII\n";

fn legacy_err(body: &str, name: &str) -> (VtkError, String) {
    let e = read_legacy_bytes(format!("{LEGACY}{body}").as_bytes(), name).expect_err(body);
    let text = e.to_string();
    assert!(text.starts_with(&format!("{name}: ")), "{text}");
    (e, text)
}

#[test]
fn inconsistent_legacy_structured_files_are_named_errors() {
    let (e, text) = legacy_err(
        "DATASET STRUCTURED_GRID\nDIMENSIONS 2 2 2\nPOINTS 7 float\n0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1\n",
        "g.vtk",
    );
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 8,
                found: 7,
                ..
            })
        ),
        "{text}"
    );
    let (_, text) = legacy_err(
        "DATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\nX_COORDINATES 2 float\n0 1\nY_COORDINATES 2 float\n0 1\n",
        "r.vtk",
    );
    assert!(text.contains("no Z_COORDINATES"), "{text}");
    let (e, text) = legacy_err(
        "DATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\nX_COORDINATES 3 float\n0 1 2\nY_COORDINATES 2 float\n0 1\nZ_COORDINATES 2 float\n0 1\n",
        "r3.vtk",
    );
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 2,
                found: 3,
                ..
            })
        ),
        "{text}"
    );
    let (_, text) = legacy_err("DATASET STRUCTURED_POINTS\nDIMENSIONS 2 two 2\n", "d.vtk");
    assert!(text.contains("\"two\""), "{text}");
    let (_, text) = legacy_err(
        "DATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\nORIGIN 0 nan 0\n",
        "o.vtk",
    );
    assert!(
        text.contains("ORIGIN: \"nan\" is not a finite number"),
        "{text}"
    );
    let (_, text) = legacy_err("DATASET STRUCTURED_POINTS\nORIGIN 0 0 0\n", "nodims.vtk");
    assert!(text.contains("STRUCTURED_POINTS: no DIMENSIONS"), "{text}");
    let (e, text) = legacy_err(
        "DATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\nPOINT_DATA 9\nSCALARS t float\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7 8\n",
        "pd.vtk",
    );
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 8,
                found: 9,
                ..
            })
        ),
        "{text}"
    );
    let (_, text) = legacy_err(
        "DATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n",
        "cells.vtk",
    );
    assert!(text.contains("CELLS in a structured dataset"), "{text}");
    let (_, text) = legacy_err(
        "DATASET STRUCTURED_POINTS\nDIMENSIONS 100000 100000 100000\n",
        "huge.vtk",
    );
    assert!(text.contains("grid size"), "{text}");
}

#[test]
fn garbled_parallel_and_multiblock_files_are_named_errors() {
    let dir = TempDir::new("garbled-collections");
    let cases: [(&str, &str, &str); 6] = [
        (
            "nopiece.pvtu",
            "<VTKFile type=\"PUnstructuredGrid\"><PUnstructuredGrid></PUnstructuredGrid></VTKFile>",
            "no <Piece Source=\"...\"> element",
        ),
        (
            "poly.pvtu",
            "<VTKFile type=\"PPolyData\"><PPolyData><Piece Source=\"a.vtp\"/></PPolyData></VTKFile>",
            "dataset \"PPolyData\" is not supported",
        ),
        ("root.pvtu", "<Other/>", "the root element is <Other>"),
        (
            "tags.vtm",
            "<VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet></Block></VTKFile>",
            "malformed XML",
        ),
        (
            "type.vtm",
            "<VTKFile type=\"vtkHierarchicalBoxDataSet\"><vtkHierarchicalBoxDataSet/></VTKFile>",
            "dataset \"vtkHierarchicalBoxDataSet\" is not supported",
        ),
        (
            "empty.vtm",
            "<VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet/></VTKFile>",
            "holds no cells in 0 block files",
        ),
    ];
    for (name, text, want) in cases {
        let path = dir.write(name, text.as_bytes());
        let e = if name.ends_with(".vtm") {
            read_multiblock_file(&path, None)
        } else {
            read_parallel_file(&path)
        }
        .unwrap_err()
        .to_string();
        assert!(e.starts_with(&path.display().to_string()), "{e}");
        assert!(e.contains(want), "{name}: {e}");
    }
    // A .vtm naming itself: an error, not a stack overflow.
    let path = dir.write(
        "self.vtm",
        b"<VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet><DataSet index=\"0\" file=\"self.vtm\"/></vtkMultiBlockDataSet></VTKFile>",
    );
    let e = read_multiblock_file(&path, None).unwrap_err().to_string();
    assert!(e.contains("nested more than 16 deep"), "{e}");
}

/// Found by the `vtk_legacy` fuzz target: DIMENSIONS of 0 made an extent
/// that ends before it starts, and counting its points overflowed (a
/// panic where overflow is checked). A zero dimension is a grid without
/// points: a clear error at the load.
#[test]
fn a_zero_dimension_is_an_error_not_an_overflow() {
    for dataset in [
        "STRUCTURED_POINTS\nDIMENSIONS 0 3 3\nSPACING 1 1 1\nORIGIN 0 0 0",
        "STRUCTURED_POINTS\nDIMENSIONS 3 3 -2",
    ] {
        let dir = std::env::temp_dir().join(format!("tetray-zero-dims-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch");
        let path = dir.join("zero.vtk");
        std::fs::write(&path, format!("{LEGACY}DATASET {dataset}\n")).expect("write");
        let err = tetray_io::load(&path, &tetray_io::LoadOptions::default()).expect_err(dataset);
        let text = err.to_string();
        assert!(text.contains("zero.vtk"), "{text}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
