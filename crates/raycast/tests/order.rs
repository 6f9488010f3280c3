//! The Morton renumbering of `Scene::new` is a pure relabelling: the
//! reordered scene renders the same image as the file's order, and its ids
//! map back to the file's.

use std::path::Path;

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_io::{LoadOptions, load};
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, hollow_box};
use tetray_mesh::{TetMesh, Topology};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::{CellOrder, Scene};

fn both(mesh: TetMesh, topology: Topology, field: &str) -> (Scene, Scene) {
    let file = Scene::new_with_order(
        mesh.clone(),
        topology.clone(),
        field,
        BuildPreset::default(),
        CellOrder::File,
    )
    .unwrap();
    let morton = Scene::new(mesh, topology, field, BuildPreset::default()).unwrap();
    (file, morton)
}

/// Every id maps back: tetrahedra, their points, and the field values.
fn check_mapping(file: &Scene, morton: &Scene) {
    assert!(file.reorder().is_none());
    let order = morton.reorder().expect("Morton order");
    assert_eq!(order.tet_from.len(), file.mesh.tets.len());
    let moved = (0..order.tet_from.len())
        .filter(|&t| order.tet_from[t] as usize != t)
        .count();
    assert!(moved > 0, "the Morton order is the identity");
    for (t, tet) in morton.mesh.tets.iter().enumerate() {
        let original = file.mesh.tets[morton.input_tet(t as u32) as usize];
        assert_eq!(tet.map(|v| morton.input_point(v)), original, "tet {t}");
    }
    for (p, &s) in morton.scalar.iter().enumerate() {
        let q = morton.input_point(p as u32) as usize;
        assert_eq!(s, file.scalar[q]);
        assert_eq!(morton.mesh.points[p], file.mesh.points[q]);
    }
    for (t, nb) in morton.topology.neighbors.iter().enumerate() {
        let original = file.topology.neighbors[morton.input_tet(t as u32) as usize];
        let mapped = nb.map(|n| {
            if n == u32::MAX {
                n
            } else {
                morton.input_tet(n)
            }
        });
        assert_eq!(mapped, original, "neighbours of tet {t}");
    }
    assert_eq!(
        morton.topology.boundary_faces.len(),
        file.topology.boundary_faces.len()
    );
}

fn views(scene: &Scene) -> Vec<Camera> {
    let (lo, hi) = scene.bounds();
    [(30.0, 20.0), (0.0, 0.0), (200.0, -35.0), (95.0, 60.0)]
        .iter()
        .map(|&(az, el)| {
            let mut camera = Camera::reset_to_bounds(lo, hi).unwrap();
            camera.azimuth(az).unwrap();
            camera.elevation(el).unwrap();
            camera.orthogonalize_view_up().unwrap();
            camera
        })
        .collect()
}

fn integrator(scene: &Scene, method: Method) -> ScalarIntegrator {
    let (lo, hi) = scene
        .scalar
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let (blo, bhi) = scene.bounds();
    let options = IntegratorOptions {
        unit_distance: (bhi - blo).length() / (scene.tet_count() as f32).cbrt(),
        ..IntegratorOptions::default()
    };
    let tf = TransferFunction::default_for_range(lo, hi);
    ScalarIntegrator::new(method, &tf, &options).unwrap()
}

fn check_images(file: &Scene, morton: &Scene, size: u32, what: &str) {
    let opts = RenderOptions {
        width: size,
        height: size,
        ..RenderOptions::default()
    };
    for method in [Method::Ppi, Method::Exact] {
        let a_int = integrator(file, method);
        let b_int = integrator(morton, method);
        for (v, camera) in views(file).iter().enumerate() {
            let a = render_scalar(file, camera, &a_int, &opts).unwrap();
            let b = render_scalar(morton, camera, &b_int, &opts).unwrap();
            assert!(a.stats.counters.rays_hit > 0, "{what} view {v}: empty");
            assert_eq!(
                a.stats.counters.segments, b.stats.counters.segments,
                "{what} view {v}"
            );
            assert_eq!(b.stats.counters.walk_failures, 0);
            assert_eq!(b.stats.counters.steps_bound_hits, 0);
            // The walk sees the same tetrahedra with the same local vertex
            // order and the same entry faces: the images are equal bit for
            // bit.
            let differing = a
                .image
                .rgba
                .iter()
                .zip(&b.image.rgba)
                .filter(|(p, q)| p.map(f32::to_bits) != q.map(f32::to_bits))
                .count();
            assert_eq!(differing, 0, "{what} {method:?} view {v}: pixels differ");
        }
    }
}

#[test]
fn hollow_box_renders_the_same() {
    let mut mesh = hollow_box(
        Vec3::ZERO,
        Vec3::new(2.0, 1.5, 1.0),
        [8, 6, 5],
        [2, 2, 1],
        [6, 4, 4],
        CellSplit::Five,
    )
    .unwrap();
    add_field(
        &mut mesh,
        "s",
        ScalarSpec::Linear {
            offset: 0.2,
            gradient: Vec3::new(0.3, -0.2, 0.5),
        },
    );
    let topology = Topology::build(&mesh).unwrap();
    let (file, morton) = both(mesh, topology, "s");
    check_mapping(&file, &morton);
    check_images(&file, &morton, 64, "hollow box");
}

#[test]
fn plot3d_post_renders_the_same() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let loaded = load(&root.join("postxyz.bin"), &LoadOptions::default()).unwrap();
    let (file, morton) = both(loaded.mesh, loaded.topology, "velocity_magnitude");
    check_mapping(&file, &morton);
    check_images(&file, &morton, 64, "Oxygen Post");
}

#[test]
fn plot3d_bluntfin_renders_the_same() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let loaded = load(&root.join("bluntfinxyz.bin"), &LoadOptions::default()).unwrap();
    let (file, morton) = both(loaded.mesh, loaded.topology, "density");
    check_images(&file, &morton, 96, "Blunt Fin");
}
