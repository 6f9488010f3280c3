//! Legacy files with mixed cells: splitting into tetrahedra (counts,
//! volume, conformity), attribute sections, VTK 5.1 cells, BINARY files
//! built byte by byte.

mod vtk_common;

use tetray_io::vtk::{CellCounts, read_legacy_bytes};
use vtk_common::{Lcg, conforming_boundary, face_counts, volume6};

/// A unit hexahedron with a wedge on its x = 1 face, a pyramid on top, a
/// voxel on its y = 1 face; two tetrahedra apart; a triangle and a line.
const MIXED: &str = "# vtk DataFile Version 3.0
mixed cells
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 20 float
0 0 0  1 0 0  1 1 0  0 1 0
0 0 1  1 0 1  1 1 1  0 1 1
2 0.5 0  2 0.5 1
0.5 0.5 2
0 2 0  1 2 0  0 2 1  1 2 1
-2 0 0  -1 0 0  -2 1 0  -2 0 1  -2 0 -1
CELLS 8 48
8 0 1 2 3 4 5 6 7
6 1 8 2 5 9 6
5 4 5 6 7 10
8 3 2 11 12 7 6 13 14
4 15 16 17 18
4 15 17 16 19
3 0 1 2
2 0 1
CELL_TYPES 8
12 13 14 11 10 10 5 3
CELL_DATA 8
SCALARS pressure double
LOOKUP_TABLE default
1 2 3 4 5 6 100 200
POINT_DATA 20
VECTORS velocity float
0 0 0  3 4 0  6 8 0  9 12 0  12 16 0  15 20 0  18 24 0  21 28 0  24 32 0  27 36 0
30 40 0  33 44 0  36 48 0  39 52 0  42 56 0  45 60 0  48 64 0  51 68 0  54 72 0  57 76 0
METADATA
INFORMATION 0

FIELD FieldData 2
temperature 1 20 float
0 0.5 1 1.5 2 2.5 3 3.5 4 4.5 5 5.5 6 6.5 7 7.5 8 8.5 9 9.5
uv 2 20 double
0 0 3 4 6 8 9 12 12 16 15 20 18 24 21 28 24 32 27 36
30 40 33 44 36 48 39 52 42 56 45 60 48 64 51 68 54 72 57 76
";

#[test]
fn mixed_cells_split_into_the_expected_conforming_tetrahedra() {
    let read = read_legacy_bytes(MIXED.as_bytes(), "mixed.vtk").unwrap();
    let expected = CellCounts {
        tetra: 2,
        hexahedra: 1,
        wedges: 1,
        pyramids: 1,
        voxels: 1,
        skipped_lower_dim: 2,
        // The hexahedron and voxel meet the 6-tet case, wedge 3, pyramid 2.
        tets_from_split: 6 + 3 + 2 + 6,
        ..CellCounts::default()
    };
    assert_eq!(read.cells, expected);
    let mesh = &read.mesh;
    assert_eq!(mesh.tets.len(), 19);

    // Cells in VTK order give positive tets; their volumes add up to the
    // cells' (hex 1, wedge 1/2, pyramid 1/3, voxel 1, tets 1/6 each).
    // Tolerance 1e-5 relative: f32 coordinates, exact here, summed in f64.
    let volumes: Vec<f64> = mesh.tets.iter().map(|&t| volume6(mesh, t) / 6.0).collect();
    assert!(volumes.iter().all(|&v| v > 0.0), "{volumes:?}");
    let total: f64 = volumes.iter().map(|v| v.abs()).sum();
    let analytic = 1.0 + 0.5 + 1.0 / 3.0 + 1.0 + 2.0 / 6.0;
    assert!(
        (total - analytic).abs() <= 1e-5 * analytic,
        "{total} vs {analytic}"
    );

    // Conforming: the hex/wedge, hex/pyramid and hex/voxel quads are cut
    // alike on both sides, so the boundary is the union's outer faces:
    // hex 3 quads, wedge 2 triangles + 2 quads, pyramid 4, voxel 5 quads,
    // the tet pair 6 triangles.
    assert_eq!(conforming_boundary(&mesh.tets), 6 + 6 + 4 + 10 + 6);

    let warnings = read.warnings.join("\n");
    assert!(
        warnings.contains("skipped 2 lower-dimensional cells"),
        "{warnings}"
    );
    assert!(
        warnings.contains("triangle") && warnings.contains("line"),
        "{warnings}"
    );
    assert!(warnings.contains("\"pressure\""), "{warnings}");
}

#[test]
fn attributes_load_as_point_fields() {
    let read = read_legacy_bytes(MIXED.as_bytes(), "mixed.vtk").unwrap();
    let names: Vec<&str> = read.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "velocity_magnitude",
            "temperature",
            "uv_magnitude",
            "pressure"
        ]
    );
    let field = |name: &str| {
        &read
            .mesh
            .fields
            .iter()
            .find(|f| f.name == name)
            .unwrap()
            .values
    };
    // |(3i, 4i, 0)| = 5i exactly.
    for (i, (&v, &uv)) in field("velocity_magnitude")
        .iter()
        .zip(field("uv_magnitude"))
        .enumerate()
    {
        assert_eq!(v, 5.0 * i as f32);
        assert_eq!(uv, 5.0 * i as f32);
    }
    assert_eq!(field("temperature")[3], 1.5);
    // Cell values averaged over the volume cells using each point; the
    // triangle (100) and line (200) do not count.
    let p = field("pressure");
    assert_eq!(p[0], 1.0); // hexahedron only
    assert_eq!(p[6], 2.5); // hexahedron, wedge, pyramid, voxel
    assert_eq!(p[10], 3.0); // pyramid apex
    assert_eq!(p[15], 5.5); // both tetrahedra
}

/// Two unit hexahedra side by side sharing the face x = 1, their points
/// labelled by a shuffled numbering.
fn two_hexes(labels: &[u32; 12]) -> String {
    let id = |x: u32, y: u32, z: u32| labels[(x + 3 * (y + 2 * z)) as usize];
    let mut coords = vec![String::new(); 12];
    for z in 0..2 {
        for y in 0..2 {
            for x in 0..3 {
                coords[id(x, y, z) as usize] = format!("{x} {y} {z}");
            }
        }
    }
    let hex = |x: u32| {
        let c = [
            (0, 0, 0),
            (1, 0, 0),
            (1, 1, 0),
            (0, 1, 0),
            (0, 0, 1),
            (1, 0, 1),
            (1, 1, 1),
            (0, 1, 1),
        ];
        let ids: Vec<String> = c
            .iter()
            .map(|&(dx, dy, dz)| id(x + dx, dy, dz).to_string())
            .collect();
        format!("8 {}", ids.join(" "))
    };
    format!(
        "# vtk DataFile Version 2.0\ntwo hexes\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 12 double\n{}\n\
         CELLS 2 18\n{}\n{}\nCELL_TYPES 2\n12\n12\n",
        coords.join("\n"),
        hex(0),
        hex(1)
    )
}

#[test]
fn two_hexahedra_cut_their_shared_face_alike_under_any_numbering() {
    let mut rng = Lcg(11);
    let mut seen = std::collections::BTreeSet::new();
    for trial in 0..300 {
        let mut labels: [u32; 12] = std::array::from_fn(|i| i as u32);
        if trial > 0 {
            for i in (1..12).rev() {
                labels.swap(i, rng.below(i as u32 + 1) as usize);
            }
        }
        let read = read_legacy_bytes(two_hexes(&labels).as_bytes(), "two.vtk").unwrap();
        let mesh = &read.mesh;
        seen.insert(mesh.tets.len());
        assert_eq!(read.cells.tets_from_split, mesh.tets.len());
        let total: f64 = mesh.tets.iter().map(|&t| volume6(mesh, t)).sum::<f64>() / 6.0;
        assert!(
            mesh.tets.iter().all(|&t| volume6(mesh, t) > 0.0),
            "{labels:?}"
        );
        assert!((total - 2.0).abs() <= 1e-12, "{labels:?}: volume {total}");
        // Both triangles of the shared face are held by a tet on each side.
        let faces = face_counts(&mesh.tets);
        let on_shared_face = |f: &[u32; 3]| f.iter().all(|&i| mesh.points[i as usize].x == 1.0);
        let shared: Vec<usize> = faces
            .iter()
            .filter(|(f, _)| on_shared_face(f))
            .map(|(_, &c)| c)
            .collect();
        assert_eq!(shared, [2, 2], "{labels:?}");
        assert_eq!(conforming_boundary(&mesh.tets), 20, "{labels:?}");
    }
    // Numberings reach the 5- and 6-tet cases for each hexahedron.
    assert!(
        seen.contains(&10) && seen.contains(&11) && seen.contains(&12),
        "{seen:?}"
    );
}

#[test]
fn vtk_5_1_offsets_and_connectivity_are_read() {
    let text = "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                POINTS 5 float\n0 0 0 1 0 0 0 1 0 0 0 1 0 0 -1\n\
                CELLS 3 8\nOFFSETS vtktypeint64\n0 4 8\nCONNECTIVITY vtktypeint64\n0 1 2 3 0 2 1 4\n\
                CELL_TYPES 2\n10\n10\n";
    let read = read_legacy_bytes(text.as_bytes(), "v51.vtk").unwrap();
    assert_eq!(read.mesh.tets, vec![[0, 1, 2, 3], [0, 2, 1, 4]]);
}

/// Big-endian bytes of a legacy BINARY file, section by section.
#[derive(Default)]
struct Binary(Vec<u8>);

impl Binary {
    fn text(mut self, s: &str) -> Self {
        self.0.extend_from_slice(s.as_bytes());
        self
    }
    fn f64s(mut self, v: &[f64]) -> Self {
        v.iter()
            .for_each(|x| self.0.extend_from_slice(&x.to_be_bytes()));
        self.0.push(b'\n');
        self
    }
    fn i32s(mut self, v: &[i32]) -> Self {
        v.iter()
            .for_each(|x| self.0.extend_from_slice(&x.to_be_bytes()));
        self.0.push(b'\n');
        self
    }
    fn i64s(mut self, v: &[i64]) -> Self {
        v.iter()
            .for_each(|x| self.0.extend_from_slice(&x.to_be_bytes()));
        self.0.push(b'\n');
        self
    }
    fn i16s(mut self, v: &[i16]) -> Self {
        v.iter()
            .for_each(|x| self.0.extend_from_slice(&x.to_be_bytes()));
        self.0.push(b'\n');
        self
    }
}

/// Coordinates whose big-endian bytes include 0x0a and 0x20 (newline and
/// space), which a text-minded reader would stumble on.
const BIN_POINTS: [f64; 15] = [
    0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 3.2e-308, 8.0, 10.0,
];

#[test]
fn binary_legacy_count_prefixed_cells_with_metadata() {
    let bytes = Binary::default()
        .text("# vtk DataFile Version 4.2\nbinary\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n")
        .f64s(&BIN_POINTS)
        .text("METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1\n\n")
        .text("CELLS 3 12\n")
        .i32s(&[4, 0, 1, 2, 3, 4, 1, 2, 3, 4, 1, 4])
        .text("CELL_TYPES 3\n")
        .i32s(&[10, 10, 1])
        .text("POINT_DATA 5\nSCALARS level int 1\nLOOKUP_TABLE default\n")
        .i32s(&[10, -1, 32, 2560, 7])
        .text("CELL_DATA 3\nFIELD FieldData 1\nflag 1 3 short\n")
        .i16s(&[2, 4, 1000])
        .0;
    let read = read_legacy_bytes(&bytes, "bin.vtk").unwrap();
    assert_eq!(read.mesh.tets, vec![[0, 1, 2, 3], [1, 2, 3, 4]]);
    let xyz: Vec<f64> = read
        .mesh
        .points
        .iter()
        .flat_map(|p| p.to_array())
        .map(f64::from)
        .collect();
    let want: Vec<f64> = BIN_POINTS.iter().map(|&x| x as f32 as f64).collect();
    assert_eq!(xyz, want);
    assert_eq!(read.mesh.fields[0].values, [10.0, -1.0, 32.0, 2560.0, 7.0]);
    // Points 1..3 are in both tets (2 and 4), point 0 in the first only.
    assert_eq!(read.mesh.fields[1].name, "flag");
    assert_eq!(read.mesh.fields[1].values, [2.0, 3.0, 3.0, 3.0, 4.0]);
    assert_eq!(read.cells.skipped_lower_dim, 1);
}

#[test]
fn binary_legacy_5_1_cells() {
    let bytes = Binary::default()
        .text("# vtk DataFile Version 5.1\nbinary\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n")
        .f64s(&BIN_POINTS)
        .text("CELLS 3 8\nOFFSETS vtktypeint64\n")
        .i64s(&[0, 4, 8])
        .text("CONNECTIVITY vtktypeint64\n")
        .i64s(&[0, 1, 2, 3, 1, 2, 3, 4])
        .text("CELL_TYPES 2\n")
        .i32s(&[10, 10])
        .0;
    let read = read_legacy_bytes(&bytes, "bin51.vtk").unwrap();
    assert_eq!(read.mesh.tets, vec![[0, 1, 2, 3], [1, 2, 3, 4]]);
}

#[test]
fn multi_component_scalars_and_name_clashes() {
    let text = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                POINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n\
                POINT_DATA 4\nSCALARS uv%20pair float 2\nLOOKUP_TABLE default\n3 4 0 1 6 8 0 0\n\
                SCALARS p float\nLOOKUP_TABLE default\n1 2 3 4\n\
                CELL_DATA 1\nSCALARS p float 1\nLOOKUP_TABLE default\n7\n";
    let read = read_legacy_bytes(text.as_bytes(), "clash.vtk").unwrap();
    let names: Vec<&str> = read.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["uv pair_magnitude", "p", "p_cell"]);
    assert_eq!(read.mesh.fields[0].values, [5.0, 1.0, 10.0, 0.0]);
    assert_eq!(read.mesh.fields[2].values, [7.0; 4]);
    assert!(
        read.warnings.iter().any(|w| w.contains("renamed")),
        "{:?}",
        read.warnings
    );
}
