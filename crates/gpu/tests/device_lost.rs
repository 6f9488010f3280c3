//! A device that is lost (here destroyed, as a driver reset or a removed
//! GPU would leave it): the next render is one clear error, within
//! seconds, not a hang or a panic.

mod support;

use std::time::{Duration, Instant};

use glam::Vec3;
use support::scene;
use tetray_core::Camera;
use tetray_gpu::{GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene, SceneData};
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityPoint, ScalarIntegrator, TransferFunction,
};
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, box_grid};

#[test]
fn a_lost_device_is_one_clear_error() {
    let ctx = match GpuContext::new() {
        Ok(ctx) => ctx,
        Err(e) => {
            assert!(
                std::env::var("TETRAY_REQUIRE_GPU").as_deref() != Ok("1"),
                "TETRAY_REQUIRE_GPU=1 but no adapter: {e}"
            );
            eprintln!("\n!!! SKIPPING GPU TEST: no adapter ({e}) !!!\n");
            return;
        }
    };
    let raycaster = GpuRaycaster::new(&ctx).expect("the kernel compiles");
    let (lo, hi) = (Vec3::ZERO, Vec3::ONE);
    let mut mesh = box_grid(lo, hi, [3, 3, 3], CellSplit::Six).expect("mesh");
    add_field(&mut mesh, "s", ScalarSpec::Constant(0.5));
    let scene = scene(mesh, "s");
    let tf = TransferFunction::new(
        vec![ColorPoint {
            scalar: 0.0,
            rgb: Vec3::ONE,
        }],
        vec![OpacityPoint {
            scalar: 0.0,
            alpha: 0.5,
        }],
    )
    .expect("tf");
    let integrator =
        ScalarIntegrator::new(Method::Ppi, &tf, &IntegratorOptions::default()).expect("ppi");
    let data = SceneData::new(&scene).expect("data");
    let upload = GpuScene::upload(&ctx, &data).expect("upload");
    let gpu_integrator = GpuIntegrator::new(&ctx, &integrator).expect("integrator");
    let camera = Camera::reset_to_bounds(lo, hi).expect("camera");
    let options = GpuRenderOptions {
        width: 16,
        height: 16,
        ..GpuRenderOptions::default()
    };
    let before = raycaster
        .render(&ctx, &upload, &gpu_integrator, &camera, &options)
        .expect("a render before the loss");
    assert!(before.image.rgba.iter().any(|p| p[3] > 0.1));

    ctx.device.destroy();
    let start = Instant::now();
    let after = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        raycaster.render(&ctx, &upload, &gpu_integrator, &camera, &options)
    }));
    let elapsed = start.elapsed();
    println!("after the loss: {:.2} s", elapsed.as_secs_f64());
    let Ok(result) = after else {
        panic!("a render on a lost device panicked");
    };
    let Err(error) = result else {
        panic!("a render on a lost device returned an image");
    };
    let message = error.to_string();
    println!("error: {message}");
    assert!(!message.contains('\n'), "{message}");
    assert!(elapsed < Duration::from_secs(10), "{elapsed:?}");
}
