//! Rays aimed exactly through grid vertices, along grid edges and inside
//! face planes (axis-aligned orthographic views of structured tet grids with
//! pixel centres on a quarter-integer lattice, where every projected
//! coordinate is exact): the watertight predicate's tie-breaking must give
//! every ray exactly one exit face per cell, so no pixel may deviate from
//! the closed form and no walk may fail.

mod support;

use glam::{DVec3, Vec3};
use support::{BeerLambert, LengthAndScalar, box_chord, box_interval, linear_integral, scene};
use tetray_core::Camera;
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, box_grid};
use tetray_raycast::{RenderOptions, render_cpu};

/// 15 pixels of 0.25 world units: pixel centres at 0.25, 0.5, .., 3.75 on
/// the grid [0, 4]^3 of unit cells, i.e. on vertices, edges, cell faces and
/// the diagonal planes of the split; never on the mesh boundary, where the
/// closed form itself would be ambiguous.
const SIZE: u32 = 15;
const CENTRE: Vec3 = Vec3::splat(2.0);

/// Every axis-aligned view, orthographic (and perspective: its central ray
/// runs exactly along a line of grid edges).
fn axis_views() -> Vec<Camera> {
    let mut views = Vec::new();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            for ortho in [true, false] {
                let mut offset = Vec3::ZERO;
                offset[axis] = 10.0 * sign;
                let mut up = Vec3::ZERO;
                up[(axis + 1) % 3] = 1.0;
                views.push(Camera {
                    position: CENTRE + offset,
                    focal_point: CENTRE,
                    view_up: up,
                    view_angle: 15.0,
                    parallel_scale: ortho.then_some(0.125 * SIZE as f32),
                });
            }
        }
    }
    views
}

#[test]
fn rays_through_vertices_edges_and_faces_match_the_closed_form() {
    let (lo, hi) = (Vec3::ZERO, Vec3::splat(4.0));
    let (offset, gradient) = (0.5f32, Vec3::new(0.25, -0.125, 0.375));
    let opts = RenderOptions {
        width: SIZE,
        height: SIZE,
        ..RenderOptions::default()
    };
    let beer = BeerLambert {
        l: Vec3::new(0.9, 0.6, 0.3),
        tau: 0.35,
    };
    for split in [CellSplit::Five, CellSplit::Six] {
        let mut mesh = box_grid(lo, hi, [4, 4, 4], split).unwrap();
        add_field(&mut mesh, "lin", ScalarSpec::Linear { offset, gradient });
        let scene = scene(mesh, "lin");
        for (v, camera) in axis_views().iter().enumerate() {
            let what = format!("{split:?} view {v}");
            let walk = render_cpu(&scene, camera, &LengthAndScalar, &opts).unwrap();
            let light = render_cpu(&scene, camera, &beer, &opts).unwrap();
            for stats in [walk.stats, light.stats] {
                assert_eq!(stats.counters.walk_failures, 0, "{what}");
                assert_eq!(stats.counters.steps_bound_hits, 0, "{what}");
                assert_eq!(stats.counters.rays_hit, u64::from(SIZE * SIZE), "{what}");
            }
            let mut bad = Vec::new();
            for py in 0..SIZE {
                for px in 0..SIZE {
                    let ray = camera.ray(px, py, SIZE, SIZE).unwrap();
                    let chord = box_chord(&ray, lo, hi);
                    let (t0, t1) = box_interval(&ray, lo, hi).unwrap();
                    let integral =
                        linear_integral(&ray, f64::from(offset), gradient.as_dvec3(), t0, t1);
                    let alpha = 1.0 - (-f64::from(beer.tau) * chord).exp();
                    let want = [chord, integral];
                    let w = walk.image.pixel(px, py).unwrap();
                    let l = light.image.pixel(px, py).unwrap();
                    // Lengths and integrals: 1e-5 (f32 distances below 12,
                    // ulp 1e-6, over ~20 segments). Beer-Lambert 1e-5 as
                    // required of the renderer.
                    let errors = [
                        (f64::from(w[0]) - want[0]).abs(),
                        (f64::from(w[1]) - want[1]).abs(),
                        (f64::from(l[3]) - alpha).abs(),
                        (DVec3::from(
                            l.map(f64::from)[..3]
                                .try_into()
                                .map(|a: [f64; 3]| a)
                                .unwrap(),
                        ) - beer.l.as_dvec3() * alpha)
                            .abs()
                            .max_element(),
                    ];
                    if errors.iter().any(|&e| e > 1e-5) {
                        bad.push((px, py, errors));
                    }
                }
            }
            assert!(
                bad.is_empty(),
                "{what}: {} pixels off: {:?}",
                bad.len(),
                &bad[..bad.len().min(5)]
            );
        }
    }
}
