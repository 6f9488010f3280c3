//! Polyhedra through the ghost-cell and piece-joining steps: their faces
//! (listed apart from the connectivity) must follow the cells and points
//! that dropping ghost cells renumbers, and the pieces that welding shifts.

mod structured_common;
mod vtk_common;

use std::fmt::Write;
use std::path::PathBuf;

use structured_common::{Enc, array, unstructured_piece, xml_file};
use tetray_io::vtk::{VtkRead, read_legacy_bytes, read_parallel_file};
use vtk_common::{face_counts, volume6};

/// The 16 points of three unit cubes in a row along x; point `(i, j, k)`
/// at `i + 4 (j + 2 k)`.
fn row_points() -> Vec<[f64; 3]> {
    let mut points = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..4 {
                points.push([i, j, k].map(f64::from));
            }
        }
    }
    points
}

/// Cube `i` (x from i to i + 1): its 8 points (VTK hexahedron order) and
/// its 6 faces, outward.
fn cube(i: i64) -> (Vec<i64>, Vec<Vec<i64>>) {
    let id = |x: i64, y: i64, z: i64| x + 4 * (y + 2 * z);
    let c = [
        id(i, 0, 0),
        id(i + 1, 0, 0),
        id(i + 1, 1, 0),
        id(i, 1, 0),
        id(i, 0, 1),
        id(i + 1, 0, 1),
        id(i + 1, 1, 1),
        id(i, 1, 1),
    ];
    let faces = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    (
        c.to_vec(),
        faces.iter().map(|f| f.map(|k| c[k]).to_vec()).collect(),
    )
}

fn f(p: [f64; 3]) -> f64 {
    p[0] + 2.0 * p[1] + 3.0 * p[2]
}

/// The two polyhedra of cubes 1 and 2: 12 tetrahedra each, conforming,
/// filling volume 2, the linear field exact at the added centroids.
fn check(read: &VtkRead, points: usize, what: &str) {
    let mesh = &read.mesh;
    assert_eq!(mesh.points.len(), points, "{what}");
    assert_eq!(mesh.tets.len(), 24, "{what}");
    assert!(face_counts(&mesh.tets).values().all(|&n| n <= 2), "{what}");
    let interior = face_counts(&mesh.tets)
        .values()
        .filter(|&&n| n == 2)
        .count();
    // Per cube a triangle from the centroid through each of the 18 edges
    // of its 12 surface triangles; and the shared face's 2, once.
    assert_eq!(interior, 2 * 18 + 2, "{what}");
    let volume: f64 = mesh.tets.iter().map(|&t| volume6(mesh, t).abs()).sum();
    assert!((volume / 6.0 - 2.0).abs() < 1e-9, "{what}: volume {volume}");
    let values = &mesh.fields.iter().find(|g| g.name == "f").unwrap().values;
    for (p, &v) in mesh.points.iter().zip(values) {
        let p = (p.as_dvec3() + read.origin).to_array();
        assert!((f64::from(v) - f(p)).abs() < 1e-5, "{what}: f at {p:?}");
    }
    assert!(mesh.points.iter().all(|p| p.x >= 1.0 - 1e-6), "{what}");
}

#[test]
fn a_ghost_cell_before_legacy_polyhedra_renumbers_their_faces() {
    // Cube 0 a hexahedron flagged ghost, cubes 1 and 2 polyhedra.
    let points = row_points();
    let mut s = format!(
        "# vtk DataFile Version 3.0\nghost\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double\n",
        points.len()
    );
    for p in &points {
        writeln!(s, "{} {} {}", p[0], p[1], p[2]).unwrap();
    }
    let mut entries = vec![cube(0).0];
    for i in [1, 2] {
        let faces = cube(i).1;
        let mut stream = vec![faces.len() as i64];
        for face in faces {
            stream.push(face.len() as i64);
            stream.extend(face);
        }
        entries.push(stream);
    }
    let size: usize = entries.iter().map(|e| e.len() + 1).sum();
    writeln!(s, "CELLS 3 {size}").unwrap();
    for e in &entries {
        let e: Vec<String> = e.iter().map(i64::to_string).collect();
        writeln!(s, "{} {}", e.len(), e.join(" ")).unwrap();
    }
    writeln!(s, "CELL_TYPES 3\n12\n42\n42").unwrap();
    writeln!(
        s,
        "CELL_DATA 3\nSCALARS vtkGhostType unsigned_char\nLOOKUP_TABLE default\n1 0 0"
    )
    .unwrap();
    writeln!(s, "POINT_DATA 16\nSCALARS f double\nLOOKUP_TABLE default").unwrap();
    for &p in &points {
        writeln!(s, "{}", f(p)).unwrap();
    }
    let read = read_legacy_bytes(s.as_bytes(), "ghost.vtk").unwrap();
    assert_eq!(read.pieces.ghost_cells_dropped, 1);
    // The x = 0 plane goes with the ghost; a centroid per polyhedron.
    check(&read, 12 + 2, "legacy");
    // Both polyhedra keep their file numbers (1, 2).
    let mut numbers = read.tet_cells.clone();
    numbers.dedup();
    assert_eq!(numbers, [1, 2]);
}

#[test]
fn polyhedra_of_two_pieces_are_welded_with_their_faces() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("polyhedra_pieces");
    std::fs::create_dir_all(&dir).unwrap();
    let all = row_points();
    for i in [1, 2] {
        // Each piece holds only its cube's points, renumbered from 0.
        let (ids, faces) = cube(i);
        let local = |g: i64| ids.iter().position(|&p| p == g).unwrap() as i64;
        let points: Vec<f64> = ids.iter().flat_map(|&g| all[g as usize]).collect();
        let values = ids.iter().map(|&g| f(all[g as usize])).collect();
        let mut piece = unstructured_piece(
            &points,
            &[(0..8).collect()],
            &[42],
            vec![array("f", "Float64", 1, values)],
            vec![],
            "",
        );
        let mut stream = vec![faces.len() as f64];
        for face in &faces {
            stream.push(face.len() as f64);
            stream.extend(face.iter().map(|&g| local(g) as f64));
        }
        let cells = piece
            .sections
            .iter_mut()
            .find(|s| s.tag == "Cells")
            .unwrap();
        let end = stream.len() as f64;
        cells.arrays.push(array("faces", "Int64", 1, stream));
        cells
            .arrays
            .push(array("faceoffsets", "Int64", 1, vec![end]));
        let bytes = xml_file("UnstructuredGrid", "", &[piece], Enc::Ascii);
        std::fs::write(dir.join(format!("p{i}.vtu")), bytes).unwrap();
    }
    let pvtu = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">\n\
                <PUnstructuredGrid GhostLevel=\"0\">\n\
                <Piece Source=\"p1.vtu\"/>\n<Piece Source=\"p2.vtu\"/>\n\
                </PUnstructuredGrid>\n</VTKFile>\n";
    let path = dir.join("two.pvtu");
    std::fs::write(&path, pvtu).unwrap();
    let read = read_parallel_file(&path).unwrap();
    assert_eq!(read.pieces.welded_points, 4);
    check(&read, 12 + 2, "pvtu");
    let mut numbers = read.tet_cells.clone();
    numbers.dedup();
    assert_eq!(numbers, [0, 1]);
}
