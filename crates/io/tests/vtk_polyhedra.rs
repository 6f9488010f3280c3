//! Polyhedra (42) and pentagonal/hexagonal prisms (15, 16): conforming
//! splits next to each other and to linear hexahedra, in the legacy and
//! both XML face layouts; malformed cells are one clear error each.

mod vtk_common;

use std::fmt::Write;
use tetray_mesh::cells::CellError;

use tetray_io::vtk::{VtkError, VtkRead, read_legacy_bytes, read_vtu_bytes};
use vtk_common::{Lcg, face_counts, volume6};

/// Hexahedron faces, outward, in VTK corner order.
const HEX_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [3, 0, 4, 7],
];

/// A legacy file: points, cells as (type, CELLS entry after the count).
fn legacy(points: &[[f64; 3]], cells: &[(i64, Vec<i64>)]) -> String {
    let mut s = format!(
        "# vtk DataFile Version 3.0\npolyhedra\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double\n",
        points.len()
    );
    for p in points {
        writeln!(s, "{} {} {}", p[0], p[1], p[2]).unwrap();
    }
    let size: usize = cells.iter().map(|(_, e)| e.len() + 1).sum();
    writeln!(s, "CELLS {} {size}", cells.len()).unwrap();
    for (_, entry) in cells {
        let e: Vec<String> = entry.iter().map(i64::to_string).collect();
        writeln!(s, "{} {}", entry.len(), e.join(" ")).unwrap();
    }
    writeln!(s, "CELL_TYPES {}", cells.len()).unwrap();
    for (t, _) in cells {
        writeln!(s, "{t}").unwrap();
    }
    writeln!(
        s,
        "POINT_DATA {}\nSCALARS f double\nLOOKUP_TABLE default",
        points.len()
    )
    .unwrap();
    for p in points {
        writeln!(s, "{}", p[0] + 2.0 * p[1] + 3.0 * p[2]).unwrap();
    }
    s
}

/// The legacy face stream of a polyhedron.
fn stream(faces: &[Vec<i64>]) -> Vec<i64> {
    let mut s = vec![faces.len() as i64];
    for f in faces {
        s.push(f.len() as i64);
        s.extend(f);
    }
    s
}

/// A cell: VTK type, point ids, faces (polyhedra only).
type Cell = (i64, Vec<i64>, Vec<Vec<i64>>);

/// A 2x2x2 block of unit cubes, alternately linear hexahedra and cube
/// polyhedra whose faces come in a random order, each from a random start
/// vertex; point ids shuffled. Returns points and (type, ids, faces).
fn checkerboard(rng: &mut Lcg) -> (Vec<[f64; 3]>, Vec<Cell>) {
    let mut order: Vec<i64> = (0..27).collect();
    for i in (1..27).rev() {
        order.swap(i, rng.below(i as u32 + 1) as usize);
    }
    let mut points = vec![[0.0; 3]; 27];
    let id = |x: usize, y: usize, z: usize| order[x + 3 * y + 9 * z];
    for z in 0..3 {
        for y in 0..3 {
            for x in 0..3 {
                points[id(x, y, z) as usize] = [x as f64, y as f64, z as f64];
            }
        }
    }
    let mut cells = Vec::new();
    for (x, y, z) in (0..8).map(|c| (c & 1, c >> 1 & 1, c >> 2)) {
        let corner = [
            [0, 0, 0],
            [1, 0, 0],
            [1, 1, 0],
            [0, 1, 0],
            [0, 0, 1],
            [1, 0, 1],
            [1, 1, 1],
            [0, 1, 1],
        ];
        let ids: Vec<i64> = corner
            .iter()
            .map(|c| id(x + c[0], y + c[1], z + c[2]))
            .collect();
        if (x + y + z) % 2 == 0 {
            cells.push((12, ids, Vec::new()));
            continue;
        }
        let mut faces: Vec<Vec<i64>> = HEX_FACES
            .iter()
            .map(|f| {
                let start = rng.below(4) as usize;
                (0..4).map(|i| ids[f[(start + i) % 4]]).collect()
            })
            .collect();
        for i in (1..6).rev() {
            faces.swap(i, rng.below(i as u32 + 1) as usize);
        }
        cells.push((42, ids, faces));
    }
    (points, cells)
}

/// Every triangle in at most two tets, the boundary on the box's faces,
/// the tets filling the box, validation passing.
fn check_conforming(read: VtkRead, lo: [f32; 3], hi: [f32; 3], volume: f64, context: &str) {
    let mesh = read.mesh;
    let faces = face_counts(&mesh.tets);
    assert!(faces.values().all(|&n| n <= 2), "{context}");
    for (f, _) in faces.iter().filter(|&(_, &n)| n == 1) {
        let on_face = (0..3).any(|a| {
            let c = f.map(|p| mesh.points[p as usize][a]);
            c.iter().all(|&v| v == lo[a]) || c.iter().all(|&v| v == hi[a])
        });
        assert!(on_face, "{context}: boundary triangle {f:?} inside the box");
    }
    let total: f64 = mesh
        .tets
        .iter()
        .map(|&t| volume6(&mesh, t).abs() / 6.0)
        .sum();
    // 1e-6 relative: f32 coordinates of the prisms' rings, summed in f64.
    assert!(
        (total - volume).abs() <= 1e-6 * volume,
        "{context}: {total} vs {volume}"
    );
    tetray_mesh::prepare(mesh).unwrap_or_else(|e| panic!("{context}: {e}"));
}

#[test]
fn polyhedra_and_hexahedra_conform_in_every_face_order() {
    for seed in 0..20 {
        let mut rng = Lcg(seed);
        let (points, cells) = checkerboard(&mut rng);
        let entries: Vec<(i64, Vec<i64>)> = cells
            .iter()
            .map(|(t, ids, faces)| (*t, if *t == 42 { stream(faces) } else { ids.clone() }))
            .collect();
        let read = read_legacy_bytes(legacy(&points, &entries).as_bytes(), "p.vtk").unwrap();
        assert_eq!(read.cells.hexahedra, 4);
        let sub = &read.cells.subdivided;
        assert_eq!(
            (
                sub[0].type_id,
                sub[0].cells,
                sub[0].tets,
                sub[0].points_added
            ),
            (42, 4, 48, 4)
        );
        // The centroid's field is the mean of its vertices': for the linear
        // field f = x + 2y + 3z, f at the centroid (exact in f32 here).
        let f = &read.mesh.fields[0].values;
        for (p, &v) in read.mesh.points.iter().zip(f).skip(27) {
            assert_eq!(v, p.x + 2.0 * p.y + 3.0 * p.z);
        }
        check_conforming(read, [0.0; 3], [2.0; 3], 8.0, &format!("seed {seed}"));
    }
}

/// The checkerboard as a .vtu: `faces` + `faceoffsets` (VTK before 9.4) or
/// the VTK 9.4 face tables.
fn vtu(points: &[[f64; 3]], cells: &[Cell], tables: bool) -> String {
    let join = |v: &[i64]| v.iter().map(i64::to_string).collect::<Vec<_>>().join(" ");
    let array = |name: &str, v: &[i64]| {
        format!(
            "<DataArray type=\"Int64\" Name=\"{name}\" format=\"ascii\">{}</DataArray>\n",
            join(v)
        )
    };
    let coords: Vec<String> = points
        .iter()
        .map(|p| format!("{} {} {}", p[0], p[1], p[2]))
        .collect();
    let connectivity: Vec<i64> = cells.iter().flat_map(|c| c.1.clone()).collect();
    let offsets: Vec<i64> = cells
        .iter()
        .scan(0, |end, c| {
            *end += c.1.len() as i64;
            Some(*end)
        })
        .collect();
    let types: Vec<i64> = cells.iter().map(|c| c.0).collect();
    let mut face_arrays = String::new();
    if tables {
        let (mut conn, mut face_ends, mut to_faces, mut poly_ends) =
            (vec![], vec![], vec![], vec![]);
        for (_, _, faces) in cells {
            for f in faces {
                to_faces.push(face_ends.len() as i64);
                conn.extend(f);
                face_ends.push(conn.len() as i64);
            }
            poly_ends.push(to_faces.len() as i64);
        }
        face_arrays += &array("face_connectivity", &conn);
        face_arrays += &array("face_offsets", &face_ends);
        face_arrays += &array("polyhedron_to_faces", &to_faces);
        face_arrays += &array("polyhedron_offsets", &poly_ends);
    } else {
        let (mut all, mut ends) = (vec![], vec![]);
        for (t, _, faces) in cells {
            if *t == 42 {
                all.extend(stream(faces));
                ends.push(all.len() as i64);
            } else {
                ends.push(-1);
            }
        }
        face_arrays += &array("faces", &all);
        face_arrays += &array("faceoffsets", &ends);
    }
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"2.3\" byte_order=\"LittleEndian\">\n\
         <UnstructuredGrid><Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n\
         <Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">{}</DataArray></Points>\n\
         <Cells>{}{}{}{}</Cells>\n</Piece></UnstructuredGrid></VTKFile>\n",
        points.len(),
        cells.len(),
        coords.join(" "),
        array("connectivity", &connectivity),
        array("offsets", &offsets),
        array("types", &types),
        face_arrays
    )
}

#[test]
fn both_xml_face_layouts_give_the_legacy_split() {
    let mut rng = Lcg(99);
    let (points, cells) = checkerboard(&mut rng);
    let entries: Vec<(i64, Vec<i64>)> = cells
        .iter()
        .map(|(t, ids, faces)| (*t, if *t == 42 { stream(faces) } else { ids.clone() }))
        .collect();
    let legacy_read = read_legacy_bytes(legacy(&points, &entries).as_bytes(), "p.vtk").unwrap();
    for tables in [false, true] {
        let read = read_vtu_bytes(vtu(&points, &cells, tables).as_bytes(), "p.vtu").unwrap();
        assert_eq!(read.mesh.tets, legacy_read.mesh.tets, "tables {tables}");
        assert_eq!(read.mesh.points, legacy_read.mesh.points, "tables {tables}");
        check_conforming(read, [0.0; 3], [2.0; 3], 8.0, &format!("tables {tables}"));
    }
}

/// A stack of `layers` prisms with an n-gon section, each a random rotation
/// of its labelling, possibly upside down; one layer as a polyhedron.
fn prism_stack(n: usize, layers: usize, rng: &mut Lcg) -> String {
    let ring = |k: usize| -> Vec<i64> { (0..n).map(|i| (k * n + i) as i64).collect() };
    let mut points = Vec::new();
    for k in 0..=layers {
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            points.push([a.cos(), a.sin(), k as f64]);
        }
    }
    let mut cells = Vec::new();
    for k in 0..layers {
        let (mut low, mut high) = (ring(k), ring(k + 1));
        let shift = rng.below(n as u32) as usize;
        low.rotate_left(shift);
        high.rotate_left(shift);
        if rng.below(2) == 1 {
            // Upside down: the top becomes the base, both reversed.
            (low, high) = (high, low);
            low.reverse();
            high.reverse();
        }
        let ids: Vec<i64> = low.iter().chain(&high).copied().collect();
        if k == 1 {
            let mut faces = vec![low.iter().rev().copied().collect::<Vec<_>>(), high.clone()];
            for i in 0..n {
                let j = (i + 1) % n;
                faces.push(vec![low[i], low[j], high[j], high[i]]);
            }
            cells.push((42, stream(&faces)));
        } else {
            cells.push((if n == 5 { 15 } else { 16 }, ids));
        }
    }
    legacy(&points, &cells)
}

#[test]
fn prism_stacks_share_their_polygon_faces() {
    for n in [5, 6] {
        for seed in 0..10 {
            let layers = 3;
            let read = read_legacy_bytes(
                prism_stack(n, layers, &mut Lcg(seed)).as_bytes(),
                "prisms.vtk",
            )
            .unwrap();
            let context = format!("{n}-gon seed {seed}");
            // A centroid per cell and one per distinct n-gon (layers + 1).
            assert_eq!(read.cells.points_added, layers + layers + 1, "{context}");
            // Boundary: the end n-gons (n triangles each) and the side quads.
            let faces = face_counts(&read.mesh.tets);
            let boundary = faces.values().filter(|&&c| c == 1).count();
            assert_eq!(boundary, 2 * n + 2 * n * layers, "{context}");
            let area = n as f64 / 2.0 * (std::f64::consts::TAU / n as f64).sin();
            // The sides are not axis-aligned: the boundary count above, no
            // triangle in three tets, and the volume stand for the box test.
            assert!(faces.values().all(|&c| c <= 2), "{context}");
            let total: f64 = read
                .mesh
                .tets
                .iter()
                .map(|&t| volume6(&read.mesh, t).abs() / 6.0)
                .sum();
            let volume = area * layers as f64;
            assert!(
                (total - volume).abs() <= 1e-6 * volume,
                "{context}: {total} vs {volume}"
            );
            tetray_mesh::prepare(read.mesh).unwrap_or_else(|e| panic!("{context}: {e}"));
        }
    }
}

fn legacy_error(cells: &[(i64, Vec<i64>)]) -> VtkError {
    let points: Vec<[f64; 3]> = (0..8)
        .map(|c| [(c & 1) as f64, (c >> 1 & 1) as f64, (c >> 2) as f64])
        .collect();
    read_legacy_bytes(legacy(&points, cells).as_bytes(), "bad.vtk").unwrap_err()
}

/// The unit cube on points x + 2y + 4z, faces outward.
fn cube_faces() -> Vec<Vec<i64>> {
    vec![
        vec![0, 2, 3, 1],
        vec![4, 5, 7, 6],
        vec![0, 1, 5, 4],
        vec![1, 3, 7, 5],
        vec![3, 2, 6, 7],
        vec![2, 0, 4, 6],
    ]
}

#[test]
fn malformed_cells_are_one_clear_error() {
    // A quadratic tetra with 9 nodes.
    let e = legacy_error(&[(24, (0..9).map(|i| i % 8).collect())]).to_string();
    assert!(
        e.contains("cell 0")
            && e.contains("quadratic tetra")
            && e.contains("has 10 points, found 9"),
        "{e}"
    );
    // A triquadratic hexahedron with 20 nodes.
    let e = legacy_error(&[(29, (0..20).map(|i| i % 8).collect())]).to_string();
    assert!(e.contains("has 27 points, found 20"), "{e}");

    // Faces that do not close: the cube without its top.
    let mut open = cube_faces();
    open.remove(1);
    let e = legacy_error(&[(10, vec![0, 1, 2, 4]), (42, stream(&open))]).to_string();
    assert!(
        e.contains("cell 1: polyhedron: the faces do not close: edge"),
        "{e}"
    );
    // One face turned inside out.
    let mut flipped = cube_faces();
    flipped[3].reverse();
    let e = legacy_error(&[(42, stream(&flipped))]).to_string();
    assert!(
        e.contains("cell 0: polyhedron: the face orientations disagree"),
        "{e}"
    );
    // A point index out of range in a face.
    let mut far = cube_faces();
    far[0][2] = 99;
    let e = legacy_error(&[(42, stream(&far))]);
    assert!(
        matches!(
            e,
            VtkError::Cell(CellError::BadIndex {
                cell: 0,
                index: 99,
                ..
            })
        ),
        "{e}"
    );
    // A face stream that claims more than it has.
    let mut s = stream(&cube_faces());
    s[0] = 7;
    let e = legacy_error(&[(42, s)]).to_string();
    assert!(e.contains("cell 0: polyhedron: face 6 of 7"), "{e}");

    // VTK 9.4 tables: a polyhedron naming a face that does not exist.
    let (points, cells) = checkerboard(&mut Lcg(3));
    let text = vtu(&points, &cells, true);
    let bad = text.replacen(
        "Name=\"polyhedron_to_faces\" format=\"ascii\">0 ",
        "Name=\"polyhedron_to_faces\" format=\"ascii\">40 ",
        1,
    );
    assert_ne!(bad, text);
    let e = read_vtu_bytes(bad.as_bytes(), "bad.vtu")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("polyhedron: face index 40 is out of range (there are 24 faces)"),
        "{e}"
    );
    // A polyhedron without any face arrays.
    let start = text
        .find("<DataArray type=\"Int64\" Name=\"face_connectivity\"")
        .unwrap();
    let bare = format!(
        "{}</Cells>{}",
        &text[..start],
        &text[text.find("</Cells>").unwrap() + 8..]
    );
    let e = read_vtu_bytes(bare.as_bytes(), "bare.vtu")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("polyhedra (type 42) but <Cells> has neither"),
        "{e}"
    );
}

#[test]
fn added_points_beyond_f32_are_an_error() {
    // A 20-node hexahedron whose corners and mid-edge nodes lie near +-f32
    // range: the serendipity face centre (-1/4 per corner, 1/2 per mid-edge
    // node) lands at -9e38, beyond f32.
    let points: Vec<[f64; 3]> = (0..20)
        .map(|i| [if i < 8 { 3e38 } else { -3e38 }, i as f64, 0.0])
        .collect();
    let e = read_legacy_bytes(
        legacy(&points, &[(25, (0..20).collect())]).as_bytes(),
        "far.vtk",
    )
    .unwrap_err();
    assert!(
        matches!(&e, VtkError::Cell(CellError::NonFinite { section, .. }) if section.contains("points added by the splits")),
        "{e}"
    );
}
