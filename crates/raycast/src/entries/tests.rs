//! The lists against the brute-force scan.

use glam::Vec3;
use tetray_boundary_bvh::{EntryHit, brute_force_first_entry, reentry_start};
use tetray_core::watertight::{RayFrame, cross_triangle};
use tetray_mesh::Topology;

use super::*;
use tetray_core::camera::Camera;
use tetray_mesh::synthetic::{CellSplit, add_field, box_grid, hollow_box, jittered_box, merge};

fn scene(mut mesh: tetray_mesh::TetMesh) -> Scene {
    add_field(
        &mut mesh,
        "s",
        tetray_mesh::synthetic::ScalarSpec::Constant(1.0),
    );
    let topology = Topology::build(&mesh).unwrap();
    Scene::new(mesh, topology, "s", Default::default()).unwrap()
}

/// A holed jittered box and, beside it, a row of ten small boxes along
/// z (rays along z enter more faces than a list holds).
fn scenes() -> Vec<Scene> {
    let (lo, hi) = (Vec3::ZERO, Vec3::ONE);
    let holed = hollow_box(lo, hi, [4, 4, 4], [1, 1, 1], [3, 3, 3], CellSplit::Five).unwrap();
    let mut row = jittered_box(lo, hi, [3, 4, 3], 0.2, 7, CellSplit::Six).unwrap();
    for k in 0..10 {
        let z = 1.2 + 0.15 * k as f32;
        let b = Vec3::new(0.3, 0.3, z);
        let cube = box_grid(b, b + Vec3::new(0.4, 0.4, 0.1), [1, 1, 1], CellSplit::Five);
        row = merge(row, cube.unwrap()).unwrap();
    }
    vec![scene(holed), scene(row)]
}

/// Views from outside: oblique, zoomed in (pixels of 1e-4 radians),
/// along an axis with pixel centres on grid lines (perspective and
/// orthographic), and orthographic with its view plane through the
/// mesh (rays starting inside).
fn cameras(scene: &Scene) -> Vec<Camera> {
    let (lo, hi) = scene.bounds();
    let mut oblique = Camera::reset_to_bounds(lo, hi).unwrap();
    oblique.azimuth(30.0).unwrap();
    oblique.elevation(20.0).unwrap();
    oblique.orthogonalize_view_up().unwrap();
    let mut zoomed = oblique;
    zoomed.zoom(300.0).unwrap();
    let centre = (lo + hi) * 0.5;
    let axis = Camera {
        position: Vec3::new(0.5, 0.5, -3.0),
        focal_point: Vec3::new(0.5, 0.5, 0.0),
        view_up: Vec3::Y,
        ..oblique
    };
    let axis_ortho = Camera {
        parallel_scale: Some(0.75),
        ..axis
    };
    let through = Camera {
        position: centre - oblique.basis().unwrap().direction * 0.01,
        parallel_scale: Some(1.5),
        ..oblique
    };
    vec![oblique, zoomed, axis, axis_ortho, through]
}

/// Every entering crossing of `ray`, in the lists' order.
fn all_entries(scene: &Scene, ray: &RayFrame) -> Vec<EntryHit> {
    let mut all: Vec<EntryHit> = (0u32..)
        .zip(&scene.topology.boundary_faces)
        .filter_map(|(face, bf)| {
            let [a, b, c] = bf
                .vertices
                .map(|v| ray.project(scene.mesh.points[v as usize]));
            let crossing = cross_triangle(a, b, c)?;
            crossing.entering.then_some(EntryHit {
                face,
                t: crossing.t,
            })
        })
        .collect();
    all.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.face.cmp(&b.face)));
    all
}

/// Each pixel's list holds exactly the entries of its ray (or says it
/// overflowed, when there are more), and answers the queries a walk
/// makes (from the start, from each entry, from each re-entry start,
/// skipping the faces entered there) as the brute-force scan does.
#[test]
fn lists_answer_as_the_brute_force_scan() {
    let (width, height) = (33, 24);
    let (mut lists, mut frames) = (Vec::new(), Vec::new());
    let (mut pixels, mut overflowed, mut reentering) = (0, 0, 0);
    // Both builds where the CPU has x86-64-v3 (`tetray_wide::run`).
    let builds = [false, true];
    for (scene, camera, wide) in (scenes().iter())
        .flat_map(|scene| {
            cameras(scene)
                .into_iter()
                .map(move |camera| (scene, camera))
        })
        .flat_map(|(scene, camera)| builds.map(|wide| (scene, camera, wide)))
    {
        let rays = camera.pixel_rays(width as u32, height as u32).unwrap();
        let bins = EntryBins::new(scene, &rays, (width, height), false, 8, wide).unwrap();
        for (y0, x0) in (0..height)
            .step_by(8)
            .flat_map(|y| (0..width).step_by(8).map(move |x| (y, x)))
        {
            let size = ((x0 + 8).min(width) - x0, (y0 + 8).min(height) - y0);
            bins.fill_tile(&rays, (x0, y0), size, &mut lists, &mut frames);
            for (list, ray) in lists.iter().zip(&frames) {
                pixels += 1;
                let all = all_entries(scene, ray);
                if !list.is_complete() {
                    assert!(all.len() > LIST_LEN);
                    overflowed += 1;
                    continue;
                }
                assert_eq!(&list.hits[..usize::from(list.len)], &all[..]);
                reentering += usize::from(all.len() > 1);
                let abs_max = scene.bvh.scene_abs_max();
                let mut starts = vec![f32::NEG_INFINITY, 0.0];
                for h in &all {
                    starts.extend([h.t, reentry_start(ray, h.t, abs_max)]);
                }
                for &t_min in &starts {
                    for skip in [vec![]].into_iter().chain(all.iter().map(|h| vec![h.face])) {
                        let want = brute_force_first_entry(
                            &scene.mesh,
                            &scene.topology,
                            ray,
                            t_min,
                            f32::INFINITY,
                            &skip,
                        );
                        assert_eq!(list.first_entry(t_min, f32::INFINITY, &skip), want);
                    }
                }
                assert_eq!(list.first_entry(f32::NAN, f32::INFINITY, &[]), None);
            }
        }
    }
    // Both paths ran, and many rays came back after leaving.
    assert!(
        overflowed > 20 && reentering > pixels / 8,
        "{overflowed} {reentering} {pixels}"
    );
}

/// A perspective eye inside the mesh's bounds sees faces behind it:
/// the frame keeps the BVH.
#[test]
fn an_eye_inside_keeps_the_bvh() {
    let scene = &scenes()[0];
    let camera = Camera {
        position: Vec3::new(0.5, 0.5, 0.1),
        ..cameras(scene)[0]
    };
    let rays = camera.pixel_rays(16, 16).unwrap();
    assert!(EntryBins::new(scene, &rays, (16, 16), true, 8, false).is_none());
}
