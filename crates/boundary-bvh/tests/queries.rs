//! `first_entry` (BVH), its flat-layout CPU twin and the brute-force scan
//! must return identical hits (face and distance bit for bit) on every build
//! preset: all three run the same exact predicate, so there is no tolerance.

mod support;

use glam::Vec3;
use support::meshes::{Case, cases};
use support::rays::{Query, grid_queries, random_queries};
use support::{Rng, next_exit, topology};
use tetray_boundary_bvh::{
    BoundaryBvh, BuildPreset, BvhError, EntryHit, FlatBvh, brute_force_first_entry,
};
use tetray_core::watertight::RayFrame;
use tetray_mesh::{TetMesh, Topology};

fn same(a: Option<EntryHit>, b: Option<EntryHit>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => a.face == b.face && a.t.to_bits() == b.t.to_bits(),
        _ => false,
    }
}

struct Built {
    preset: BuildPreset,
    bvh: BoundaryBvh,
    flat: FlatBvh,
}

fn build_all(mesh: &TetMesh, topo: &Topology) -> Vec<Built> {
    BuildPreset::ALL
        .into_iter()
        .map(|preset| {
            let bvh = BoundaryBvh::build(mesh, topo, preset).expect("build");
            let flat = bvh.flatten().expect("test trees are shallow");
            Built { preset, bvh, flat }
        })
        .collect()
}

/// Checks one query on every build; returns the brute-force answer.
fn check(
    case: &Case,
    topo: &Topology,
    builds: &[Built],
    q: &Query,
    skip: &[u32],
) -> Option<EntryHit> {
    let expected = brute_force_first_entry(&case.mesh, topo, &q.ray, q.t_min, q.t_max, skip);
    for b in builds {
        let got = b.bvh.first_entry(&q.ray, q.t_min, q.t_max, skip);
        assert!(
            same(got, expected),
            "{} / {}: BVH {got:?} != brute force {expected:?} for {q:?} skip {skip:?}",
            case.name,
            b.preset
        );
        let twin = b
            .flat
            .first_entry(&case.mesh.points, &q.ray, q.t_min, q.t_max, skip);
        assert!(
            same(twin, expected),
            "{} / {}: flat twin {twin:?} != brute force {expected:?} for {q:?}",
            case.name,
            b.preset
        );
    }
    expected
}

#[test]
fn first_entry_matches_brute_force_on_every_preset() {
    let mut rng = Rng::new(1);
    for case in cases() {
        let topo = topology(&case.mesh);
        let builds = build_all(&case.mesh, &topo);
        let mut queries = random_queries(&case.mesh, 2000, &mut rng);
        for grid in &case.grids {
            queries.extend(grid_queries(grid));
        }
        let mut hits = 0;
        for q in &queries {
            hits += usize::from(check(&case, &topo, &builds, q, &[]).is_some());
        }
        // The comparison must not be vacuous: plenty of rays hit something.
        assert!(hits * 5 > queries.len(), "{}: only {hits} hits", case.name);
    }
}

/// Walks each ray through the mesh: entry, exit (from the predicate), then
/// the next entry with `t_min` = that exit and the exit face (plus random
/// other faces, sometimes the very answer) skipped, until it leaves for good.
#[test]
fn reentry_queries_match_brute_force() {
    let mut rng = Rng::new(2);
    for case in cases() {
        let topo = topology(&case.mesh);
        let builds = build_all(&case.mesh, &topo);
        let faces = topo.boundary_faces.len();
        let mut queries = random_queries(&case.mesh, 400, &mut rng);
        for grid in &case.grids {
            queries.extend(grid_queries(grid).into_iter().step_by(3));
        }
        let mut reentries = 0;
        for q in queries {
            let mut t_min = q.t_min;
            let mut skip = Vec::new();
            for step in 0.. {
                let query = Query { t_min, ..q };
                let Some(hit) = check(&case, &topo, &builds, &query, &skip) else {
                    break;
                };
                reentries += usize::from(step > 0);
                // Skipping the answer itself must give the next one.
                check(&case, &topo, &builds, &query, &[hit.face]);
                let Some((exit_face, exit_t)) = next_exit(&case.mesh, &topo, &q.ray, hit.t) else {
                    panic!("{}: entered at {hit:?} but never left", case.name);
                };
                t_min = exit_t;
                skip = vec![exit_face];
                skip.extend((0..rng.below(4)).map(|_| rng.below(faces) as u32));
            }
        }
        if case.name != "box-5" && case.name != "box-6" {
            assert!(reentries > 20, "{}: only {reentries} re-entries", case.name);
        }
    }
}

#[test]
fn ties_go_to_the_lowest_face_index() {
    // Two coincident copies of one box: every entering crossing is found
    // twice at the same distance, the lower face index must win everywhere.
    let case = &cases()[0];
    let single = topology(&case.mesh);
    let mut doubled = single.clone();
    doubled
        .boundary_faces
        .extend(single.boundary_faces.iter().rev().copied());
    let builds = build_all(&case.mesh, &doubled);
    let mut rng = Rng::new(3);
    let mut hits = 0;
    for q in random_queries(&case.mesh, 500, &mut rng) {
        if let Some(hit) = check(case, &doubled, &builds, &q, &[]) {
            hits += 1;
            assert!((hit.face as usize) < single.boundary_faces.len());
        }
    }
    assert!(hits > 100, "only {hits} hits");
}

#[test]
fn single_tetrahedron_on_every_preset() {
    let mut mesh = TetMesh {
        points: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z],
        tets: vec![[0, 1, 2, 3]],
        fields: Vec::new(),
    };
    support::meshes::orient(&mut mesh);
    let topo = topology(&mesh);
    for preset in BuildPreset::ALL {
        let bvh = BoundaryBvh::build(&mesh, &topo, preset).unwrap();
        let ray = RayFrame::new(Vec3::new(0.2, 0.2, -1.0), Vec3::Z);
        let hit = bvh.first_entry(&ray, 0.0, f32::INFINITY, &[]).unwrap();
        // Enters through the z = 0 face (opposite vertex 3) at t = 1 exactly.
        assert_eq!(topo.boundary_faces[hit.face as usize].local_face, 3);
        assert_eq!(hit.t, 1.0);
        assert_eq!(bvh.first_entry(&ray, 1.5, f32::INFINITY, &[]), None);
        assert_eq!(bvh.first_entry(&ray, 0.0, 0.5, &[]), None);
        assert_eq!(bvh.first_entry(&ray, 0.0, f32::INFINITY, &[hit.face]), None);
        let nan = RayFrame::new(Vec3::splat(f32::NAN), Vec3::Z);
        assert_eq!(bvh.first_entry(&nan, 0.0, f32::INFINITY, &[]), None);
        let stats = bvh.stats();
        assert_eq!(stats.faces, 4);
        assert_eq!(stats.nodes, 2 * stats.leaves - 1);
    }
}

#[test]
fn stats_describe_a_binary_tree_over_every_face() {
    let case = &cases()[3];
    let topo = topology(&case.mesh);
    for b in build_all(&case.mesh, &topo) {
        let s = b.bvh.stats();
        assert_eq!(s.faces, topo.boundary_faces.len());
        assert_eq!(s.nodes, 2 * s.leaves - 1, "{}", b.preset);
        assert!(s.primitive_refs >= s.faces, "{}", b.preset);
        assert!(s.max_leaf_size >= 1 && s.max_leaf_size <= 255);
        // A binary tree over L leaves is at least log2(L) deep.
        assert!(1u64 << s.max_depth >= s.leaves as u64, "{}", b.preset);
        assert_eq!(b.flat.max_depth(), s.max_depth);
        // Every face appears in some leaf of the flat layout.
        let mut seen = vec![false; s.faces];
        for node in b.flat.nodes().iter().filter(|n| n.count > 0) {
            for prim in &b.flat.prims()[node.index as usize..(node.index + node.count) as usize] {
                seen[prim.face as usize] = true;
                assert_eq!(
                    prim.vertices,
                    topo.boundary_faces[prim.face as usize].vertices
                );
            }
        }
        assert!(
            seen.iter().all(|&s| s),
            "{}: a face is in no leaf",
            b.preset
        );
    }
}

/// The leaf-order pass gives every face once, with its own points, on
/// every preset (pre-splits put a face in several leaves).
#[test]
fn leaf_order_gives_every_face_once_with_its_points() {
    for case in &cases() {
        let topo = topology(&case.mesh);
        for b in build_all(&case.mesh, &topo) {
            let faces = b.bvh.face_count();
            let mut seen = vec![false; faces];
            for i in 0..faces {
                let (face, tri) = b.bvh.face_in_leaf_order(i);
                assert!(!std::mem::replace(&mut seen[face as usize], true));
                let points = topo.boundary_faces[face as usize]
                    .vertices
                    .map(|v| case.mesh.points[v as usize]);
                assert_eq!(tri, points, "{} / {}: face {face}", case.name, b.preset);
            }
            assert!(seen.iter().all(|&s| s), "{} / {}", case.name, b.preset);
        }
    }
}

#[test]
fn flat_layout_is_the_documented_wgsl_layout() {
    use std::mem::{align_of, offset_of, size_of};
    use tetray_boundary_bvh::{FlatNode, FlatPrim};
    assert_eq!(size_of::<FlatNode>(), 32);
    assert_eq!(offset_of!(FlatNode, min), 0);
    assert_eq!(offset_of!(FlatNode, index), 12);
    assert_eq!(offset_of!(FlatNode, max), 16);
    assert_eq!(offset_of!(FlatNode, count), 28);
    assert_eq!(align_of::<FlatNode>(), 4);
    assert_eq!(size_of::<FlatPrim>(), 16);
    assert_eq!(offset_of!(FlatPrim, face), 12);
}

#[test]
fn bad_input_is_an_error() {
    let case = &cases()[0];
    let topo = topology(&case.mesh);
    let empty = Topology::default();
    assert_eq!(
        BoundaryBvh::build(&case.mesh, &empty, BuildPreset::default()).err(),
        Some(BvhError::NoBoundaryFaces)
    );
    let mut bad = case.mesh.clone();
    let v = topo.boundary_faces[7].vertices[1];
    bad.points[v as usize].y = f32::NAN;
    assert!(matches!(
        BoundaryBvh::build(&bad, &topo, BuildPreset::default()),
        Err(BvhError::NonFinitePoint { point, .. }) if point == v
    ));
    let mut short = case.mesh.clone();
    short.points.truncate(3);
    assert!(matches!(
        BoundaryBvh::build(&short, &topo, BuildPreset::default()),
        Err(BvhError::PointOutOfRange { points: 3, .. })
    ));
}
