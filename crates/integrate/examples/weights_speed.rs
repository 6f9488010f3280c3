//! Throughput of the per-channel weight computations (ns per call).
use std::hint::black_box;
use std::time::Instant;
use tetray_integrate::PsiTable;
use tetray_integrate::average::average_weights;
use tetray_integrate::exact::exact_weights;
use tetray_integrate::ppi::ppi_weights;

fn main() {
    let size = std::env::var("PSI_SIZE").map_or(1024, |s| s.parse().unwrap());
    let table = PsiTable::shared(size).unwrap();
    let n = 20_000_000usize;
    let inputs: Vec<(f32, f32)> = (0..4096)
        .map(|i| {
            let a = ((i * 7919) % 4096) as f32 / 4096.0 * 0.6;
            let b = ((i * 104_729) % 4096) as f32 / 4096.0 * 0.6;
            (a, b)
        })
        .collect();
    let time = |name: &str, f: &dyn Fn(f32, f32) -> f32| {
        let t = Instant::now();
        let mut acc = 0.0f32;
        for i in 0..n {
            let (a, b) = inputs[i & 4095];
            acc += f(black_box(a), black_box(b));
        }
        black_box(acc);
        println!(
            "{name}: {:.2} ns/call",
            t.elapsed().as_secs_f64() * 1e9 / n as f64
        );
    };
    time("average", &|a, b| average_weights(a, b).psi);
    time("ppi", &|a, b| ppi_weights(&table, a, b).psi);
    time("ppi lookup only", &|a, b| table.lookup(a, b));
    time("exp", &|a, b| (-(a + b)).exp());
    time("sqrt+div", &|a, b| {
        1.0 / (1.0 + a).sqrt() + 1.0 / (1.0 + b).sqrt()
    });
    time("exact", &|a, b| exact_weights(a, b).psi);
}
