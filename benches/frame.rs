//! Full frames of the Blunt Fin (128 x 128, partial pre-integration): the
//! CPU ray caster by wall clock, the GPU ray caster by GPU timestamp
//! queries (`iter_custom` sums the pass times). Throughput: rays (pixels).
//! Without an adapter the GPU group is skipped with a message.

use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use tetray_gpu::{GpuContext, GpuIntegrator, GpuRaycaster, GpuRenderOptions, GpuScene};
use tetray_integrate::Method;
use tetray_raycast::{RenderOptions, render_scalar};

mod support;

const EDGE: u32 = 128;

fn cpu_frame(c: &mut Criterion) {
    let scene = support::blunt_fin();
    let camera = support::camera(&scene);
    let mut group = c.benchmark_group("cpu_frame");
    group.throughput(Throughput::Elements(u64::from(EDGE * EDGE)));
    group.sample_size(20);
    group.measurement_time(Duration::from_secs(4));
    let options = RenderOptions {
        width: EDGE,
        height: EDGE,
        ..RenderOptions::default()
    };
    for method in [Method::Ppi, Method::Exact, Method::Average] {
        let integrator = support::integrator(&scene, method);
        group.bench_function(format!("blunt_fin_{EDGE}_{method}"), |b| {
            b.iter(|| render_scalar(&scene, &camera, &integrator, &options).expect("frame"))
        });
    }
    group.finish();
}

fn gpu_frame(c: &mut Criterion) {
    let ctx = match GpuContext::new() {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("gpu_frame: skipped, no adapter ({e})");
            return;
        }
    };
    eprintln!(
        "gpu_frame: {} ({})",
        ctx.adapter_name(),
        if ctx.timestamps {
            "timestamp queries"
        } else {
            "no timestamps: wall clock"
        }
    );
    let raycaster = GpuRaycaster::new(&ctx).expect("kernel");
    let scene = support::blunt_fin();
    let camera = support::camera(&scene);
    let gpu_scene = GpuScene::new(&ctx, &scene).expect("upload");
    let options = GpuRenderOptions {
        width: EDGE,
        height: EDGE,
        ..GpuRenderOptions::default()
    };
    let mut group = c.benchmark_group("gpu_frame");
    group.throughput(Throughput::Elements(u64::from(EDGE * EDGE)));
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(5));
    for method in [Method::Ppi, Method::Exact, Method::Average] {
        let integrator =
            GpuIntegrator::new(&ctx, &support::integrator(&scene, method)).expect("upload");
        group.bench_function(format!("blunt_fin_{EDGE}_{method}"), |b| {
            b.iter_custom(|iters| {
                (0..iters)
                    .map(|_| {
                        raycaster
                            .render(&ctx, &gpu_scene, &integrator, &camera, &options)
                            .expect("frame")
                            .stats
                            .frame_time()
                    })
                    .sum()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, cpu_frame, gpu_frame);
criterion_main!(benches);
