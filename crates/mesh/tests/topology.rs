//! Face matching on small hand-built meshes: neighbour symmetry, boundary
//! counts, outward boundary normals, non-manifold faces.

use glam::Vec3;
use tetray_mesh::structured::{boundary_quad_count, structured_tets};
use tetray_mesh::{FACE_VERTICES, MeshError, NO_NEIGHBOR, TetMesh, Topology};

/// Two tetrahedra sharing the face (0, 1, 2), apexes on either side.
fn two_tets() -> TetMesh {
    let mut mesh = TetMesh {
        points: vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::new(0.3, 0.3, -1.0),
        ],
        tets: vec![[0, 1, 2, 3], [0, 1, 2, 4]],
        fields: vec![],
    };
    mesh.orient();
    mesh
}

/// An `n x n x n` point grid on the unit cube, gently sheared so no face is
/// axis-aligned, split 5 tets per hex.
fn grid(n: usize) -> TetMesh {
    let mut points = Vec::new();
    let h = 1.0 / (n - 1) as f32;
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let p = Vec3::new(i as f32, j as f32, k as f32) * h;
                points.push(p + Vec3::new(0.1 * p.y, 0.05 * p.z, 0.02 * p.x));
            }
        }
    }
    TetMesh {
        points,
        tets: structured_tets([n, n, n], n % 2),
        fields: vec![],
    }
}

/// Checks symmetry, that neighbours really share the face's points, and the
/// boundary bookkeeping.
fn check_consistent(mesh: &TetMesh, topo: &Topology) {
    assert_eq!(topo.neighbors.len(), mesh.tets.len());
    for (t, nbs) in topo.neighbors.iter().enumerate() {
        for (f, &nb) in nbs.iter().enumerate() {
            if nb == NO_NEIGHBOR {
                let b = topo
                    .boundary_face_index(t as u32, f)
                    .expect("a face with no neighbour is a boundary face");
                let face = topo.boundary_faces[b];
                assert_eq!((face.tet as usize, face.local_face as usize), (t, f));
                continue;
            }
            assert_eq!(topo.boundary_face_index(t as u32, f), None);
            let back = topo.shared_face(t as u32, nb).expect("neighbour symmetry");
            let mut mine = FACE_VERTICES[f].map(|v| mesh.tets[t][v]);
            let mut theirs = FACE_VERTICES[back].map(|v| mesh.tets[nb as usize][v]);
            mine.sort_unstable();
            theirs.sort_unstable();
            assert_eq!(mine, theirs, "tet {t} face {f} vs tet {nb} face {back}");
        }
    }
}

/// Every boundary face's right-hand normal points away from the owning
/// tetrahedron's opposite vertex. Exact sign test: the points are small
/// multiples of simple fractions and the test only needs the sign.
fn check_outward(mesh: &TetMesh, topo: &Topology) {
    for face in &topo.boundary_faces {
        let [a, b, c] = face.vertices.map(|i| mesh.points[i as usize]);
        let opposite = mesh.points[mesh.tets[face.tet as usize][face.local_face as usize] as usize];
        let normal = (b - a).cross(c - a);
        assert!(
            normal.dot(opposite - a) < 0.0,
            "face {face:?} points inwards"
        );
    }
}

#[test]
fn two_tets_share_one_face() {
    let mesh = two_tets();
    let topo = Topology::build(&mesh).unwrap();
    check_consistent(&mesh, &topo);
    check_outward(&mesh, &topo);
    assert_eq!(topo.boundary_faces.len(), 6);
    let interior: usize = topo
        .neighbors
        .iter()
        .flatten()
        .filter(|&&n| n != NO_NEIGHBOR)
        .count();
    assert_eq!(interior, 2);
    assert_eq!(topo.components().0, 1);
}

#[test]
fn hex_grid_is_conforming() {
    // 3 x 3 x 3 points: 2 x 2 x 2 hexes, both parities present.
    let mut mesh = grid(3);
    assert_eq!(mesh.orient(), 0, "the split emits positive tets");
    let topo = Topology::build(&mesh).unwrap();
    check_consistent(&mesh, &topo);
    check_outward(&mesh, &topo);
    // Conforming: the only boundary triangles are the halves of the 24
    // boundary quads.
    assert_eq!(
        topo.boundary_faces.len(),
        2 * boundary_quad_count([3, 3, 3])
    );
    assert_eq!(topo.components(), (1, vec![0; 40]));
    let volume: f64 = (0..mesh.tets.len()).map(|t| mesh.signed_volume(t)).sum();
    // The shear has determinant 1 + 0.1*0.05*0.02; f32 coordinates: 1e-6.
    assert!((volume - 1.0001).abs() < 1e-6, "volume {volume}");
}

#[test]
fn components_are_counted() {
    let mut mesh = two_tets();
    let offset = mesh.points.len() as u32;
    let shifted: Vec<Vec3> = mesh.points.iter().map(|p| *p + Vec3::splat(5.0)).collect();
    mesh.points.extend(shifted);
    mesh.tets.push([offset, offset + 1, offset + 2, offset + 3]);
    mesh.orient();
    let topo = Topology::build(&mesh).unwrap();
    assert_eq!(topo.components(), (2, vec![0, 0, 1]));
}

/// Components by a breadth-first search, labels in order of first
/// tetrahedron: the reference for [`Topology::components`].
fn components_by_search(topo: &Topology) -> (usize, Vec<u32>) {
    let mut label = vec![u32::MAX; topo.neighbors.len()];
    let mut count = 0;
    for seed in 0..label.len() {
        if label[seed] != u32::MAX {
            continue;
        }
        label[seed] = count;
        let mut queue = std::collections::VecDeque::from([seed]);
        while let Some(t) = queue.pop_front() {
            for &nb in &topo.neighbors[t] {
                if nb != NO_NEIGHBOR && label[nb as usize] == u32::MAX {
                    label[nb as usize] = count;
                    queue.push_back(nb as usize);
                }
            }
        }
        count += 1;
    }
    (count as usize, label)
}

#[test]
fn components_of_many_shuffled_blocks_match_a_search() {
    // 41 disjoint 6^3-point grids (625 tetrahedra each, 25 625 in all: more
    // than one parallel task) with their tetrahedra shuffled together, so
    // components interleave in the numbering and unions race.
    let block = grid(6);
    let mut mesh = TetMesh {
        points: vec![],
        tets: vec![],
        fields: vec![],
    };
    for b in 0..41u32 {
        let offset = mesh.points.len() as u32;
        let shift = Vec3::new(2.0 * b as f32, 0.0, 0.0);
        mesh.points.extend(block.points.iter().map(|p| *p + shift));
        mesh.tets
            .extend(block.tets.iter().map(|t| t.map(|v| v + offset)));
    }
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for i in (1..mesh.tets.len()).rev() {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1);
        mesh.tets.swap(i, (state >> 33) as usize % (i + 1));
    }
    mesh.orient();
    let topo = Topology::build(&mesh).unwrap();
    let (count, label) = topo.components();
    assert_eq!(count, 41);
    assert_eq!((count, label), components_by_search(&topo));
}

#[test]
fn face_shared_by_three_tets_is_named() {
    let mut mesh = two_tets();
    mesh.points.push(Vec3::new(0.2, 0.2, 2.0));
    mesh.tets.push([0, 1, 2, 5]);
    match Topology::build(&mesh) {
        Err(MeshError::NonManifoldFace { vertices, mut tets }) => {
            assert_eq!(vertices, [0, 1, 2]);
            tets.sort_unstable();
            assert_eq!(tets, vec![0, 1, 2]);
        }
        other => panic!("expected NonManifoldFace, got {other:?}"),
    }
}

#[test]
fn large_grid_matches_every_face() {
    // 51^3 points: 625,000 tets. Timing is printed, not asserted (shared
    // machine); the counts are exact.
    let mesh = grid(51);
    let start = std::time::Instant::now();
    let topo = Topology::build(&mesh).unwrap();
    eprintln!(
        "Topology::build of {} tets: {:?}",
        mesh.tets.len(),
        start.elapsed()
    );
    assert_eq!(
        topo.boundary_faces.len(),
        2 * boundary_quad_count([51, 51, 51])
    );
    let symmetric = topo.neighbors.iter().enumerate().all(|(t, nbs)| {
        nbs.iter()
            .all(|&nb| nb == NO_NEIGHBOR || topo.shared_face(t as u32, nb).is_some())
    });
    assert!(symmetric);
}

/// The bucketed matching against an independent one (a hash map of sorted
/// point triples) on a grid whose points and tetrahedra are shuffled, so
/// that buckets are not filled in order.
#[test]
fn matches_a_hash_map_on_a_shuffled_mesh() {
    let mut mesh = grid(9);
    let mut state = 0x9e37_79b9_u64;
    let mut next = move |n: usize| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1);
        (state >> 33) as usize % n
    };
    let mut relabel: Vec<u32> = (0..mesh.points.len() as u32).collect();
    for i in (1..relabel.len()).rev() {
        relabel.swap(i, next(i + 1));
    }
    for tet in &mut mesh.tets {
        *tet = tet.map(|v| relabel[v as usize]);
    }
    let mut points = mesh.points.clone();
    for (old, &new) in relabel.iter().enumerate() {
        points[new as usize] = mesh.points[old];
    }
    mesh.points = points;
    for i in (1..mesh.tets.len()).rev() {
        mesh.tets.swap(i, next(i + 1));
    }
    let topo = Topology::build(&mesh).unwrap();
    check_consistent(&mesh, &topo);
    check_outward(&mesh, &topo);
    // The buckets are filled by one chunk of tetrahedra per thread: any
    // thread count gives the same topology.
    for threads in [1, 3, 8] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let again = pool.install(|| Topology::build(&mesh)).unwrap();
        assert!(again == topo, "{threads} threads");
    }

    let mut faces: std::collections::HashMap<[u32; 3], Vec<u32>> = Default::default();
    for (t, tet) in mesh.tets.iter().enumerate() {
        for local in FACE_VERTICES {
            let mut key = local.map(|v| tet[v]);
            key.sort_unstable();
            faces.entry(key).or_default().push(t as u32);
        }
    }
    for (t, tet) in mesh.tets.iter().enumerate() {
        for (f, local) in FACE_VERTICES.iter().enumerate() {
            let mut key = local.map(|v| tet[v]);
            key.sort_unstable();
            let expected = faces[&key]
                .iter()
                .copied()
                .find(|&o| o != t as u32)
                .unwrap_or(NO_NEIGHBOR);
            assert_eq!(topo.neighbors[t][f], expected, "tet {t} face {f}");
        }
    }
}

/// With several faces shared by three tetrahedra, the one named is the
/// one with the smallest points, whatever the order of the tetrahedra.
#[test]
fn the_first_non_manifold_face_is_named() {
    let mut mesh = two_tets();
    mesh.points.push(Vec3::new(0.2, 0.2, 2.0));
    mesh.points.push(Vec3::new(0.1, 0.9, 1.5));
    // Face (1, 2, 3) of tet 0 shared by two more; face (0, 1, 2) by one more.
    mesh.tets.insert(0, [1, 2, 3, 6]);
    mesh.tets.insert(0, [1, 2, 3, 5]);
    mesh.tets.push([0, 1, 2, 5]);
    match Topology::build(&mesh) {
        Err(MeshError::NonManifoldFace { vertices, tets }) => {
            assert_eq!(vertices, [0, 1, 2]);
            assert_eq!(tets, vec![2, 3, 4]);
        }
        other => panic!("expected NonManifoldFace, got {other:?}"),
    }
}
