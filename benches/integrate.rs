//! Integration stages: every segment method on the CPU (segments/s) and the
//! Psi table build (table entries/s).
//!
//! `cargo bench --bench integrate`; save a baseline with
//! `cargo bench --bench integrate -- --save-baseline NAME`, compare with
//! `-- --baseline NAME`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use tetray_integrate::TransferFunction;
use tetray_integrate::{GammaSpacing, IntegratorOptions, Method, PsiTable, ScalarIntegrator};

/// Segments per iteration: scalars spread over the transfer function's
/// range (so segments cross knots as they do in a frame), lengths of a
/// tenth to two unit distances.
const SEGMENTS: usize = 4096;

fn segments() -> Vec<(f32, f32, f32)> {
    // A fixed low-discrepancy sequence: the same work every run.
    let frac = |x: f64| (x - x.floor()) as f32;
    (0..SEGMENTS)
        .map(|i| {
            let i = i as f64;
            (
                frac(i * 0.618_033_988_7),
                frac(i * 0.414_213_562_3 + 0.3),
                0.1 + 1.9 * frac(i * 0.732_050_807_5),
            )
        })
        .collect()
}

fn segment_integrators(c: &mut Criterion) {
    let tf = TransferFunction::default_for_range(0.0, 1.0);
    let options = IntegratorOptions {
        riemann_step: 0.1,
        preintegration_length: 1.0,
        ..IntegratorOptions::default()
    };
    let work = segments();
    let mut group = c.benchmark_group("segment_integrators");
    group.throughput(Throughput::Elements(SEGMENTS as u64));
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    for method in Method::ALL {
        // The f64 references take milliseconds per segment: not a
        // renderer's method.
        if matches!(method, Method::Reference | Method::ReferenceOpacity) {
            continue;
        }
        let integrator = ScalarIntegrator::new(method, &tf, &options).expect("integrator");
        group.bench_function(BenchmarkId::from_parameter(method.name()), |b| {
            b.iter(|| {
                let mut sum = 0.0f32;
                for &(front, back, length) in &work {
                    let light = integrator.integrate(front, back, length);
                    sum += light.emitted.x + light.transmittance.x;
                }
                black_box(sum)
            })
        });
    }
    group.finish();
}

fn psi_table_build(c: &mut Criterion) {
    let mut group = c.benchmark_group("psi_table_build");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(3));
    for size in [64usize, 256] {
        group.throughput(Throughput::Elements((size * size) as u64));
        for spacing in [GammaSpacing::Uniform, GammaSpacing::Quadratic] {
            group.bench_with_input(BenchmarkId::new(spacing.name(), size), &size, |b, &size| {
                b.iter(|| PsiTable::build(size, spacing).expect("table"))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, segment_integrators, psi_table_build);
criterion_main!(benches);
