//! The split walk (`render_fragments`) against the whole-ray walk
//! (`render_scalar`): on a hollow box, where rays leave the mesh into the
//! hole and come back, each pixel's fragments composited front to back
//! give the pixel, and on a convex box each pixel has at most one
//! fragment, equal to the pixel bit for bit (same segments, same order).

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, box_grid, hollow_box};
use tetray_mesh::{TetMesh, Topology};
use tetray_raycast::{Fragment, RenderOptions, render_scalar, render_scalar_fragments};
use tetray_scene::Scene;

fn scene(mut mesh: TetMesh) -> Scene {
    add_field(
        &mut mesh,
        "s",
        ScalarSpec::Linear {
            offset: 0.5,
            gradient: Vec3::new(0.2, -0.1, 0.15),
        },
    );
    let topology = Topology::build(&mesh).unwrap();
    Scene::new(mesh, topology, "s", BuildPreset::default()).unwrap()
}

fn setup(scene: &Scene) -> (Camera, ScalarIntegrator, RenderOptions) {
    let (lo, hi) = scene.bounds();
    let mut camera = Camera::default();
    camera.reset(lo, hi, 1.0).unwrap();
    camera.azimuth(25.0).unwrap();
    camera.elevation(15.0).unwrap();
    camera.orthogonalize_view_up().unwrap();
    let tf = TransferFunction::default_for_range(-0.5, 1.5);
    let integrator = ScalarIntegrator::new(
        Method::Ppi,
        &tf,
        &IntegratorOptions {
            unit_distance: 0.5,
            ..IntegratorOptions::default()
        },
    )
    .unwrap();
    let opts = RenderOptions {
        width: 48,
        height: 48,
        ..RenderOptions::default()
    };
    (camera, integrator, opts)
}

fn blend(fragments: &[Fragment]) -> [f32; 4] {
    let (mut c, mut t) = ([0.0f32; 3], [1.0f32; 3]);
    for f in fragments {
        for i in 0..3 {
            c[i] += t[i] * f.color[i];
            t[i] *= f.transmittance[i];
        }
    }
    [c[0], c[1], c[2], 1.0 - (t[0] + t[1] + t[2]) / 3.0]
}

#[test]
fn hollow_box_fragments_composite_to_the_whole_ray() {
    let mesh = hollow_box(
        Vec3::ZERO,
        Vec3::new(3.0, 2.0, 2.5),
        [6, 4, 5],
        [2, 1, 1],
        [4, 3, 4],
        CellSplit::Five,
    )
    .unwrap();
    let scene = scene(mesh);
    let (camera, integrator, opts) = setup(&scene);
    let whole = render_scalar(&scene, &camera, &integrator, &opts).unwrap();
    let split = render_scalar_fragments(&scene, &camera, &integrator, &opts).unwrap();
    assert_eq!(split.stats.counters.segments, whole.stats.counters.segments);
    let mut per_pixel = vec![Vec::new(); 48 * 48];
    for f in &split.fragments {
        per_pixel[f.pixel as usize].push(*f);
    }
    // Some rays cross the hole: two intervals.
    assert!(per_pixel.iter().any(|f| f.len() >= 2));
    for (p, frags) in per_pixel.iter().enumerate() {
        assert!(frags.windows(2).all(|w| w[0].depth < w[1].depth));
        let got = blend(frags);
        let want = whole.image.rgba[p];
        // The same segments composited with one more rounding per
        // interval: f32 rounding, 1e-6.
        for c in 0..4 {
            assert!(
                (got[c] - want[c]).abs() < 1e-6,
                "pixel {p}: {got:?} {want:?}"
            );
        }
    }
}

#[test]
fn a_convex_box_has_one_fragment_per_hit_pixel_equal_to_it() {
    let mesh = box_grid(Vec3::ZERO, Vec3::splat(2.0), [3, 3, 3], CellSplit::Six).unwrap();
    let scene = scene(mesh);
    let (camera, integrator, opts) = setup(&scene);
    let whole = render_scalar(&scene, &camera, &integrator, &opts).unwrap();
    let split = render_scalar_fragments(&scene, &camera, &integrator, &opts).unwrap();
    assert_eq!(split.fragments.len() as u64, whole.stats.counters.rays_hit);
    for f in &split.fragments {
        assert_eq!(blend(&[*f]), whole.image.rgba[f.pixel as usize]);
    }
    // Early termination would cut rays on this mesh alone: refused.
    let cut = RenderOptions {
        early_termination: 0.99,
        ..opts
    };
    assert!(render_scalar_fragments(&scene, &camera, &integrator, &cut).is_err());
}
