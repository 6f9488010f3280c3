//! The frame loop takes many rays through each step together, stage by
//! stage, and integrates their segments at once (partial pre-integration in
//! SIMD lanes); a pixel traced alone takes its steps by itself and
//! integrates each segment with the one-segment integrator. Both must give
//! the same bits, for every method.

use glam::Vec3;
use tetray_core::Camera;
use tetray_integrate::{
    ColorPoint, IntegratorOptions, KernelVisitor, Method, OpacityPoint, ScalarIntegrator,
    SegmentKernel, TransferFunction, Typed,
};
use tetray_mesh::Topology;
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, hollow_box};
use tetray_raycast::{RenderOptions, render_scalar, trace_pixel};
use tetray_scene::Scene;

/// One pixel traced alone with the integrator's method fixed in its type,
/// as the frame loop has it.
struct Trace<'a> {
    scene: &'a Scene,
    camera: &'a Camera,
    opts: &'a RenderOptions,
    x: u32,
    y: u32,
}

impl KernelVisitor for Trace<'_> {
    type Output = [f32; 4];
    fn visit<K: SegmentKernel>(self, integrator: Typed<'_, K>) -> [f32; 4] {
        trace_pixel(
            self.scene,
            self.camera,
            &integrator,
            self.opts,
            self.x,
            self.y,
        )
        .unwrap()
        .0
    }
}

/// A hollow box (rays leave and re-enter it) with a linear field, and a
/// transfer function with knots inside the field's range, so that many
/// segments cross knots (integrated piece by piece, outside the lanes).
fn scene_and_tf() -> (Scene, TransferFunction) {
    let (lo, hi) = (Vec3::ZERO, Vec3::ONE);
    let mut mesh = hollow_box(lo, hi, [6, 5, 4], [1, 1, 1], [4, 3, 3], CellSplit::Five).unwrap();
    add_field(
        &mut mesh,
        "s",
        ScalarSpec::Linear {
            offset: 0.2,
            gradient: Vec3::new(0.9, -0.4, 0.3),
        },
    );
    let topology = Topology::build(&mesh).unwrap();
    let scene = Scene::new(mesh, topology, "s", Default::default()).unwrap();
    let color = [
        (-0.3, [0.1, 0.2, 0.9]),
        (0.4, [0.9, 0.9, 0.2]),
        (1.2, [0.8, 0.1, 0.1]),
    ]
    .map(|(scalar, rgb)| ColorPoint {
        scalar,
        rgb: Vec3::from(rgb),
    });
    let opacity = [(-0.3, 0.1), (0.1, 0.9), (0.5, 0.3), (1.2, 0.99)]
        .map(|(scalar, alpha)| OpacityPoint { scalar, alpha });
    let tf = TransferFunction::new(color.to_vec(), opacity.to_vec()).unwrap();
    (scene, tf)
}

#[test]
fn rays_stepped_together_give_the_bits_of_rays_traced_alone() {
    let (scene, tf) = scene_and_tf();
    let (lo, hi) = scene.bounds();
    let mut outside = Camera::reset_to_bounds(lo, hi).unwrap();
    outside.azimuth(30.0).unwrap();
    outside.elevation(20.0).unwrap();
    outside.orthogonalize_view_up().unwrap();
    // From inside the box's wall: segments clipped at the ray origin.
    let inside = Camera {
        position: Vec3::new(0.5, 0.5, 0.1),
        ..outside
    };
    let opts = RenderOptions {
        width: 29,
        height: 23,
        ..RenderOptions::default()
    };
    let options = IntegratorOptions {
        psi_table_size: 64,
        unit_distance: 0.2,
        ..IntegratorOptions::default()
    };
    for method in [
        Method::Ppi,
        Method::Exact,
        Method::Average,
        Method::LinOpacity,
    ] {
        let integrator = ScalarIntegrator::new(method, &tf, &options).unwrap();
        for camera in [&outside, &inside] {
            let frame = render_scalar(&scene, camera, &integrator, &opts).unwrap();
            assert!(
                frame.stats.counters.segments > 2000
                    && frame.stats.counters.entries > frame.stats.counters.rays_hit
            );
            for y in 0..opts.height {
                for x in 0..opts.width {
                    let alone = integrator.dispatch(Trace {
                        scene: &scene,
                        camera,
                        opts: &opts,
                        x,
                        y,
                    });
                    let together = frame.image.pixel(x, y).unwrap();
                    assert_eq!(
                        together.map(f32::to_bits),
                        alone.map(f32::to_bits),
                        "{method:?} pixel ({x}, {y}): {together:?} against {alone:?}"
                    );
                }
            }
        }
    }
}
