//! The Psi table (dissertation section 5.2): bilinear lookup against the f64
//! value over a dense grid, its exact corners and limits, and why its nodes
//! are not uniform in gamma.

use tetray_integrate::exact::exact_zeta_psi;
use tetray_integrate::psi::psi;
use tetray_integrate::{GammaSpacing, PsiTable};

/// `tau D` of gamma (eq. 5.9 inverted), infinite at 1.
fn tau_d(gamma: f64) -> f64 {
    if gamma >= 1.0 {
        f64::INFINITY
    } else {
        gamma / (1.0 - gamma)
    }
}

const GOLDEN: f64 = 0.618_033_988_749_895;

/// A dense grid of gammas that falls between the nodes (irrational
/// offsets), with both ends.
fn dense_gammas(n: usize) -> Vec<f64> {
    let mut g: Vec<f64> = (0..n).map(|i| (i as f64 + GOLDEN) / n as f64).collect();
    g.extend([0.0, 1.0]);
    g
}

/// The dense grid plus points crowding the opaque edges, down to
/// `1 - gamma = 6e-8` (`tau D = 1.6e7`).
fn edge_gammas(n: usize) -> Vec<f64> {
    let mut g = dense_gammas(n);
    g.extend((1..=7).map(|k| 1.0 - 10f64.powi(-k) * GOLDEN));
    g
}

/// Max |bilinear lookup - f64 Psi| over `gammas` squared.
fn max_bilinear_error(table: &PsiTable, gammas: &[f64]) -> (f64, f64, f64) {
    let mut worst = (0.0, 0.0, 0.0);
    for &gb in gammas {
        for &gf in gammas {
            // The f32 gamma the lookup sees, so only the table is measured.
            let (b, f) = (gb as f32, gf as f32);
            let want = psi(tau_d(f64::from(b)), tau_d(f64::from(f)));
            let got = f64::from(table.lookup_gamma(b, f));
            let e = (got - want).abs();
            if e > worst.0 {
                worst = (e, gb, gf);
            }
        }
    }
    worst
}

#[test]
fn bilinear_lookup_is_within_1e5_everywhere() {
    let table = PsiTable::shared(1024).unwrap();
    assert_eq!(table.spacing(), GammaSpacing::Quadratic);
    let (e, gb, gf) = max_bilinear_error(&table, &dense_gammas(500));
    eprintln!("1024^2 quadratic table: max bilinear error {e:.3e} at ({gb}, {gf})");
    // Measured 1.03e-6: interpolation (h^2/8 |Psi''| in the warped
    // coordinate) plus f32 rounding of the stored values.
    assert!(e < 1e-5, "max error {e} at ({gb}, {gf})");
}

#[test]
fn extremely_opaque_corner_stays_within_3e4() {
    // Where both ends are extremely opaque (tau_b D > 1e6, tau_f D > 1e3)
    // Psi < 1e-3 changes over w_b ~ w_f^2 (see GammaSpacing::Quadratic):
    // finer than one table cell. Measured 1.1e-4.
    let table = PsiTable::shared(1024).unwrap();
    let (e, gb, gf) = max_bilinear_error(&table, &edge_gammas(100));
    eprintln!("1024^2 quadratic table with edges: max bilinear error {e:.3e} at ({gb}, {gf})");
    assert!(e < 3e-4, "max error {e} at ({gb}, {gf})");
    if e > 1e-5 {
        assert!(
            gb > 0.999 && gf > 0.999,
            "large error away from the corner: ({gb}, {gf})"
        );
    }
}

#[test]
fn uniform_gamma_nodes_cannot_reach_1e5_near_the_opaque_back() {
    // The dissertation's table: nodes uniform in gamma. Near gamma_b = 1,
    // Psi(a, 0) ~ sqrt(pi / 2a) ~ sqrt(pi (1 - gamma_b) / 2): a square root
    // whose curvature no uniform grid resolves. This is why the default
    // table warps its nodes (GammaSpacing::Quadratic).
    let uniform = PsiTable::build(1024, GammaSpacing::Uniform).unwrap();
    let (e, gb, _) = max_bilinear_error(&uniform, &dense_gammas(600));
    eprintln!("1024^2 uniform table: max bilinear error {e:.3e} at gamma_b {gb}");
    assert!(e > 1e-3 && gb > 0.99, "{e} at {gb}");
    assert!(e < 1e-2);
    let quadratic = PsiTable::shared(1024).unwrap();
    let (q, _, _) = max_bilinear_error(&quadratic, &dense_gammas(600));
    assert!(q < e / 100.0, "quadratic {q} vs uniform {e}");
}

#[test]
fn bilinear_beats_nearest() {
    let table = PsiTable::build(256, GammaSpacing::Quadratic).unwrap();
    let gammas = dense_gammas(150);
    let (mut bilinear, mut nearest) = (0.0f64, 0.0f64);
    for &gb in &gammas {
        for &gf in &gammas {
            let want = psi(tau_d(gb), tau_d(gf));
            let (b, f) = (gb as f32, gf as f32);
            bilinear = bilinear.max((f64::from(table.lookup_gamma(b, f)) - want).abs());
            nearest = nearest.max((f64::from(table.lookup_gamma_nearest(b, f)) - want).abs());
        }
    }
    eprintln!("256^2: nearest {nearest:.3e}, bilinear {bilinear:.3e}");
    assert!(bilinear < nearest / 20.0, "{bilinear} vs {nearest}");
}

#[test]
fn corners_and_limits() {
    // Psi(0, 0) = 1: a transparent segment passes all its own light.
    assert_eq!(psi(0.0, 0.0), 1.0);
    let table = PsiTable::shared(1024).unwrap();
    assert_eq!(table.lookup_gamma(0.0, 0.0), 1.0);
    assert_eq!(table.lookup(0.0, 0.0), 1.0);
    // tau -> infinity at either end: nothing reaches the eye from inside.
    for g in [0.0, 0.3, 0.9, 1.0] {
        assert_eq!(table.lookup_gamma(1.0, g), 0.0);
        assert_eq!(table.lookup_gamma(g, 1.0), 0.0);
        assert_eq!(table.lookup(f32::INFINITY, g), 0.0);
    }
    // The approach to the limits: Psi(a, 0) ~ sqrt(pi / (2a)) and
    // Psi(0, b) ~ 1/b for large optical depths.
    for big in [1e4f64, 1e6, 1e8] {
        let back = psi(big, 0.0) / (std::f64::consts::PI / (2.0 * big)).sqrt();
        let front = psi(0.0, big) * big;
        assert!((back - 1.0).abs() < 2.0 / big.sqrt(), "{big}: {back}");
        assert!((front - 1.0).abs() < 2.0 / big, "{big}: {front}");
    }
}

#[test]
fn psi_is_a_mean_transmittance() {
    // zeta <= Psi <= 1, decreasing in both optical depths.
    let depths = [0.0, 0.01, 0.3, 1.0, 2.5, 10.0, 100.0];
    for (i, &a) in depths.iter().enumerate() {
        for (j, &b) in depths.iter().enumerate() {
            let (zeta, p) = exact_zeta_psi(a, b);
            assert!(zeta <= p && p <= 1.0, "Psi({a}, {b}) = {p}, zeta {zeta}");
            if i > 0 {
                assert!(psi(depths[i - 1], b) >= p);
            }
            if j > 0 {
                assert!(psi(a, depths[j - 1]) >= p);
            }
        }
    }
}

#[test]
fn table_nodes_hold_the_f64_values() {
    let table = PsiTable::build(64, GammaSpacing::Quadratic).unwrap();
    let n = table.size();
    for i in [0, 1, 17, 40, 62, 63] {
        for j in [0, 5, 31, 63] {
            let want = psi(tau_d(table.node_gamma(i)), tau_d(table.node_gamma(j)));
            let got = table.values()[j * n + i];
            assert!(
                (f64::from(got) - want).abs() <= 6e-8 * want.max(1e-30),
                "node ({i}, {j})"
            );
        }
    }
    assert!(PsiTable::build(1, GammaSpacing::Quadratic).is_err());
    assert!(PsiTable::build(100_000, GammaSpacing::Quadratic).is_err());
}
