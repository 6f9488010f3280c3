//! The three NASA PLOT3D datasets (see data/README.md): tetrahedron
//! counts, face matching, conformity, the collapsed cells of Blunt Fin and
//! the concave cells of the Combustor. All counts are exact.

use std::path::{Path, PathBuf};
use std::time::Instant;

use tetray_io::{LoadOptions, LoadedMesh, load};
use tetray_mesh::structured::{boundary_quad_count, structured_tets};
use tetray_mesh::{MeshSummary, NO_NEIGHBOR, TetMesh, Topology, tet_shape};

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d")
}

fn grid_path(name: &str) -> PathBuf {
    let path = data_dir().join(format!("{name}xyz.bin"));
    assert!(path.is_file(), "missing {}", path.display());
    path
}

fn load_dataset(name: &str) -> LoadedMesh {
    let start = Instant::now();
    // No q path given: the loader finds the sibling `<name>q.bin`.
    let loaded = load(&grid_path(name), &LoadOptions::default()).unwrap();
    eprintln!("{name}: loaded in {:?}", start.elapsed());
    eprintln!("{}", MeshSummary::new(&loaded));
    loaded
}

/// Every interior face has exactly one tetrahedron on each side: the
/// neighbour relation is symmetric and never points to the tet itself.
fn check_interior_faces(topology: &Topology) {
    for (t, nbs) in topology.neighbors.iter().enumerate() {
        for &nb in nbs {
            if nb != NO_NEIGHBOR {
                assert_ne!(nb as usize, t);
                assert!(
                    topology.shared_face(t as u32, nb).is_some(),
                    "tet {t} -> {nb} not symmetric"
                );
            }
        }
    }
}

/// Conformity: the split of all hexahedra (before dropping anything) has
/// exactly two boundary triangles per boundary quad of the grid, so no
/// face inside the grid is left unmatched. Then the boundary of the loaded
/// mesh is what dropping the flat tetrahedra explains: a face of a kept
/// tetrahedron is on the boundary iff it was on the grid's boundary or its
/// neighbour was dropped. Returns the dropped count.
fn check_conforming(loaded: &LoadedMesh, dims: [usize; 3], parity: usize) -> usize {
    let mesh = &loaded.mesh;
    let full = TetMesh {
        points: mesh.points.clone(),
        tets: structured_tets(dims, parity),
        fields: vec![],
    };
    let full_topology = Topology::build(&full).unwrap();
    assert_eq!(
        full_topology.boundary_faces.len(),
        2 * boundary_quad_count(dims)
    );

    let shapes: Vec<_> = full
        .tets
        .iter()
        .map(|t| tet_shape(t.map(|i| mesh.points[i as usize])))
        .collect();
    let dropped: Vec<bool> = shapes.iter().map(|s| s.is_degenerate()).collect();
    let kept = dropped.iter().filter(|&&d| !d).count();
    assert_eq!(kept, mesh.tets.len());
    let expected_boundary: usize = full_topology
        .neighbors
        .iter()
        .enumerate()
        .filter(|&(t, _)| !dropped[t])
        .map(|(_, nbs)| {
            nbs.iter()
                .filter(|&&nb| nb == NO_NEIGHBOR || dropped[nb as usize])
                .count()
        })
        .sum();
    assert_eq!(loaded.topology.boundary_faces.len(), expected_boundary);
    // Dropped tetrahedra hold no volume (relative 1e-12: f64 sums of f32
    // products; in fact they are exactly 0 here).
    let dropped_volume: f64 = shapes
        .iter()
        .zip(&dropped)
        .filter(|&(_, &d)| d)
        .map(|(s, _)| s.volume6.abs())
        .sum();
    let total: f64 = shapes.iter().map(|s| s.volume6.abs()).sum();
    assert!(
        dropped_volume <= 1e-12 * total,
        "{dropped_volume} of {total}"
    );
    full.tets.len() - kept
}

/// `(hex index, number of flat tets)` of the hexes whose split (parity 0)
/// has flat tets.
fn flat_tets_per_hex(mesh: &TetMesh, dims: [usize; 3]) -> Vec<(usize, usize)> {
    let tets = structured_tets(dims, 0);
    let mut out: Vec<(usize, usize)> = Vec::new();
    for (t, tet) in tets.iter().enumerate() {
        if tet_shape(tet.map(|i| mesh.points[i as usize])).is_degenerate() {
            match out.last_mut() {
                Some((h, n)) if *h == t / 5 => *n += 1,
                _ => out.push((t / 5, 1)),
            }
        }
    }
    out
}

#[test]
fn blunt_fin() {
    let loaded = load_dataset("bluntfin");
    let report = &loaded.report;
    // 37,479 hexes x 5 = 187,395, less 77 tets of zero volume: along the
    // line j = 0, k = 0 the grid points (i, 0, 0) and (i, 1, 0) coincide
    // for i = 1..39. Hex (0, 0, 0) has one collapsed edge and loses one
    // tet; hexes (1..38, 0, 0) have two and lose two each: 1 + 2 x 38.
    assert_eq!(report.cells_split, 37_479);
    assert_eq!(report.degenerate_dropped, 77);
    assert_eq!(loaded.mesh.tets.len(), 187_395 - 77);
    assert_eq!(report.inverted_fixed, 0);
    assert_eq!(report.validation.duplicate_points, 39);
    assert_eq!(report.validation.components, 1);
    let names: Vec<&str> = loaded.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "density",
            "pressure",
            "velocity_magnitude",
            "stagnation_energy",
            "momentum_magnitude"
        ]
    );
    assert!(
        report.warnings.iter().any(|w| w.contains("484 bytes")),
        "{:?}",
        report.warnings
    );
    check_interior_faces(&loaded.topology);
    assert_eq!(check_conforming(&loaded, [40, 32, 32], 0), 77);
    let flat_per_hex = flat_tets_per_hex(&loaded.mesh, [40, 32, 32]);
    let mut expected = vec![(0, 1)];
    expected.extend((1..39).map(|h| (h, 2)));
    assert_eq!(flat_per_hex, expected, "(hex index, flat tets)");
}

#[test]
fn oxygen_post() {
    let loaded = load_dataset("post");
    assert_eq!(loaded.mesh.tets.len(), 513_375);
    assert_eq!(loaded.report.degenerate_dropped, 0);
    assert_eq!(loaded.report.inverted_fixed, 0);
    // The grid wraps around the post: the planes j = 0 and j = 75 coincide
    // (38 x 38 duplicate points). 75 cells around is odd, so no alternating
    // split can match diagonals across that seam; the mesh is cut there
    // and rays cross it by leaving and re-entering.
    assert_eq!(loaded.report.validation.duplicate_points, 38 * 38);
    check_interior_faces(&loaded.topology);
    assert_eq!(check_conforming(&loaded, [38, 76, 38], 0), 0);

    let start = Instant::now();
    let topology = Topology::build(&loaded.mesh).unwrap();
    eprintln!(
        "post: Topology::build of 513,375 tets in {:?}",
        start.elapsed()
    );
    assert_eq!(topology, loaded.topology);
}

#[test]
fn combustor() {
    let loaded = load_dataset("comb");
    assert_eq!(loaded.mesh.tets.len(), 215_040);
    assert_eq!(loaded.report.degenerate_dropped, 0);
    // Cells (39, 0, 0) and (39, 31, 0) have a concave corner: the split
    // with diagonals on even points inverts one corner tet in each, the one
    // on odd points does not, so the reader picks the latter.
    assert_eq!(loaded.report.inverted_fixed, 0);
    let direct = tetray_io::read_plot3d_files(&grid_path("comb"), None).unwrap();
    assert_eq!(direct.diagonal_parity, 1);
    check_interior_faces(&loaded.topology);
    assert_eq!(check_conforming(&loaded, [57, 33, 25], 1), 0);
}
