//! Special functions in f64 for the closed forms of the volume rendering
//! integral (dissertation section 3.2.3): the scaled complementary error
//! function `erfcx(x) = exp(x^2) erfc(x)` and Dawson's integral
//! `F(x) = exp(-x^2) int_0^x exp(t^2) dt`, plus Gauss-Legendre nodes.
//!
//! Both are written in the scaled form so that no `exp(x^2)` factor has to
//! cancel a tiny bracket: that cancellation is what makes eq. 3.19-3.20
//! unstable when evaluated literally.

use std::f64::consts::PI;
use std::sync::OnceLock;

/// `1 / sqrt(pi)`.
const FRAC_1_SQRT_PI: f64 = 0.564_189_583_547_756_3;

/// `exp(x^2) erfc(x)` for `x >= 0` (and finite negative `x` down to about
/// -26, where it overflows), to about 1e-15 relative.
pub fn erfcx(x: f64) -> f64 {
    if x.is_nan() {
        return f64::NAN;
    }
    if x < 26.0 {
        // x^2 split into hi + lo exactly, so exp(x^2) keeps full precision.
        let hi = x * x;
        let lo = x.mul_add(x, -hi);
        return hi.exp() * (1.0 + lo) * libm::erfc(x);
    }
    if x.is_infinite() {
        return 0.0;
    }
    // Asymptotic series: 1/(x sqrt(pi)) sum_k (-1)^k (2k-1)!! / (2x^2)^k.
    // At x >= 26 the seventh term is below 1e-17 relative.
    let inv_2x2 = 0.5 / (x * x);
    let mut term = 1.0;
    let mut sum = 1.0;
    for k in 1..=7 {
        term *= -f64::from(2 * k - 1) * inv_2x2;
        sum += term;
    }
    FRAC_1_SQRT_PI / x * sum
}

/// Dawson's integral `F(x) = exp(-x^2) int_0^x exp(t^2) dt`, odd in `x`, to
/// about 1e-15 relative.
///
/// Small `|x|`: its Maclaurin series. Otherwise Rybicki's exponentially
/// convergent sampling formula `F(x) ~ pi^-1/2 sum_{n odd} exp(-(x - n h)^2)
/// / n`, recentred on the even multiple of `h` nearest to `x` so that every
/// exponential stays bounded; with `h = 0.2` its error is about
/// `exp(-(pi / 2h)^2) = 1e-27`. Large `|x|`: the asymptotic series.
pub fn dawson(x: f64) -> f64 {
    if x.is_nan() {
        return f64::NAN;
    }
    let (sign, x) = if x < 0.0 { (-1.0, -x) } else { (1.0, x) };
    sign * dawson_nonnegative(x)
}

fn dawson_nonnegative(x: f64) -> f64 {
    const H: f64 = 0.2;
    const PAIRS: usize = 17;
    if x < 0.2 {
        // x sum_n (-2 x^2)^n / (2n+1)!!
        let x2 = x * x;
        let mut term = x;
        let mut sum = x;
        let mut n = 1.0;
        while term.abs() > 1e-18 * sum.abs() {
            term *= -2.0 * x2 / (2.0 * n + 1.0);
            sum += term;
            n += 1.0;
        }
        return sum;
    }
    if x > 1e4 {
        if x.is_infinite() {
            return 0.0;
        }
        // F(x) ~ 1/(2x) sum_k (2k-1)!! / (2x^2)^k.
        let inv_2x2 = 0.5 / (x * x);
        return 0.5 / x * (1.0 + inv_2x2 + 3.0 * inv_2x2 * inv_2x2);
    }
    static WEIGHTS: OnceLock<[f64; PAIRS]> = OnceLock::new();
    let weights = WEIGHTS.get_or_init(|| {
        std::array::from_fn(|k| {
            let m = (2 * k + 1) as f64;
            (-(m * H) * (m * H)).exp()
        })
    });
    let n0 = 2.0 * (0.5 * x / H).round();
    let xp = x - n0 * H;
    let e_step = (4.0 * H * xp).exp();
    let mut e1 = (2.0 * H * xp).exp();
    let (mut d1, mut d2) = (n0 + 1.0, n0 - 1.0);
    let mut sum = 0.0;
    for &w in weights {
        sum += w * (e1 / d1 + 1.0 / (d2 * e1));
        d1 += 2.0;
        d2 -= 2.0;
        e1 *= e_step;
    }
    FRAC_1_SQRT_PI * (-xp * xp).exp() * sum
}

/// Nodes and weights of the 16-point Gauss-Legendre rule on `[-1, 1]`.
pub fn gauss_legendre_16() -> &'static ([f64; 16], [f64; 16]) {
    static RULE: OnceLock<([f64; 16], [f64; 16])> = OnceLock::new();
    RULE.get_or_init(gauss_legendre::<16>)
}

/// The `N`-point Gauss-Legendre rule by Newton iteration on `P_N`.
fn gauss_legendre<const N: usize>() -> ([f64; N], [f64; N]) {
    let mut nodes = [0.0; N];
    let mut weights = [0.0; N];
    let n = N as f64;
    for i in 0..N {
        let mut x = (PI * (i as f64 + 0.75) / (n + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // P_N(x) and P_N'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=N {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1.0);
            let step = p1 / derivative;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    (nodes, weights)
}

/// `int_a^b f` by the 16-point Gauss-Legendre rule.
pub fn gauss_legendre_panel(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let (nodes, weights) = gauss_legendre_16();
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let mut sum = 0.0;
    for (x, w) in nodes.iter().zip(weights) {
        sum += w * f(mid + half * x);
    }
    sum * half
}

#[cfg(test)]
mod tests {
    use super::*;

    /// erfc by brute-force quadrature of exp(-t^2) on [x, x + 12] (f64).
    fn erfc_quadrature(x: f64) -> f64 {
        let panels = 400;
        let h = 12.0 / panels as f64;
        let mut sum = 0.0;
        for i in 0..panels {
            let a = x + i as f64 * h;
            sum += gauss_legendre_panel(a, a + h, |t| (-t * t).exp());
        }
        2.0 / PI.sqrt() * sum
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        let (nodes, weights) = gauss_legendre_16();
        assert!((weights.iter().sum::<f64>() - 2.0).abs() < 1e-14);
        // x^30 over [-1, 1] = 2/31 (degree 31 is the rule's limit).
        let value: f64 = nodes.iter().zip(weights).map(|(x, w)| w * x.powi(30)).sum();
        assert!((value - 2.0 / 31.0).abs() < 1e-14, "{value}");
    }

    #[test]
    fn erfcx_matches_quadrature_and_asymptotics() {
        for &x in &[0.0f64, 0.1, 0.5, 1.0, 2.0, 4.0, 8.0] {
            let expected = (x * x).exp() * erfc_quadrature(x);
            let got = erfcx(x);
            assert!(
                ((got - expected) / expected).abs() < 1e-13,
                "erfcx({x}) = {got}, quadrature {expected}"
            );
        }
        // Continuity across the switch to the asymptotic series.
        let below = erfcx(26.0 - 1e-12);
        let above = erfcx(26.0);
        assert!(((below - above) / above).abs() < 1e-13);
        // erfcx(x) ~ 1 / (x sqrt(pi)) for large x.
        let x = 1e8;
        assert!((erfcx(x) * x * PI.sqrt() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn dawson_matches_its_defining_integral() {
        for &x in &[0.05, 0.19, 0.2, 0.21, 0.5, 0.9241388, 1.5, 3.0, 7.0, 20.0] {
            // exp(-x^2) int_0^x exp(t^2) dt = int_0^x exp((t - x)(t + x)) dt.
            let panels = 64;
            let h = x / panels as f64;
            let mut expected = 0.0;
            for i in 0..panels {
                let a = i as f64 * h;
                expected += gauss_legendre_panel(a, a + h, |t| ((t - x) * (t + x)).exp());
            }
            let got = dawson(x);
            assert!(
                ((got - expected) / expected).abs() < 1e-13,
                "F({x}) = {got}, quadrature {expected}"
            );
            assert_eq!(dawson(-x), -got);
        }
        // The maximum of F is 0.5410442246 at x = 0.9241388730.
        assert!((dawson(0.924_138_873_0) - 0.541_044_224_6).abs() < 1e-10);
        assert!((dawson(2e4) * 4e4 - 1.0).abs() < 1e-8);
    }
}
