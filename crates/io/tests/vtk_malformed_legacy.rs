//! Malformed legacy files, cut or damaged in their counts, indices, values,
//! cells and keywords: each kind of damage gives its own error, naming the
//! file and the place.

use tetray_io::vtk::{VtkError, read_legacy_bytes};
use tetray_mesh::cells::CellError;

const HEAD: &str = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n";
const FIVE_POINTS: &str = "POINTS 5 float\n0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n";

fn legacy_err(body: &str) -> VtkError {
    let text = format!("{HEAD}{body}");
    let err = read_legacy_bytes(text.as_bytes(), "bad.vtk").expect_err(body);
    assert!(err.to_string().starts_with("bad.vtk: "), "{err}");
    err
}

#[test]
fn legacy_count_errors() {
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 1 6\n4 0 1 2 3 4\nCELL_TYPES 1\n10\n"
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::CountMismatch { expected: 5, found: 6, section, .. }) if section.contains("CELLS")),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 2 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n"
    ));
    assert!(
        matches!(
            &e,
            VtkError::Cell(CellError::CountMismatch {
                expected: 2,
                found: 1,
                ..
            })
        ),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 1 5\n7 0 1 2 3\nCELL_TYPES 1\n10\n"
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::Invalid { message, .. }) if message.contains("claims 7 points")),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n"
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::CountMismatch { expected: 1, found: 2, section, .. }) if section.contains("CELL_TYPES")),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}POINT_DATA 4\nSCALARS s float\nLOOKUP_TABLE default\n1 2 3 4\n"
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::CountMismatch { expected: 5, found: 4, section, .. }) if section.contains("POINT_DATA")),
        "{e}"
    );
    // A scalar array shorter than the points: the file ends inside it.
    let e = legacy_err(&format!(
        "{FIVE_POINTS}POINT_DATA 5\nSCALARS s float\nLOOKUP_TABLE default\n1 2 3\n"
    ));
    assert!(
        matches!(&e, VtkError::Truncated { expected: 5, found: 3, section, .. } if section.contains("SCALARS \"s\"")),
        "{e}"
    );
    let e = legacy_err("POINTS 5 float\n0 0 0 1 0 0\n");
    assert!(
        matches!(
            &e,
            VtkError::Truncated {
                expected: 15,
                found: 6,
                ..
            }
        ),
        "{e}"
    );
    // Without its blank line, METADATA still stops at the next section.
    let e = legacy_err(&format!(
        "{FIVE_POINTS}METADATA\nINFORMATION 0\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n"
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::CountMismatch { section, .. }) if section.contains("CELL_TYPES")),
        "{e}"
    );
}

#[test]
fn legacy_index_value_and_cell_errors() {
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 2 10\n4 0 1 2 3\n4 1 2 3 9\nCELL_TYPES 2\n10 10\n"
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::BadIndex {
                cell: 1,
                index: 9,
                npoints: 5,
                ..
            })
        ),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 1 5\n4 0 -1 2 3\nCELL_TYPES 1\n10\n"
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::BadIndex {
                cell: 0,
                index: -1,
                ..
            })
        ),
        "{e}"
    );
    let e = legacy_err("POINTS 2 float\n0 0 0 1 nan 0\n");
    assert!(
        matches!(&e, VtkError::Cell(CellError::NonFinite { section, .. }) if section.contains("point 1 coordinate y")),
        "{e}"
    );
    let e = legacy_err("POINTS 1 double\n0 1e300 0\n");
    assert!(
        matches!(e, VtkError::Cell(CellError::NonFinite { index: 1, .. })),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}POINT_DATA 5\nSCALARS s double 1\nLOOKUP_TABLE default\n0 1 inf 3 4\n"
    ));
    assert!(
        matches!(&e, VtkError::Cell(CellError::NonFinite { index: 2, section, .. }) if section.contains("\"s\"")),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 2 16\n4 0 1 2 3\n10 0 1 2 3 4 0 1 2 3 4\nCELL_TYPES 2\n10 78\n"
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::UnsupportedCell {
                cell: 1,
                type_id: 78,
                type_name: "Bezier tetrahedron",
                ..
            })
        ),
        "{e}"
    );
    assert!(
        e.to_string().contains("cell 1") && e.to_string().contains("78"),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n99\n"
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::UnsupportedCell { type_id: 99, .. })
        ),
        "{e}"
    );
    let e = legacy_err(&format!(
        "{FIVE_POINTS}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n12\n"
    ));
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::CellSize {
                expected: 8,
                found: 4,
                ..
            })
        ),
        "{e}"
    );
}

#[test]
fn legacy_format_errors() {
    let e = read_legacy_bytes(
        b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n",
        "p.vtk",
    );
    assert!(matches!(e, Err(VtkError::UnsupportedDataset { found, .. }) if found == "POLYDATA"));
    let e = read_legacy_bytes(b"<?xml version=\"1.0\"?>\n", "x.vtk").unwrap_err();
    assert!(matches!(e, VtkError::Syntax { line: 1, .. }), "{e}");
    let e = legacy_err("POINTS 1 bit\n0 0 0\n");
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::Unsupported {
                what: "data type",
                ..
            })
        ),
        "{e}"
    );
    let e = legacy_err("POINTS 1 float\n0 0 x\n");
    assert!(
        matches!(&e, VtkError::Syntax { line: 6, message, .. } if message.contains("\"x\"")),
        "{e}"
    );
    let e = legacy_err(&format!("{FIVE_POINTS}BANANAS 3\n"));
    assert!(
        matches!(&e, VtkError::Syntax { message, .. } if message.contains("BANANAS")),
        "{e}"
    );
    let e = legacy_err(&format!("{FIVE_POINTS}CELLS 1 5\n4 0 1 2 3\n"));
    assert!(
        matches!(&e, VtkError::Cell(CellError::Invalid { message, .. }) if message.contains("CELL_TYPES")),
        "{e}"
    );
}
