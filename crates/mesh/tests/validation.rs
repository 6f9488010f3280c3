//! Validation of meshes built in memory: every defect is rejected by
//! `validate` with the variant that names it; what renders fine passes with
//! a warning. `prepare` (the loader) leaves out the cells that cannot be
//! walked (flat, overlapping, on a non-manifold face) and reports them;
//! non-conforming faces are warnings, since rays cross them through the
//! boundary BVH.

use glam::Vec3;
use tetray_mesh::structured::structured_tets;
use tetray_mesh::{MeshError, ScalarField, TetMesh, prepare, validate};

/// The unit cube split into 5 tets (2 x 2 x 2 points), with a scalar.
fn cube() -> TetMesh {
    let points: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, (i >> 2) as f32))
        .collect();
    let values = points.iter().map(|p| p.x + 2.0 * p.y).collect();
    TetMesh {
        points,
        tets: structured_tets([2, 2, 2], 0),
        fields: vec![ScalarField {
            name: "s".into(),
            values,
        }],
    }
}

/// `n` unit cubes in a row along x (`n + 1` x 2 x 2 points); hex `h` split
/// with diagonal parity `parities[h]` (equal parities for all hexes make
/// the conforming split).
fn row(parities: &[usize]) -> TetMesh {
    let n = parities.len();
    let dims = [n + 1, 2, 2];
    let mut points = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..=n {
                points.push(Vec3::new(i as f32, j as f32, k as f32));
            }
        }
    }
    let tets = parities
        .iter()
        .enumerate()
        .flat_map(|(h, &p)| structured_tets(dims, p)[5 * h..5 * h + 5].to_vec())
        .collect();
    TetMesh {
        points,
        tets,
        fields: vec![],
    }
}

fn err(mesh: TetMesh) -> MeshError {
    match prepare(mesh) {
        Ok(_) => panic!("expected an error"),
        Err(e) => {
            // Every message is a sentence naming something specific.
            assert!(!e.to_string().is_empty());
            e
        }
    }
}

#[test]
fn a_good_mesh_passes_without_warnings() {
    let loaded = prepare(cube()).unwrap();
    assert_eq!(loaded.report.inverted_fixed, 0);
    assert!(
        loaded.report.warnings.is_empty(),
        "{:?}",
        loaded.report.warnings
    );
    assert_eq!(loaded.report.validation.components, 1);
    assert_eq!(loaded.topology.boundary_faces.len(), 12);
}

#[test]
fn empty_and_short_fields() {
    assert!(matches!(err(TetMesh::default()), MeshError::Empty));
    let mut mesh = cube();
    mesh.fields[0].values.pop();
    assert!(matches!(
        err(mesh),
        MeshError::FieldLength { field, expected: 8, found: 7 } if field == "s"
    ));
}

#[test]
fn dangling_and_repeated_indices() {
    let mut mesh = cube();
    mesh.tets[3][2] = 8;
    assert!(matches!(
        err(mesh),
        MeshError::DanglingIndex {
            tet: 3,
            corner: 2,
            index: 8,
            npoints: 8
        }
    ));
    let mut mesh = cube();
    mesh.tets[4][3] = mesh.tets[4][1];
    let point = mesh.tets[4][1];
    assert!(matches!(err(mesh), MeshError::RepeatedVertex { tet: 4, point: p, .. } if p == point));
}

#[test]
fn non_finite_coordinates_and_scalars() {
    let mut mesh = cube();
    mesh.points[6].y = f32::NAN;
    let e = err(mesh);
    assert!(
        matches!(
            e,
            MeshError::NonFiniteCoordinate {
                point: 6,
                axis: 'y',
                ..
            }
        ),
        "{e}"
    );
    let mut mesh = cube();
    mesh.fields[0].values[5] = f32::INFINITY;
    let e = err(mesh);
    assert!(
        matches!(&e, MeshError::NonFiniteScalar { field, point: 5, value } if field == "s" && value.is_infinite()),
        "{e}"
    );
}

#[test]
fn degenerate_tet_is_rejected_by_validate_and_dropped_on_load() {
    let mut mesh = cube();
    // A fifth point on the face z = 0 and a tet flat in that plane.
    mesh.points.push(Vec3::new(0.5, 0.5, 0.0));
    mesh.fields[0].values.push(0.0);
    mesh.tets.push([0, 1, 2, 8]);
    let e = validate(&mesh).unwrap_err();
    assert!(matches!(e, MeshError::DegenerateTet { tet: 5, .. }), "{e}");
    let loaded = prepare(mesh).unwrap();
    assert_eq!(loaded.report.excluded.flat_tets, 1);
    assert!(loaded.report.excluded.cells.is_empty());
    assert_eq!(loaded.mesh.tets.len(), 5);
    assert!(loaded.report.warnings.iter().any(|w| w.contains("1 flat")));
}

#[test]
fn inverted_tet_is_fixed_and_counted() {
    let mut mesh = cube();
    mesh.tets[2].swap(0, 1);
    // validate() wants oriented input...
    assert!(matches!(
        validate(&mesh),
        Err(MeshError::Inverted { tet: 2, .. })
    ));
    // ...prepare() orients first.
    let loaded = prepare(mesh).unwrap();
    assert_eq!(loaded.report.inverted_fixed, 1);
    assert!((0..5).all(|t| loaded.mesh.signed_volume(t) > 0.0));
}

#[test]
fn face_shared_by_three_tets() {
    let mut mesh = cube();
    let face = [mesh.tets[0][1], mesh.tets[0][2], mesh.tets[0][3]];
    mesh.points.push(Vec3::new(2.0, 2.0, 2.0));
    mesh.fields[0].values.push(0.0);
    mesh.tets.push([face[0], face[1], face[2], 8]);
    mesh.orient();
    let e = validate(&mesh).unwrap_err();
    assert!(
        matches!(&e, MeshError::NonManifoldFace { tets, .. } if tets.len() == 3),
        "{e}"
    );
    // The loader leaves the three out; the other three tets remain.
    let loaded = prepare(mesh).unwrap();
    let x = &loaded.report.excluded;
    assert_eq!(x.non_manifold, 3);
    assert_eq!(x.cells.len(), 3);
    assert!(
        x.cells.contains(&0) && x.cells.contains(&5),
        "{:?}",
        x.cells
    );
    assert_eq!(loaded.mesh.tets.len(), 3);
}

#[test]
fn overlapping_tets_across_a_face() {
    // Two tets with their apexes on the same side of the shared face.
    let mesh = TetMesh {
        points: vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::new(0.2, 0.2, 1.0),
            Vec3::new(0.3, 0.3, 2.0),
        ],
        tets: vec![[0, 1, 2, 3], [0, 1, 2, 4]],
        fields: vec![],
    };
    let e = validate(&mesh).unwrap_err();
    assert!(
        matches!(e, MeshError::Overlapping { tet_a: 0, tet_b: 1, vertices } if {
            let mut v = vertices; v.sort_unstable(); v == [0, 1, 2]
        }),
        "{e}"
    );
    // The loader leaves both out (the face cannot tell which is wrong):
    // nothing is left, which is an error saying so.
    let e = err(mesh);
    assert!(
        matches!(
            e,
            MeshError::NothingLeft {
                tets: 2,
                flat: 0,
                cells: 2
            }
        ),
        "{e}"
    );
}

/// A tet above the triangle (p0, p1, p2); below it, the same triangle
/// split at the midpoint m of p0-p1 into two tets: m hangs on an edge.
/// Once rejected; now a warning: the unmatched faces on both sides are
/// boundary faces, and a ray crossing from one side to the other leaves and
/// re-enters the mesh through the boundary BVH, exactly as at a seam (the
/// ray caster's `nonconforming.rs` checks the image).
#[test]
fn t_junction_is_a_warning() {
    let points = vec![
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0), // m
        Vec3::new(0.5, 0.5, 1.0),
        Vec3::new(0.5, 0.5, -1.0),
    ];
    let mesh = TetMesh {
        points,
        tets: vec![[0, 1, 2, 4], [0, 3, 2, 5], [3, 1, 2, 5]],
        fields: vec![],
    };
    let loaded = prepare(mesh).unwrap();
    let v = &loaded.report.validation;
    assert_eq!(v.hanging_nodes, 1);
    // The two faces of tet 0 on the hanging node's edge (z = 0 and the
    // outer face y = 0, against which the lower tets' outer faces make a
    // T-junction too), and the two faces below z = 0.
    let tets: Vec<u32> = v.nonconforming_faces.iter().map(|f| f.tet).collect();
    assert_eq!(tets, [0, 0, 1, 2]);
    assert!(
        loaded
            .report
            .warnings
            .iter()
            .any(|w| w.contains("4 faces do not meet"))
    );
    assert!(
        loaded
            .report
            .changes()
            .unwrap()
            .contains("4 non-conforming faces")
    );
}

/// The triangle below split at its centroid: the centroid hangs inside the
/// face of the tet above (a warning, as the T-junction).
#[test]
fn hanging_node_inside_a_face_is_a_warning() {
    let points = vec![
        Vec3::ZERO,
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0), // centroid
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(1.0, 1.0, -1.0),
    ];
    let tets = vec![[0, 1, 2, 4], [0, 1, 3, 5], [1, 2, 3, 5], [2, 0, 3, 5]];
    let loaded = prepare(TetMesh {
        points,
        tets,
        fields: vec![],
    })
    .unwrap();
    let v = &loaded.report.validation;
    assert_eq!(v.hanging_nodes, 1);
    // Each lower face shares an edge with the upper one and lies on it.
    assert_eq!(v.folded_face_pairs, 3);
    assert_eq!(v.nonconforming_faces.len(), 4);
}

/// Once rejected, now a warning (as the T-junction above).
#[test]
fn mismatched_diagonals_are_a_warning() {
    // Conforming: alternate the split.
    let conforming = prepare(row(&[0, 0])).unwrap();
    assert!(conforming.report.validation.nonconforming_faces.is_empty());
    assert!(conforming.report.changes().is_none());
    // Both hexes with the same local pattern: the shared face x = 1 is cut
    // along different diagonals from its two sides.
    let loaded = prepare(row(&[0, 1])).unwrap();
    let v = &loaded.report.validation;
    // Two triangles on each side, each folded onto both of the other side.
    assert_eq!(v.folded_face_pairs, 4);
    assert_eq!(v.nonconforming_faces.len(), 4);
    assert_eq!(v.hanging_nodes, 0);
    // The four faces are the topology's boundary faces beyond the box's 20.
    assert_eq!(loaded.topology.boundary_faces.len(), 24);
}

/// Two cubes side by side that do not share points: a seam. Rendering
/// crosses it by leaving and re-entering the mesh, so it is a warning,
/// whether the faces on the two sides coincide or not.
#[test]
fn seams_are_warnings() {
    for (second, coincident_faces) in [(1, 4), (0, 0)] {
        let mut mesh = cube();
        let mut other = cube();
        // Parity 1 continues the alternation across x = 1 (same diagonals
        // on both sides); parity 0 cuts the shared square the other way.
        if second == 1 {
            other.tets = structured_tets([2, 2, 2], 1);
        }
        let offset = mesh.points.len() as u32;
        mesh.points
            .extend(other.points.iter().map(|p| *p + Vec3::X));
        mesh.fields[0]
            .values
            .extend_from_slice(&other.fields[0].values);
        mesh.tets
            .extend(other.tets.iter().map(|t| t.map(|i| i + offset)));
        let loaded = prepare(mesh).unwrap();
        let v = &loaded.report.validation;
        assert_eq!(v.duplicate_points, 4);
        assert_eq!(v.seam_faces, coincident_faces);
        assert_eq!(v.components, 2);
        assert!(
            loaded
                .report
                .warnings
                .iter()
                .any(|w| w.contains("4 points repeat"))
        );
    }
}

#[test]
fn unused_points_are_a_warning() {
    let mut mesh = cube();
    mesh.points.push(Vec3::splat(9.0));
    mesh.fields[0].values.push(1.0);
    let loaded = prepare(mesh).unwrap();
    assert_eq!(loaded.report.validation.unused_points, 1);
    assert!(
        loaded
            .report
            .warnings
            .iter()
            .any(|w| w.contains("1 points are used by no"))
    );
}
