//! Quadratic Exodus II blocks (TETRA10, HEX20), written with the test
//! support's netCDF classic writer, go through the same subdivision as
//! VTK's quadratic cells: the mid-edge nodes become vertices of the
//! tetrahedra (so their field values shape the field), the tetrahedra
//! conform across the elements' shared faces and fill the elements.

mod exodus_common;

use std::collections::HashMap;
use std::path::PathBuf;

use exodus_common::{Block, Model, Version};
use tetray_io::vtk::Linearize;
use tetray_io::{LoadOptions, LoadedMesh, load};

/// Exodus node order of the mid-edge nodes (SEACAS Exodus II manual,
/// 0-based corners): TETRA10 nodes 5-10, HEX20 nodes 9-20.
const TETRA10_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]];
const HEX20_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
];

/// The field: quadratic, so a value at a mid-edge node differs from the
/// mean of the edge's corners.
fn f(p: [f64; 3]) -> f64 {
    p[0] * p[0] + 2.0 * p[1] * p[1] + 3.0 * p[2] * p[2]
}

/// A model of quadratic elements on `corners` (1-based ids in `cells`),
/// a mid-edge node added per distinct edge (shared by the elements of the
/// edge), the nodal variable "q" = `f`. Returns it and the mid-edge points.
fn quadratic_model(
    corners: &[[f64; 3]],
    cells: &[&[usize]],
    edges: &[[usize; 2]],
    elem_type: &str,
) -> (Model, Vec<[f64; 3]>) {
    let mut coords = corners.to_vec();
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    let mut connectivity = Vec::new();
    for cell in cells {
        connectivity.extend(cell.iter().map(|&c| c as i64));
        for &[a, b] in edges {
            let (a, b) = (cell[a], cell[b]);
            let key = (a.min(b), a.max(b));
            let id = *mid.entry(key).or_insert_with(|| {
                let (p, q) = (corners[a - 1], corners[b - 1]);
                coords.push([0, 1, 2].map(|k| 0.5 * (p[k] + q[k])));
                coords.len()
            });
            connectivity.push(id as i64);
        }
    }
    let nodes = cells[0].len() + edges.len();
    let values = coords.iter().map(|&p| f(p)).collect();
    let model = Model {
        coords: coords.clone(),
        blocks: vec![Block::new(1, "quadratic", elem_type, nodes, &connectivity)],
        times: vec![0.0],
        nodal: vec![("q".into(), vec![values])],
        elem: Vec::new(),
        old_layout: false,
        int64: false,
    };
    (model, coords[corners.len()..].to_vec())
}

fn load_model(model: &Model, file: &str, linearize: Linearize) -> LoadedMesh {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("exodus_quadratic");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(file);
    std::fs::write(&path, model.write(Version::Cdf1)).unwrap();
    let opts = LoadOptions {
        linearize,
        ..LoadOptions::default()
    };
    load(&path, &opts).unwrap()
}

/// Checks the tets conform (no triangle in more than two tets), their
/// boundary has area `area` and they fill `volume`; that every mid-edge
/// point is a tet vertex carrying its own value of `f` (not the mean of
/// the edge's corners).
fn check(loaded: &LoadedMesh, mid_edge: &[[f64; 3]], volume: f64, area: f64) {
    let mesh = &loaded.mesh;
    let origin = loaded.report.origin;
    let at = |i: u32| (mesh.points[i as usize].as_dvec3() + origin).to_array();
    let mut faces: HashMap<[u32; 3], usize> = HashMap::new();
    let mut filled = 0.0;
    for t in &mesh.tets {
        let p = t.map(|i| glam::DVec3::from(at(i)));
        filled += (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])).abs() / 6.0;
        for skip in 0..4 {
            let mut face: Vec<u32> = (0..4).filter(|&k| k != skip).map(|k| t[k]).collect();
            face.sort_unstable();
            *faces.entry([face[0], face[1], face[2]]).or_insert(0) += 1;
        }
    }
    assert!(faces.values().all(|&n| n <= 2), "a triangle in 3+ tets");
    let boundary: f64 = faces
        .iter()
        .filter(|&(_, &n)| n == 1)
        .map(|(f, _)| {
            let p = f.map(|i| glam::DVec3::from(at(i)));
            (p[1] - p[0]).cross(p[2] - p[0]).length() / 2.0
        })
        .sum();
    assert!(
        (filled - volume).abs() < 1e-5,
        "volume {filled} != {volume}"
    );
    assert!(
        (boundary - area).abs() < 1e-5,
        "boundary {boundary} != {area}"
    );
    let q = &mesh.fields.iter().find(|f| f.name == "q").unwrap().values;
    for &m in mid_edge {
        let i = (0..mesh.points.len() as u32)
            .find(|&i| at(i).iter().zip(m).all(|(a, b)| (a - b).abs() < 1e-6))
            .unwrap_or_else(|| panic!("no point at {m:?}"));
        assert!(
            mesh.tets.iter().any(|t| t.contains(&i)),
            "mid-edge node {m:?} is no tet's vertex"
        );
        assert!((f64::from(q[i as usize]) - f(m)).abs() < 1e-5, "q at {m:?}");
    }
}

#[test]
fn tetra10_and_hex20_blocks_are_subdivided_through_their_mid_edge_nodes() {
    // Two TETRA10 sharing the face 2-3-4.
    let corners = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
    ];
    let (model, mid) = quadratic_model(
        &corners,
        &[&[1, 2, 3, 4], &[2, 4, 3, 5]],
        &TETRA10_EDGES,
        "TETRA10",
    );
    assert_eq!(mid.len(), 9);
    let loaded = load_model(&model, "tetra10.exo", Linearize::Subdivide);
    // 8 tets per TETRA10, no point added.
    assert_eq!(loaded.mesh.tets.len(), 16);
    let s = &loaded.report.subdivided;
    assert_eq!(
        (s.len(), s[0].type_id, s[0].cells, s[0].tets),
        (1, 24, 2, 16)
    );
    assert_eq!(loaded.report.points_added, 0);
    // Volumes 1/6 and 1/3; the boundary is the six outer faces.
    let area = |a: usize, b: usize, c: usize| {
        let p = [a, b, c].map(|i| glam::DVec3::from(corners[i]));
        (p[1] - p[0]).cross(p[2] - p[0]).length() / 2.0
    };
    let outer = area(0, 1, 2)
        + area(0, 1, 3)
        + area(0, 2, 3)
        + area(1, 2, 4)
        + area(1, 3, 4)
        + area(2, 3, 4);
    check(&loaded, &mid, 1.0 / 6.0 + 1.0 / 3.0, outer);
    // Corners only: one tet per element, the mid-edge nodes unused.
    let corners_only = load_model(&model, "tetra10_corners.exo", Linearize::Corners);
    assert_eq!(corners_only.mesh.tets.len(), 2);

    // Two HEX20 side by side, the unit cubes at x 0..1 and 1..2, on a
    // 3 x 2 x 2 grid of corners.
    let mut corners = Vec::new();
    for z in 0..2 {
        for y in 0..2 {
            for x in 0..3 {
                corners.push([x, y, z].map(f64::from));
            }
        }
    }
    let hex = |x: usize| {
        let id = |dx: usize, y: usize, z: usize| 1 + x + dx + 3 * y + 6 * z;
        [
            id(0, 0, 0),
            id(1, 0, 0),
            id(1, 1, 0),
            id(0, 1, 0),
            id(0, 0, 1),
            id(1, 0, 1),
            id(1, 1, 1),
            id(0, 1, 1),
        ]
    };
    let (left, right) = (hex(0), hex(1));
    let (model, mid) = quadratic_model(&corners, &[&left, &right], &HEX20_EDGES, "HEX20");
    assert_eq!(mid.len(), 12 + 12 - 4);
    let loaded = load_model(&model, "hex20.exo", Linearize::Subdivide);
    let s = &loaded.report.subdivided;
    assert_eq!((s.len(), s[0].type_id, s[0].cells), (1, 25, 2));
    assert!(loaded.report.points_added > 0);
    check(&loaded, &mid, 2.0, 10.0);
    let corners_only = load_model(&model, "hex20_corners.exo", Linearize::Corners);
    assert_eq!(corners_only.report.points_added, 0);
    check_corners_only(&corners_only, 2.0);
}

/// Corners mode: the mid-edge nodes are no tet's vertices, the hexahedra
/// still fill their volume.
fn check_corners_only(loaded: &LoadedMesh, volume: f64) {
    let mesh = &loaded.mesh;
    let used: std::collections::HashSet<u32> = mesh.tets.iter().flatten().copied().collect();
    assert_eq!(used.len(), 12, "corners only");
    let filled: f64 = mesh
        .tets
        .iter()
        .map(|t| {
            let p = t.map(|i| mesh.points[i as usize].as_dvec3());
            (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])).abs() / 6.0
        })
        .sum();
    assert!((filled - volume).abs() < 1e-5);
}
