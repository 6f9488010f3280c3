//! Structured grids: the StructuredGrid.vts sample, and small grids written
//! here as `.vts`, `.vtr`, `.vti` (every encoding) and legacy
//! STRUCTURED_GRID, RECTILINEAR_GRID, STRUCTURED_POINTS, read back.

mod structured_common;

use std::time::Instant;

use structured_common::{
    ENCODINGS, Enc, Piece, TempDir, array, extent_attr, real_data, section, warped_points, xml_file,
};
use tetray_io::vtk::{VtkError, VtkRead, read_legacy_bytes, read_vtu_bytes, read_vtu_file};
use tetray_io::{LoadOptions, load};

fn dims(e: [i64; 6]) -> [usize; 3] {
    [0, 1, 2].map(|a| (e[2 * a + 1] - e[2 * a] + 1) as usize)
}

/// Asserts the mesh's points are `want` (f64), in order: relative to the
/// origin the reader stored them from, rounded to f32 (as it does).
fn assert_points(read: &VtkRead, want: &[f64], what: &str) {
    let got: Vec<f32> = read.mesh.points.iter().flat_map(|p| p.to_array()).collect();
    let o = read.origin.to_array();
    let want: Vec<f32> = want
        .iter()
        .enumerate()
        .map(|(i, &v)| (v - o[i % 3]) as f32)
        .collect();
    assert_eq!(got, want, "{what}: points");
}

fn field<'a>(read: &'a VtkRead, name: &str) -> &'a [f32] {
    let names: Vec<&str> = read.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    &read
        .mesh
        .fields
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no field {name}: {names:?}"))
        .values
}

#[test]
fn structured_grid_sample_has_the_counts_of_its_extent() {
    let path = real_data("StructuredGrid.vts");
    // The counts come from the file's own WholeExtent attribute.
    let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
    let at = text.find("WholeExtent=\"").unwrap() + 13;
    let extent: Vec<i64> = text[at..at + text[at..].find('"').unwrap()]
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    assert_eq!(extent, [0, 5, 0, 11, 0, 8]);
    let d = dims(extent.try_into().unwrap());
    let start = Instant::now();
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    eprintln!(
        "StructuredGrid.vts loaded in {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    assert_eq!(loaded.mesh.points.len(), d[0] * d[1] * d[2]);
    assert_eq!(
        loaded.report.cells_split,
        (d[0] - 1) * (d[1] - 1) * (d[2] - 1)
    );
    assert_eq!(loaded.report.format, "VTK XML StructuredGrid");
    assert_eq!(loaded.report.validation.components, 1);
    let names: Vec<&str> = loaded.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["Density", "Momentum_magnitude", "StagnationEnergy"]);
    let read = read_vtu_file(&path).unwrap();
    assert_eq!(read.cells.hexahedra, 440);
    assert_eq!(read.dataset, "StructuredGrid");
}

/// Point fields "temp" (x + 2y + 3z per point index, Float64) and "vel"
/// (3 components, Float32), cell field "cell" (its index, Int32).
fn sections_for(
    npoints: usize,
    ncells: usize,
) -> (
    Vec<f64>,
    structured_common::Section,
    structured_common::Section,
) {
    let temp: Vec<f64> = (0..npoints).map(|p| 0.5 * p as f64 - 3.0).collect();
    let vel: Vec<f64> = (0..3 * npoints).map(|v| (v % 7) as f64).collect();
    let cell: Vec<f64> = (0..ncells).map(|c| c as f64).collect();
    (
        temp.clone(),
        section(
            "PointData",
            "Scalars=\"temp\"",
            vec![
                array("temp", "Float64", 1, temp),
                array("vel", "Float32", 3, vel),
            ],
        ),
        section("CellData", "", vec![array("cell", "Int32", 1, cell)]),
    )
}

fn check_fields(read: &VtkRead, temp: &[f64], what: &str) {
    let want: Vec<f32> = temp.iter().map(|&v| v as f32).collect();
    assert_eq!(field(read, "temp"), want.as_slice(), "{what}");
    // Tuple (0, 1, 2) has magnitude sqrt(5).
    assert_eq!(field(read, "vel_magnitude")[0], 5f32.sqrt(), "{what}");
    // Point 0 is in cell 0 only: its average is 0.
    assert_eq!(field(read, "cell")[0], 0.0, "{what}");
}

#[test]
fn vts_round_trips_in_every_encoding() {
    let extent = [2, 5, 0, 2, -1, 3];
    let [nx, ny, nz] = dims(extent);
    let points = warped_points(extent);
    let ncells = (nx - 1) * (ny - 1) * (nz - 1);
    let (temp, pd, cd) = sections_for(nx * ny * nz, ncells);
    for enc in ENCODINGS {
        let piece = Piece {
            attrs: extent_attr(extent),
            sections: vec![
                pd.clone(),
                cd.clone(),
                section(
                    "Points",
                    "",
                    vec![array("Points", "Float64", 3, points.clone())],
                ),
            ],
        };
        let whole = extent_attr(extent).replace("Extent", "WholeExtent");
        let bytes = xml_file("StructuredGrid", &whole, &[piece], enc);
        let read = read_vtu_bytes(&bytes, "grid.vts").unwrap();
        let what = format!("{enc:?}");
        assert_points(&read, &points, &what);
        assert_eq!(read.cells.hexahedra, 3 * 2 * 4, "{what}");
        check_fields(&read, &temp, &what);
    }
}

#[test]
fn vtr_round_trips_in_every_encoding() {
    let (x, y, z) = (
        vec![0.0, 1.0, 3.0, 6.0],
        vec![-2.0, 0.5, 2.0],
        vec![-1.0, 0.0, 1.0, 2.0, 4.0],
    );
    let extent = [0, 3, 0, 2, 0, 4];
    let mut want = Vec::new();
    for &pz in &z {
        for &py in &y {
            for &px in &x {
                want.extend_from_slice(&[px, py, pz]);
            }
        }
    }
    let (temp, pd, cd) = sections_for(60, 24);
    for enc in ENCODINGS {
        let coordinates = section(
            "Coordinates",
            "",
            vec![
                array("x", "Float64", 1, x.clone()),
                array("y", "Float32", 1, y.clone()),
                array("z", "Float64", 1, z.clone()),
            ],
        );
        let piece = Piece {
            attrs: extent_attr(extent),
            sections: vec![pd.clone(), cd.clone(), coordinates],
        };
        let bytes = xml_file(
            "RectilinearGrid",
            "WholeExtent=\"0 3 0 2 0 4\"",
            &[piece],
            enc,
        );
        let read = read_vtu_bytes(&bytes, "grid.vtr").unwrap();
        let what = format!("{enc:?}");
        assert_points(&read, &want, &what);
        assert_eq!(read.cells.hexahedra, 24, "{what}");
        assert_eq!(read.dataset, "RectilinearGrid");
        check_fields(&read, &temp, &what);
    }
}

#[test]
fn vti_places_points_by_origin_spacing_and_direction() {
    let extent = [2, 4, 0, 2, 1, 3];
    // A quarter turn about z: index x goes to world y, index y to world -x.
    let attrs = "WholeExtent=\"0 4 0 2 1 3\" Origin=\"10 20 30\" Spacing=\"0.5 2 4\" \
                 Direction=\"0 -1 0 1 0 0 0 0 1\"";
    let mut want = Vec::new();
    for k in 1..=3 {
        for j in 0..=2 {
            for i in 2..=4 {
                let (a, b, c) = (0.5 * i as f64, 2.0 * j as f64, 4.0 * k as f64);
                want.extend_from_slice(&[10.0 - b, 20.0 + a, 30.0 + c]);
            }
        }
    }
    let (temp, pd, cd) = sections_for(27, 8);
    for enc in ENCODINGS {
        let piece = Piece {
            attrs: extent_attr(extent),
            sections: vec![pd.clone(), cd.clone()],
        };
        let bytes = xml_file("ImageData", attrs, &[piece], enc);
        let read = read_vtu_bytes(&bytes, "image.vti").unwrap();
        let what = format!("{enc:?}");
        assert_points(&read, &want, &what);
        assert_eq!(read.cells.hexahedra, 8, "{what}");
        check_fields(&read, &temp, &what);
    }
    // Without Direction: the identity.
    let piece = Piece {
        attrs: extent_attr([0, 1, 0, 1, 0, 1]),
        sections: vec![],
    };
    let bytes = xml_file(
        "ImageData",
        "Origin=\"1 2 3\" Spacing=\"1 1 1\"",
        &[piece],
        Enc::Ascii,
    );
    let read = read_vtu_bytes(&bytes, "cube.vti").unwrap();
    let p7 = read.mesh.points[7].as_dvec3() + read.origin;
    assert_eq!(p7.to_array(), [2.0, 3.0, 4.0]);
}

#[test]
fn pieces_of_one_vts_are_welded_on_their_shared_face() {
    let pieces: Vec<Piece> = [[0, 2, 0, 2, 0, 2], [2, 4, 0, 2, 0, 2]]
        .iter()
        .map(|&e| Piece {
            attrs: extent_attr(e),
            sections: vec![section(
                "Points",
                "",
                vec![array("P", "Float64", 3, warped_points(e))],
            )],
        })
        .collect();
    let dir = TempDir::new("vts-pieces");
    let bytes = xml_file(
        "StructuredGrid",
        "WholeExtent=\"0 4 0 2 0 2\"",
        &pieces,
        Enc::Base64,
    );
    let path = dir.write("two.vts", &bytes);
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    // 27 points per piece; the 3 x 3 points of the plane x = 2 are shared.
    assert_eq!(loaded.report.pieces.welded_points, 9);
    assert_eq!(loaded.report.pieces.pieces, 2);
    assert_eq!(loaded.mesh.points.len(), 45);
    assert_eq!(loaded.report.cells_split, 16);
    assert_eq!(loaded.report.validation.components, 1);
}

/// The legacy header, then the structured sections.
fn legacy(dataset: &str, body: &str) -> Vec<u8> {
    format!("# vtk DataFile Version 3.0\ntest\nASCII\nDATASET {dataset}\n{body}").into_bytes()
}

fn legacy_attributes(npoints: usize, ncells: usize) -> String {
    let temp: Vec<String> = (0..npoints)
        .map(|p| format!("{}", 0.5 * p as f64 - 3.0))
        .collect();
    let cell: Vec<String> = (0..ncells).map(|c| c.to_string()).collect();
    format!(
        "POINT_DATA {npoints}\nSCALARS temp double 1\nLOOKUP_TABLE default\n{}\n\
         VECTORS vel float\n{}\nCELL_DATA {ncells}\nSCALARS cell int\nLOOKUP_TABLE default\n{}\n",
        temp.join(" "),
        (0..3 * npoints)
            .map(|v| (v % 7).to_string())
            .collect::<Vec<_>>()
            .join(" "),
        cell.join(" ")
    )
}

#[test]
fn legacy_structured_datasets_round_trip() {
    let extent = [0, 3, 0, 2, 0, 4];
    let points = warped_points(extent);
    let coords: Vec<String> = points.iter().map(|v| format!("{v:?}")).collect();
    let (temp, _, _) = sections_for(60, 24);
    let attributes = legacy_attributes(60, 24);

    let grid = legacy(
        "STRUCTURED_GRID",
        &format!(
            "DIMENSIONS 4 3 5\nPOINTS 60 double\n{}\n{attributes}",
            coords.join(" ")
        ),
    );
    let read = read_legacy_bytes(&grid, "grid.vtk").unwrap();
    assert_points(&read, &points, "STRUCTURED_GRID");
    assert_eq!(read.cells.hexahedra, 24);
    assert_eq!(read.dataset, "StructuredGrid");
    check_fields(&read, &temp, "STRUCTURED_GRID");

    // BINARY: big-endian values on the line after the POINTS header.
    let mut binary = b"# vtk DataFile Version 3.0\ntest\nBINARY\nDATASET STRUCTURED_GRID\nDIMENSIONS 4 3 5\nPOINTS 60 double\n".to_vec();
    for v in &points {
        binary.extend_from_slice(&v.to_be_bytes());
    }
    binary.push(b'\n');
    let read = read_legacy_bytes(&binary, "binary.vtk").unwrap();
    assert_points(&read, &points, "BINARY STRUCTURED_GRID");

    let rect = legacy(
        "RECTILINEAR_GRID",
        &format!(
            "DIMENSIONS 4 3 5\nX_COORDINATES 4 float\n0 1 3 6\nY_COORDINATES 3 double\n-2 0.5 2\n\
             Z_COORDINATES 5 float\n-1 0 1 2 4\n{attributes}"
        ),
    );
    let read = read_legacy_bytes(&rect, "rect.vtk").unwrap();
    assert_eq!(read.mesh.points[59].to_array(), [6.0, 2.0, 4.0]);
    assert_eq!(read.mesh.points[1].to_array(), [1.0, -2.0, -1.0]);
    assert_eq!(read.cells.hexahedra, 24);
    check_fields(&read, &temp, "RECTILINEAR_GRID");

    let image = legacy(
        "STRUCTURED_POINTS",
        &format!("DIMENSIONS 4 3 5\nORIGIN 1 2 3\nSPACING 0.5 1 2\n{attributes}"),
    );
    let read = read_legacy_bytes(&image, "image.vtk").unwrap();
    assert_eq!(read.mesh.points[0].to_array(), [1.0, 2.0, 3.0]);
    // Point 59 is (3, 2, 4): 1 + 1.5, 2 + 2, 3 + 8.
    assert_eq!(read.mesh.points[59].to_array(), [2.5, 4.0, 11.0]);
    assert_eq!(read.dataset, "ImageData");
    check_fields(&read, &temp, "STRUCTURED_POINTS");
}

#[test]
fn blanked_points_and_hidden_cells_are_dropped() {
    // 4 x 4 x 4 points, 27 hexahedra. Point (1, 1, 1) (index 21) is hidden:
    // the 8 cells around it go. Cell (2, 2, 2) (index 26) is hidden too.
    let extent = [0, 3, 0, 3, 0, 3];
    let mut point_ghosts = vec![0.0; 64];
    point_ghosts[21] = 2.0;
    let mut cell_ghosts = vec![0.0; 27];
    cell_ghosts[26] = 32.0;
    let piece = Piece {
        attrs: extent_attr(extent),
        sections: vec![
            section(
                "PointData",
                "",
                vec![
                    array("vtkGhostType", "UInt8", 1, point_ghosts),
                    array("t", "Float64", 1, (0..64).map(f64::from).collect()),
                ],
            ),
            section(
                "CellData",
                "",
                vec![array("vtkGhostType", "UInt8", 1, cell_ghosts)],
            ),
            section(
                "Points",
                "",
                vec![array("Points", "Float64", 3, warped_points(extent))],
            ),
        ],
    };
    let bytes = xml_file(
        "StructuredGrid",
        "WholeExtent=\"0 3 0 3 0 3\"",
        &[piece],
        Enc::AppendedRaw,
    );
    let read = read_vtu_bytes(&bytes, "blanked.vts").unwrap();
    assert_eq!(read.cells.hexahedra, 27 - 8 - 1);
    assert_eq!(read.pieces.hidden_cells_dropped, 9);
    // Points with i, j, k all in {0, 1} lie only in the 8 cells around
    // (1, 1, 1), point 63 only in cell 26: no cell left uses them. The
    // others keep their order (field t is the old point index).
    let kept: Vec<f32> = (0..64)
        .filter(|&p| !(p % 4 < 2 && (p / 4) % 4 < 2 && p / 16 < 2) && p != 63)
        .map(|p| p as f32)
        .collect();
    assert_eq!(kept.len(), 55);
    assert_eq!(read.mesh.points.len(), 55);
    let names: Vec<&str> = read.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["t"]);
    assert_eq!(field(&read, "t"), kept.as_slice());
}

#[test]
fn flat_grids_are_one_no_volume_error() {
    let piece = Piece {
        attrs: extent_attr([0, 3, 0, 3, 0, 0]),
        sections: vec![section(
            "Points",
            "",
            vec![array("P", "Float64", 3, warped_points([0, 3, 0, 3, 0, 0]))],
        )],
    };
    let bytes = xml_file(
        "StructuredGrid",
        "WholeExtent=\"0 3 0 3 0 0\"",
        &[piece],
        Enc::Ascii,
    );
    let e = read_vtu_bytes(&bytes, "flat.vts").unwrap_err();
    assert!(matches!(e, VtkError::NoVolumeCells { .. }), "{e}");
    assert_eq!(
        e.to_string(),
        "flat.vts holds only surface cells (9 quadrilaterals): nothing to volume-render"
    );
    let e = read_legacy_bytes(
        &legacy("STRUCTURED_POINTS", "DIMENSIONS 5 1 1\n"),
        "line.vtk",
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "line.vtk holds only lower-dimensional cells (4 lines): nothing to volume-render"
    );
}

#[test]
fn left_handed_grids_load_reoriented_with_their_format_names() {
    let dir = TempDir::new("left-handed");
    let piece = Piece {
        attrs: extent_attr([0, 2, 0, 2, 0, 2]),
        sections: vec![],
    };
    // A negative z spacing makes the i, j, k axes left-handed: every
    // hexahedron, and so every tetrahedron of its split, is inverted.
    let vti = xml_file(
        "ImageData",
        "WholeExtent=\"0 2 0 2 0 2\" Spacing=\"1 1 -1\"",
        &[piece],
        Enc::Base64,
    );
    let loaded = load(&dir.write("left.vti", &vti), &LoadOptions::default()).unwrap();
    assert_eq!(loaded.report.format, "VTK XML ImageData");
    assert_eq!(loaded.report.cells_split, 8);
    assert_eq!(loaded.report.inverted_fixed, loaded.mesh.tets.len());
    assert_eq!(loaded.report.validation.components, 1);

    let rect = legacy(
        "RECTILINEAR_GRID",
        "DIMENSIONS 2 2 2\nX_COORDINATES 2 float\n0 1\nY_COORDINATES 2 float\n0 1\nZ_COORDINATES 2 float\n0 -1\n",
    );
    let loaded = load(&dir.write("rect.vtk", &rect), &LoadOptions::default()).unwrap();
    assert_eq!(loaded.report.format, "VTK legacy RECTILINEAR_GRID");
    assert_eq!(loaded.report.inverted_fixed, loaded.mesh.tets.len());
}
