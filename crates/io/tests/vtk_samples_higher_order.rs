//! The higher-order and polyhedral samples of `data/real` (VTK's test
//! data) load, split into the expected tetrahedra and validate.

use std::path::PathBuf;

use tetray_io::vtk::{Linearize, ReadOptions, VtkRead, read_vtu_file, read_vtu_file_with};
use tetray_io::{LoadOptions, load};

fn sample(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/real")
        .join(name)
}

/// (type id, cells, tets, points added) per subdivided type.
fn per_type(read: &VtkRead) -> Vec<(i64, usize, usize, usize)> {
    let sub = &read.cells.subdivided;
    sub.iter()
        .map(|s| (s.type_id, s.cells, s.tets, s.points_added))
        .collect()
}

/// Loads through [`load`] (orient, validate, topology) and checks there are
/// no validation errors and every tet is used once.
fn loads(name: &str, linearize: Linearize) -> tetray_io::LoadedMesh {
    let opts = LoadOptions {
        linearize,
        ..LoadOptions::default()
    };
    load(&sample(name), &opts).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn quadratic_tetra_sample_gives_eight_tets_per_cell() {
    let read = read_vtu_file(&sample("QuadraticTetra.vtu")).unwrap();
    assert_eq!(per_type(&read), [(24, 96, 768, 0)]);
    assert_eq!(read.mesh.tets.len(), 768);
    assert_eq!(read.cells.tets_from_split, 768);
    let loaded = loads("QuadraticTetra.vtu", Linearize::Subdivide);
    assert_eq!(loaded.report.cells_split, 96);
    assert_eq!(loaded.report.points_added, 0);
    // Every node is used: the mid-edge values shape the field.
    assert_eq!(loaded.report.validation.unused_points, 0);

    let corners = read_vtu_file_with(
        &sample("QuadraticTetra.vtu"),
        &ReadOptions {
            linearize: Linearize::Corners,
        },
    )
    .unwrap();
    assert_eq!(corners.mesh.tets.len(), 96);
    let loaded = loads("QuadraticTetra.vtu", Linearize::Corners);
    assert!(loaded.report.validation.unused_points > 0);
}

#[test]
fn single_quadratic_tetra_uses_all_ten_nodes() {
    // One curved quadratic tetra and two quadratic triangles (skipped).
    let read = read_vtu_file(&sample("tetra.vtu")).unwrap();
    assert_eq!(per_type(&read), [(24, 1, 8, 0)]);
    assert_eq!(read.cells.skipped_lower_dim, 2);
    let mut used: Vec<u32> = read.mesh.tets.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    assert_eq!(used, (0..10).collect::<Vec<u32>>());
    loads("tetra.vtu", Linearize::Subdivide);
}

#[test]
fn quadratic_wedge_sample_gets_shared_quad_centres() {
    let read = read_vtu_file(&sample("QuadraticWedge.vtu")).unwrap();
    // 16 wedges, 8 linear wedges each, 3 tets each; one centre per distinct
    // quad face (32 of the 48 wedge quads; the other 16 are shared).
    assert_eq!(per_type(&read), [(26, 16, 384, 32)]);
    assert_eq!(read.mesh.points.len(), 93 + 32);
    for f in &read.mesh.fields {
        assert_eq!(f.values.len(), 125, "{}", f.name);
    }
    loads("QuadraticWedge.vtu", Linearize::Subdivide);
    let corners = loads("QuadraticWedge.vtu", Linearize::Corners);
    assert_eq!(corners.mesh.tets.len(), 16 * 3);
}

#[test]
fn notch_sample_quadratic_hexahedra_and_wedges_load() {
    let read = read_vtu_file(&sample("notch_disp.vtu")).unwrap();
    let types = per_type(&read);
    assert_eq!(types.len(), 2, "{types:?}");
    let (hex, wedge) = (types[0], types[1]);
    assert_eq!((hex.0, hex.1, wedge.0, wedge.1), (25, 2188, 26, 4));
    // 8 sub-hexahedra of 5 or 6 tets, 8 sub-wedges of 3 tets.
    assert!(hex.2 >= 2188 * 40 && hex.2 <= 2188 * 48, "{hex:?}");
    assert_eq!(wedge.2, 4 * 24);
    // A body centre per hexahedron plus the distinct face centres.
    assert!(hex.3 > 2188, "{hex:?}");
    assert_eq!(read.cells.points_added, hex.3 + wedge.3);
    assert_eq!(read.mesh.points.len(), 12717 + read.cells.points_added);

    // The displacement magnitude at an added point is the magnitude of the
    // interpolated vector: finite, and at most the sum of the weights'
    // magnitudes (3 at a face centre, 5 at a body centre) times the largest
    // magnitude at the file's points.
    let field = &read.mesh.fields[0];
    assert_eq!(field.name, "Nodal Displacement_magnitude");
    let max = field.values[..12717].iter().copied().fold(0.0f32, f32::max);
    assert!(
        field.values[12717..]
            .iter()
            .all(|&v| v.is_finite() && v >= 0.0 && v <= 5.0 * max)
    );

    let loaded = loads("notch_disp.vtu", Linearize::Subdivide);
    assert_eq!(loaded.report.validation.components, 1);
    assert_eq!(loaded.report.cells_split, 2192);
    let report_types: Vec<(i64, usize)> = loaded
        .report
        .subdivided
        .iter()
        .map(|s| (s.type_id, s.cells))
        .collect();
    assert_eq!(report_types, [(25, 2188), (26, 4)]);
    assert_eq!(loaded.report.points_added, read.cells.points_added);
    let corners = loads("notch_disp.vtu", Linearize::Corners);
    assert!(corners.mesh.tets.len() <= 2188 * 6 + 4 * 3);
}

#[test]
fn polyhedron_sample_loads() {
    let read = read_vtu_file(&sample("polyhedron2pieces.vtu")).unwrap();
    // Per piece a pyramid (2 tets) on a cube-shaped polyhedron (6 quads,
    // 2 tets each around the added centroid).
    assert_eq!(read.cells.pyramids, 2);
    assert_eq!(per_type(&read), [(42, 2, 24, 2)]);
    let centroids: Vec<[f32; 3]> = read.mesh.points[18..]
        .iter()
        .map(|p| p.to_array())
        .collect();
    assert_eq!(centroids, [[0.5, 0.5, 0.5], [0.5, 2.5, 0.5]]);
    let loaded = loads("polyhedron2pieces.vtu", Linearize::Subdivide);
    assert_eq!(loaded.report.validation.components, 2);
    assert_eq!(loaded.report.points_added, 2);
}
