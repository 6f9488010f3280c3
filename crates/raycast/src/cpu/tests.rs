//! Unit tests of the frame: the walk's builds and the entry lists give the
//! same bits.

use glam::Vec3A;
use tetray_mesh::Topology;

use super::*;
use crate::segment::SegmentIntegrator;
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, hollow_box};

/// Light growing with the segment's length and scalars.
pub(crate) struct Glow;

impl SegmentIntegrator for Glow {
    type Sample = f32;
    fn sample(&self, s: f32) -> f32 {
        s
    }
    fn segment(&self, front: &f32, back: &f32, length: f32) -> (Vec3A, Vec3A) {
        let t = (-0.7 * length).exp();
        (
            Vec3A::new(front * length, back * length, length),
            Vec3A::splat(t),
        )
    }
}

/// A holed box (rays leave into the hole and re-enter) with a linear
/// field, and three views of it: from outside, a perspective eye
/// inside the mesh, and orthographic with the view plane through it.
pub(crate) fn holed_box_views() -> (Scene, [Camera; 3]) {
    let (lo, hi) = (Vec3::ZERO, Vec3::ONE);
    let mut mesh = hollow_box(lo, hi, [5, 4, 4], [1, 1, 1], [4, 3, 3], CellSplit::Five).unwrap();
    add_field(
        &mut mesh,
        "s",
        ScalarSpec::Linear {
            offset: 0.5,
            gradient: Vec3::new(1.0, -0.5, 0.25),
        },
    );
    let topology = Topology::build(&mesh).unwrap();
    let scene = Scene::new(mesh, topology, "s", Default::default()).unwrap();
    let mut outside = Camera::reset_to_bounds(lo, hi).unwrap();
    outside.azimuth(30.0).unwrap();
    outside.elevation(20.0).unwrap();
    outside.orthogonalize_view_up().unwrap();
    let inside = Camera {
        position: Vec3::new(0.5, 0.5, 0.1),
        ..outside
    };
    let through = Camera {
        position: Vec3::new(0.5, 0.45, 0.5),
        parallel_scale: Some(0.9),
        ..outside
    };
    (scene, [outside, inside, through])
}

/// The large-mesh walk (the records of the cells a ray may enter next
/// prefetched, and the new vertex of the cell it enters), the x86-64-v3
/// build of either, and each with its entries from per-pixel lists instead
/// of the BVH, give the small-mesh walk's image and counters bit for bit,
/// on a mesh with a hole (re-entries) from outside and from inside
/// (perspective, and orthographic with the view plane through the mesh).
#[test]
fn prefetching_walk_gives_the_same_bits() {
    let (scene, [outside, inside, through]) = holed_box_views();
    let opts = RenderOptions {
        width: 45,
        height: 38,
        ..RenderOptions::default()
    };
    for camera in [outside, inside, through] {
        let rays = camera.pixel_rays(opts.width, opts.height).unwrap();
        let mut frame = Frame::new(&scene, &camera, &rays, &Glow, &opts);
        frame.bin_entries();
        assert_eq!(frame.uses_entry_lists(), camera != inside);
        let mut images = Vec::new();
        // Both walks, each as the baseline build and as x86-64-v3's
        // (where the CPU has it; the baseline otherwise), each with
        // and without entry lists.
        let builds = [(false, false), (true, false), (false, true), (true, true)];
        for ((large, wide), entries) in builds.into_iter().flat_map(|b| [(b, false), (b, true)]) {
            frame.large = large;
            frame.wide = wide;
            if entries {
                frame.bin_entries();
            } else {
                frame.entries = None;
            }
            let mut pixels = vec![[0.0f32; 4]; 45 * 38];
            let stats = frame.run(&mut pixels);
            images.push((pixels, stats));
        }
        let (a, sa) = &images[0];
        assert!(sa.counters.segments > 1000 && sa.counters.entries > sa.counters.rays_hit);
        for (b, sb) in &images[1..] {
            assert!(
                a.iter()
                    .flatten()
                    .map(|v| v.to_bits())
                    .eq(b.iter().flatten().map(|v| v.to_bits()))
            );
            assert_eq!(
                (sa.counters.segments, sa.counters.steps, sa.counters.entries),
                (sb.counters.segments, sb.counters.steps, sb.counters.entries)
            );
        }
    }
    if !tetray_wide::detected() {
        eprintln!("note: this CPU lacks x86-64-v3; only the baseline walk ran");
    }
}
