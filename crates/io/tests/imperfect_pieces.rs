//! The readers joined since the imperfect-mesh work (parallel pieces,
//! Exodus blocks) go through the same f64 centring and the same exclusion
//! of cells that cannot be walked as a single `.vtk`: a mesh far from zero
//! is stored relative to an origin, and a tangled cell is left out and
//! reported by its number in the file(s): a piece's cells counted on from
//! all the cells (ghost cells included) of the pieces before it, Exodus
//! elements across all blocks (skipped ones included).

mod exodus_common;
mod structured_common;

use std::path::PathBuf;

use exodus_common::{Block, Model, Version};
use glam::DVec3;
use structured_common::{Enc, array, unstructured_piece, xml_file};
use tetray_io::{LoadOptions, LoadedMesh, load};

/// Far from zero: stored relative to an origin near the mesh.
const OFFSET: DVec3 = DVec3::new(7.0e6, -3.0e6, 1.0e6);

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("imperfect_pieces")
        .join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The points `x0..=x1` (x), 0..=1 (y, z) of a row of unit cubes, moved by
/// [`OFFSET`]; point `(i, j, k)` at `(i - x0) + n (j + 2 k)`.
fn row_points(x0: usize, x1: usize) -> Vec<[f64; 3]> {
    let mut points = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in x0..=x1 {
                let p = DVec3::new(i as f64, j as f64, k as f64) + OFFSET;
                points.push(p.to_array());
            }
        }
    }
    points
}

/// The hexahedra (VTK = Exodus HEX8 order, 0-based) of such a row; the
/// ones in `twisted` list their top face as a bow-tie, so their split has
/// tetrahedra of both orientations.
fn row_hexes(n: usize, twisted: &[usize]) -> Vec<Vec<i64>> {
    let id = |i: usize, j: usize, k: usize| (i + n * (j + 2 * k)) as i64;
    (0..n - 1)
        .map(|i| {
            let mut hex = vec![
                id(i, 0, 0),
                id(i + 1, 0, 0),
                id(i + 1, 1, 0),
                id(i, 1, 0),
                id(i, 0, 1),
                id(i + 1, 0, 1),
                id(i + 1, 1, 1),
                id(i, 1, 1),
            ];
            if twisted.contains(&i) {
                hex.swap(6, 7);
            }
            hex
        })
        .collect()
}

/// The stored points are near zero, `origin + point` the file's.
fn check_centred(loaded: &LoadedMesh) {
    let origin = loaded.report.origin;
    assert!((origin - OFFSET).length() < 10.0, "origin {origin}");
    assert!(loaded.mesh.points.iter().all(|p| p.length() < 10.0));
    let min = loaded
        .mesh
        .points
        .iter()
        .map(|p| p.as_dvec3() + origin)
        .fold(DVec3::splat(f64::MAX), DVec3::min);
    assert_eq!(min, OFFSET);
}

#[test]
fn a_tangled_cell_of_a_second_piece_is_numbered_after_the_first_pieces_cells() {
    let dir = scratch("pvtu");
    // Cubes A (x 0..1), B (1..2), C (2..3). Piece 0: A and B as a ghost;
    // piece 1: B and C, C twisted. The cells are 0, 1 (ghost), 2, 3.
    let piece = |x0: usize, x1: usize, twisted: &[usize], ghosts: Vec<f64>| {
        let points: Vec<f64> = row_points(x0, x1).concat();
        let cells = row_hexes(x1 - x0 + 1, twisted);
        let f = (0..points.len() / 3).map(|p| p as f64).collect();
        let p = unstructured_piece(
            &points,
            &cells,
            &vec![12; cells.len()],
            vec![array("f", "Float64", 1, f)],
            vec![array("vtkGhostType", "UInt8", 1, ghosts)],
            "",
        );
        xml_file("UnstructuredGrid", "", &[p], Enc::Base64)
    };
    std::fs::write(dir.join("p0.vtu"), piece(0, 2, &[], vec![0.0, 1.0])).unwrap();
    std::fs::write(dir.join("p1.vtu"), piece(1, 3, &[1], vec![0.0, 0.0])).unwrap();
    let pvtu = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">\n\
                <PUnstructuredGrid GhostLevel=\"1\">\n\
                <Piece Source=\"p0.vtu\"/>\n<Piece Source=\"p1.vtu\"/>\n\
                </PUnstructuredGrid>\n</VTKFile>\n";
    let path = dir.join("row.pvtu");
    std::fs::write(&path, pvtu).unwrap();
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(loaded.report.pieces.ghost_cells_dropped, 1);
    let x = &loaded.report.excluded;
    assert_eq!(x.cells, [3], "{:?}", loaded.report.changes());
    assert_eq!((x.tangled, x.tets), (1, 6));
    // A and B remain: 12 tetrahedra.
    assert_eq!(loaded.mesh.tets.len(), 12);
    check_centred(&loaded);
}

#[test]
fn a_tangled_exodus_element_is_numbered_across_all_blocks() {
    let dir = scratch("exodus");
    let coords = row_points(0, 3);
    let one_based =
        |cells: Vec<Vec<i64>>| -> Vec<i64> { cells.concat().iter().map(|&i| i + 1).collect() };
    // A shell (skipped, element 0) before three hexahedra (elements 1-3),
    // the last twisted.
    let model = Model {
        coords: coords.clone(),
        blocks: vec![
            Block::new(1, "skin", "SHELL4", 4, &[1, 2, 6, 5]),
            Block::new(2, "solid", "HEX8", 8, &one_based(row_hexes(4, &[2]))),
        ],
        times: vec![0.0],
        nodal: vec![(
            "f".into(),
            vec![(0..coords.len()).map(|p| p as f64).collect()],
        )],
        elem: Vec::new(),
        old_layout: false,
        int64: false,
    };
    let path = dir.join("row.exo");
    std::fs::write(&path, model.write(Version::Cdf2)).unwrap();
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let x = &loaded.report.excluded;
    assert_eq!(x.cells, [3], "{:?}", loaded.report.changes());
    assert_eq!(x.tangled, 1);
    assert_eq!(loaded.mesh.tets.len(), 12);
    check_centred(&loaded);
}
