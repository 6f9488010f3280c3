//! Max bilinear-lookup error of Psi tables against the f64 value.
use tetray_integrate::psi::psi;
use tetray_integrate::{GammaSpacing, PsiTable};

fn main() {
    let n: usize = std::env::args().nth(1).map_or(1024, |s| s.parse().unwrap());
    let m: usize = std::env::args().nth(2).map_or(600, |s| s.parse().unwrap());
    for spacing in [GammaSpacing::Uniform, GammaSpacing::Quadratic] {
        let t = std::time::Instant::now();
        let table = PsiTable::build(n, spacing).unwrap();
        let build = t.elapsed();
        let mut worst = (0.0f64, 0.0, 0.0);
        let mut worst_nearest = 0.0f64;
        let golden = 0.618_033_988_749_895;
        for i in 0..m {
            for j in 0..m {
                let gb = ((i as f64 + golden) / m as f64).min(1.0);
                let gf = ((j as f64 + golden * golden) / m as f64).min(1.0);
                let exact = psi(gb / (1.0 - gb), gf / (1.0 - gf));
                let got = f64::from(table.lookup_gamma(gb as f32, gf as f32));
                let e = (got - exact).abs();
                if e > worst.0 {
                    worst = (e, gb, gf);
                }
                let near = f64::from(table.lookup_gamma_nearest(gb as f32, gf as f32));
                worst_nearest = worst_nearest.max((near - exact).abs());
            }
        }
        println!(
            "{spacing:?} n={n} build {build:?}: bilinear max {:.3e} at ({:.5}, {:.5}); nearest max {worst_nearest:.3e}",
            worst.0, worst.1, worst.2
        );
    }
}
