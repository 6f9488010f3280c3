//! The visibility sorts on meshes with known answers: every order is a
//! permutation; MPVO and MPVONC respect every shared face (the cell the eye
//! is not on the side of comes first), with no cycle on a convex box
//! (whose five-tet split is a regular, hence acyclic, subdivision); the
//! centroid sort is by depth.

mod support;

use glam::Vec3;
use support::{camera, convex_box, scene};
use tetray_mesh::NO_NEIGHBOR;
use tetray_mesh::synthetic::{CellSplit, hollow_box};
use tetray_project::{ProjectScene, SortKind, View, visibility_order};

fn is_permutation(order: &[u32], n: usize) -> bool {
    let mut seen = vec![false; n];
    order.len() == n
        && order
            .iter()
            .all(|&t| !std::mem::replace(&mut seen[t as usize], true))
}

/// Shared faces whose cell behind comes after the cell in front.
fn face_violations(scene: &ProjectScene, view: &View, order: &[u32]) -> usize {
    let mut position = vec![0usize; order.len()];
    for (i, &t) in order.iter().enumerate() {
        position[t as usize] = i;
    }
    let mut bad = 0;
    for (t, (planes, neighbors)) in scene.planes.iter().zip(&scene.neighbors).enumerate() {
        for j in 0..4 {
            let n = neighbors[j];
            // The eye on t's inner side: the neighbour is behind t.
            if n != NO_NEIGHBOR
                && view.eye_side(&planes[j]) < 0.0
                && position[n as usize] > position[t]
            {
                bad += 1;
            }
        }
    }
    bad
}

#[test]
fn mpvo_orders_a_convex_mesh_by_its_faces() {
    let scene = convex_box(5);
    let project = ProjectScene::new(&scene).expect("project");
    for orthographic in [false, true] {
        let view = View::new(&camera(&scene, orthographic), 64, 64).expect("view");
        for kind in [SortKind::Mpvo, SortKind::Mpvonc] {
            let order = visibility_order(&project, &view, kind);
            assert!(is_permutation(&order.tets, project.tet_count()), "{kind}");
            assert_eq!(order.cycle_breaks, 0, "{kind}: a convex box has no cycle");
            assert_eq!(face_violations(&project, &view, &order.tets), 0, "{kind}");
        }
    }
}

#[test]
fn mpvo_stays_a_face_order_on_a_nonconvex_mesh() {
    let mut mesh = hollow_box(
        Vec3::splat(-1.0),
        Vec3::splat(1.0),
        [6, 6, 6],
        [2, 2, 0],
        [4, 4, 6],
        CellSplit::Five,
    )
    .expect("hollow box");
    support::add_smooth_field(&mut mesh, "smooth");
    let scene = scene(mesh, "smooth");
    let project = ProjectScene::new(&scene).expect("project");
    let view = View::new(&camera(&scene, false), 64, 64).expect("view");
    for kind in [SortKind::Mpvo, SortKind::Mpvonc] {
        let order = visibility_order(&project, &view, kind);
        assert!(is_permutation(&order.tets, project.tet_count()));
        assert_eq!(face_violations(&project, &view, &order.tets), 0, "{kind}");
    }
}

#[test]
fn centroid_sort_is_by_depth_far_first() {
    let scene = convex_box(6);
    let project = ProjectScene::new(&scene).expect("project");
    let view = View::new(&camera(&scene, false), 64, 64).expect("view");
    let order = visibility_order(&project, &view, SortKind::Centroid);
    assert!(is_permutation(&order.tets, project.tet_count()));
    let depths: Vec<f32> = order
        .tets
        .iter()
        .map(|&t| view.depth(project.centroids[t as usize]))
        .collect();
    assert!(depths.windows(2).all(|w| w[0] >= w[1]), "not far to near");
    // The far-first key orders any finite depths, negative ones included.
    let keys: Vec<u32> = [3.0f32, 1.0, 0.0, -0.5, -7.0]
        .iter()
        .map(|&d| tetray_project::sort::far_first_key(d))
        .collect();
    assert!(keys.windows(2).all(|w| w[0] < w[1]), "{keys:?}");
}
