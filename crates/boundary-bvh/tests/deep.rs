//! A tree deeper than the inline traversal stack: geometrically shrinking
//! tets make PLOC chain them. Checks the heap-stack fallback of
//! `first_entry` (a binary tree deeper than 64 levels collapses to a wide
//! one of at least 22, a wide level spanning at most three binary ones,
//! whose traversal may keep 3 entries a level pending: more than the
//! inline 64) and that `flatten` refuses a tree the GPU stack cannot hold.

mod support;

use glam::Vec3;
use support::rays::random_dir;
use support::{Rng, topology};
use tetray_boundary_bvh::{BoundaryBvh, BuildPreset, FLAT_STACK_SIZE, brute_force_first_entry};
use tetray_core::watertight::RayFrame;
use tetray_mesh::TetMesh;

/// Tet `k` has size and position `2^-k` (k = 0..count), all disjoint; the
/// smallest are still normal f32 (2^-119 > 2^-126).
fn shrinking_tets(count: u32) -> TetMesh {
    let mut mesh = TetMesh::default();
    for k in 0..count {
        let s = (-(k as f32)).exp2();
        let base = Vec3::new(s, 0.3 * s, -0.2 * s);
        let first = mesh.points.len() as u32;
        mesh.points.extend([
            base,
            base + Vec3::X * (0.4 * s),
            base + Vec3::Y * (0.4 * s),
            base + Vec3::Z * (0.4 * s),
        ]);
        mesh.tets.push([first, first + 1, first + 2, first + 3]);
    }
    // Positively oriented by construction (the volume itself underflows f32
    // for the smallest tets, so it is not checked).
    mesh
}

#[test]
fn deep_trees_use_the_heap_stack_and_are_refused_for_the_gpu() {
    let mesh = shrinking_tets(120);
    let topo = topology(&mesh);
    let mut rng = Rng::new(9);
    let mut deep = 0;
    let mut hits = 0;
    for preset in BuildPreset::ALL {
        let bvh = BoundaryBvh::build(&mesh, &topo, preset).unwrap();
        let depth = bvh.stats().max_depth;
        if depth as usize <= FLAT_STACK_SIZE {
            assert!(bvh.flatten().is_ok());
            continue;
        }
        deep += 1;
        assert!(bvh.flatten().is_err(), "{preset}: depth {depth} flattened");
        // Rays aimed at tets of every scale, from a distance of a few sizes.
        for k in 0..120 {
            let s = (-(k as f32)).exp2();
            let target = Vec3::new(s * 1.1, 0.35 * s, -0.15 * s);
            let dir = random_dir(&mut rng);
            let ray = RayFrame::new(target - dir * (3.0 * s), dir);
            let got = bvh.first_entry(&ray, 0.0, f32::INFINITY, &[]);
            let want = brute_force_first_entry(&mesh, &topo, &ray, 0.0, f32::INFINITY, &[]);
            assert_eq!(got, want, "{preset}: tet {k}");
            hits += usize::from(got.is_some());
        }
    }
    // The construction must actually exercise the fallback.
    assert!(
        deep > 0,
        "no preset built a tree deeper than {FLAT_STACK_SIZE}"
    );
    assert!(hits > 50 * deep, "only {hits} hits");
}
