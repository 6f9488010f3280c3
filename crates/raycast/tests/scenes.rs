//! The synthetic meshes: positively oriented, conforming (shared faces
//! matched by the topology, so the boundary is exactly the box surface),
//! filling their boxes, deterministic.

use glam::{DVec3, Vec3};
use tetray_mesh::synthetic::{
    BuildError, CellSplit, ScalarSpec, add_field, box_grid, hollow_box, jittered_box, two_boxes,
};
use tetray_mesh::{TetMesh, Topology};

fn volumes(mesh: &TetMesh) -> Vec<f64> {
    mesh.tets
        .iter()
        .map(|t| {
            let [a, b, c, d] = t.map(|v| mesh.points[v as usize].as_dvec3());
            (b - a).dot((c - a).cross(d - a)) / 6.0
        })
        .collect()
}

/// Boundary triangles of an `n`-cell grid box: two per boundary quad.
fn box_boundary_faces(n: [usize; 3]) -> usize {
    4 * (n[0] * n[1] + n[1] * n[2] + n[0] * n[2])
}

#[test]
fn grids_are_oriented_conforming_and_fill_the_box() {
    let (lo, hi) = (Vec3::new(-1.0, 0.0, 2.0), Vec3::new(2.0, 1.0, 4.0));
    for (split, per_cell) in [(CellSplit::Five, 5), (CellSplit::Six, 6)] {
        let mesh = box_grid(lo, hi, [3, 2, 4], split).unwrap();
        assert_eq!(mesh.tets.len(), 24 * per_cell);
        assert_eq!(mesh.points.len(), 4 * 3 * 5);
        let v = volumes(&mesh);
        assert!(v.iter().all(|&x| x > 0.0));
        // Volumes of f32 grid points, summed in f64: 1e-9 relative.
        assert!((v.iter().sum::<f64>() - 6.0).abs() < 1e-9 * 6.0);
        let topo = Topology::build(&mesh).unwrap();
        assert_eq!(
            topo.boundary_faces.len(),
            box_boundary_faces([3, 2, 4]),
            "{split:?}"
        );
    }
}

#[test]
fn jittered_box_is_irregular_valid_and_deterministic() {
    let (lo, hi) = (Vec3::ZERO, Vec3::new(1.0, 2.0, 1.5));
    let mesh = jittered_box(lo, hi, [5, 4, 3], 0.2, 42, CellSplit::Five).unwrap();
    let again = jittered_box(lo, hi, [5, 4, 3], 0.2, 42, CellSplit::Five).unwrap();
    assert_eq!(mesh, again);
    let other = jittered_box(lo, hi, [5, 4, 3], 0.2, 43, CellSplit::Five).unwrap();
    assert_ne!(mesh.points, other.points);
    let v = volumes(&mesh);
    let regular = 1.0 / 5.0 * 0.5 * 0.5 / 6.0;
    assert!(v.iter().all(|&x| x > 0.01 * regular));
    // Still exactly the box: volume and bounds (1e-6: f32 jittered points).
    assert!((v.iter().sum::<f64>() - 3.0).abs() < 1e-6);
    assert_eq!(mesh.bounds(), (lo, hi));
    // Irregular: interior points moved off the lattice.
    let moved = mesh
        .points
        .iter()
        .filter(|p| (p.x * 5.0 - (p.x * 5.0).round()).abs() > 1e-3)
        .count();
    assert!(moved > 20, "{moved}");
    let topo = Topology::build(&mesh).unwrap();
    assert_eq!(topo.boundary_faces.len(), box_boundary_faces([5, 4, 3]));
    assert!(matches!(
        jittered_box(lo, hi, [2, 2, 2], 0.3, 1, CellSplit::Five),
        Err(BuildError::BadJitter(_))
    ));
}

#[test]
fn hollow_box_and_two_boxes_have_the_expected_boundaries() {
    let mesh = hollow_box(
        Vec3::ZERO,
        Vec3::splat(4.0),
        [4, 4, 4],
        [1, 1, 1],
        [3, 3, 3],
        CellSplit::Five,
    )
    .unwrap();
    assert_eq!(mesh.tets.len(), (64 - 8) * 5);
    let v: f64 = volumes(&mesh).iter().sum();
    assert!((v - 56.0).abs() < 1e-9);
    let topo = Topology::build(&mesh).unwrap();
    assert_eq!(
        topo.boundary_faces.len(),
        box_boundary_faces([4, 4, 4]) + box_boundary_faces([2, 2, 2])
    );
    assert!(
        hollow_box(
            Vec3::ZERO,
            Vec3::ONE,
            [2, 2, 2],
            [1, 1, 1],
            [1, 2, 2],
            CellSplit::Six
        )
        .is_err()
    );

    let mesh = two_boxes(
        (Vec3::ZERO, Vec3::ONE, [1, 1, 1]),
        (Vec3::splat(2.0), Vec3::splat(3.0), [2, 1, 1]),
        CellSplit::Six,
    )
    .unwrap();
    assert_eq!(mesh.tets.len(), 18);
    let topo = Topology::build(&mesh).unwrap();
    assert_eq!(
        topo.boundary_faces.len(),
        box_boundary_faces([1, 1, 1]) + box_boundary_faces([2, 1, 1])
    );
    assert_eq!(topo.components().0, 2);
}

#[test]
fn fields_are_sampled_from_their_closed_forms() {
    let mut mesh = box_grid(Vec3::ZERO, Vec3::ONE, [2, 2, 2], CellSplit::Five).unwrap();
    let spec = ScalarSpec::Linear {
        offset: 1.0,
        gradient: Vec3::new(1.0, 2.0, -3.0),
    };
    add_field(&mut mesh, "lin", spec);
    add_field(&mut mesh, "c", ScalarSpec::Constant(0.5));
    add_field(&mut mesh, "lin", ScalarSpec::Constant(2.0));
    assert_eq!(mesh.fields.len(), 2, "same name replaces");
    let c = mesh.field("c").unwrap();
    assert!(c.values.iter().all(|&v| v == 0.5));
    assert_eq!(spec.eval(DVec3::new(1.0, 1.0, 1.0)), 1.0);
    assert!(matches!(
        box_grid(Vec3::ZERO, Vec3::ONE, [0, 1, 1], CellSplit::Five),
        Err(BuildError::NoCells(_))
    ));
    assert!(matches!(
        box_grid(Vec3::ONE, Vec3::ZERO, [1, 1, 1], CellSplit::Five),
        Err(BuildError::BadBox { .. })
    ));
}
