//! Special functions in f64 for the closed forms of the volume rendering
//! integral (dissertation section 3.2.3): the scaled complementary error
//! function `erfcx(x) = exp(x^2) erfc(x)` and Dawson's integral
//! `F(x) = exp(-x^2) int_0^x exp(t^2) dt`, plus Gauss-Legendre nodes.
//!
//! Both are written in the scaled form so that no `exp(x^2)` factor has to
//! cancel a tiny bracket: that cancellation is what makes eq. 3.19-3.20
//! unstable when evaluated literally.
//!
//! Each comes twice. The reference forms ([`erfcx_reference`],
//! [`dawson_reference`]) follow the definitions closely and cost several
//! exponentials and divisions per call. The forms the exact integrator
//! calls ([`erfcx`], [`dawson`]) are piecewise polynomials fitted once to
//! the reference forms on `[0, 12)` (intervals of width 1/4, degree 12),
//! a short Maclaurin sum for Dawson's integral below 1/4 and the asymptotic
//! series from 12 on: a Horner sum each, within 6e-16 relative of the true
//! values (the reference forms: within 7e-16; see the tests).

use std::f64::consts::PI;
use std::sync::OnceLock;

use crate::fastmath::horner;
use crate::piecewise::Piecewise;

/// `1 / sqrt(pi)`.
const FRAC_1_SQRT_PI: f64 = 0.564_189_583_547_756_3;

/// Where the fits end and the asymptotic series take over: at 12 their
/// first omitted terms, `(2k - 1)!! / 288^k` for `k = 13`, are below
/// `1e-19` of the sums.
const FIT_END: f64 = 12.0;
/// Intervals per unit, intervals, and coefficients (degree + 1) of a fit.
const PER_UNIT: f64 = 4.0;
const INTERVALS: usize = 48;
const COEFFICIENTS: usize = 13;

type Fit = Piecewise<COEFFICIENTS, INTERVALS>;

/// The fits of erfcx and of Dawson's integral on `[0, FIT_END)`.
fn fits() -> &'static (Fit, Fit) {
    static FITS: OnceLock<(Fit, Fit)> = OnceLock::new();
    FITS.get_or_init(|| {
        let erfcx = Fit::fit(erfcx_reference, 0.0, PER_UNIT);
        let dawson = Fit::fit(dawson_reference, 0.0, PER_UNIT);
        debug_assert_eq!(erfcx.end(), FIT_END);
        (erfcx, dawson)
    })
}

/// `(2k - 1)!!` for `k = 0..N`, with alternating signs if `alternate`:
/// the coefficients of the asymptotic series in `1 / (2 x^2)`.
const fn double_factorials<const N: usize>(alternate: bool) -> [f64; N] {
    let mut terms = [0.0; N];
    let mut product = 1.0;
    let mut k = 0;
    while k < N {
        if k > 0 {
            product *= (2 * k - 1) as f64;
        }
        terms[k] = if alternate && k % 2 == 1 {
            -product
        } else {
            product
        };
        k += 1;
    }
    terms
}

/// `exp(x^2) erfc(x)`, within 6e-16 relative for `x >= 0`; negative `x`
/// takes [`erfcx_reference`].
#[inline]
pub fn erfcx(x: f64) -> f64 {
    const ASYMPTOTIC: [f64; 13] = double_factorials(true);
    if (0.0..FIT_END).contains(&x) {
        fits().0.eval(x)
    } else if x >= FIT_END {
        // 1/(x sqrt(pi)) sum_k (-1)^k (2k-1)!! / (2x^2)^k; zero at infinity.
        FRAC_1_SQRT_PI / x * horner(&ASYMPTOTIC, 0.5 / (x * x))
    } else {
        erfcx_reference(x)
    }
}

/// Dawson's integral, odd in `x`, within 6e-16 relative.
#[inline]
pub fn dawson(x: f64) -> f64 {
    const ASYMPTOTIC: [f64; 13] = double_factorials(false);
    const MACLAURIN: [f64; 11] = maclaurin_terms();
    let ax = x.abs();
    let f = if ax < 0.25 {
        // x sum_n (-2 x^2)^n / (2n+1)!!: at 1/4 the first omitted term is
        // below 1e-19 of the sum.
        ax * horner(&MACLAURIN, -2.0 * ax * ax)
    } else if ax < FIT_END {
        fits().1.eval(ax)
    } else if ax.is_nan() {
        return f64::NAN;
    } else {
        // 1/(2x) sum_k (2k-1)!! / (2x^2)^k; zero at infinity.
        0.5 / ax * horner(&ASYMPTOTIC, 0.5 / (ax * ax))
    };
    f.copysign(x)
}

/// `1 / (2n+1)!!` for `n = 0..N`.
const fn maclaurin_terms<const N: usize>() -> [f64; N] {
    let mut terms = [0.0; N];
    let mut product = 1.0;
    let mut n = 0;
    while n < N {
        product *= (2 * n + 1) as f64;
        terms[n] = 1.0 / product;
        n += 1;
    }
    terms
}

/// `exp(x^2) erfc(x)` for `x >= 0` (and finite negative `x` down to about
/// -26, where it overflows), to about 1e-15 relative.
pub fn erfcx_reference(x: f64) -> f64 {
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
pub fn dawson_reference(x: f64) -> f64 {
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

    /// Dawson's integral and erfcx at 17 and 15 points, correctly rounded:
    /// their Maclaurin series (or the asymptotic series above 20) summed in
    /// 260-digit decimal arithmetic, rounded once to f64.
    const DAWSON: [(f64, f64); 17] = [
        (0.001, 0.0009999993333336),
        (0.1, 0.09933599239785286),
        (0.2499, 0.2397511509229938),
        (0.26234, 0.25062837896127366),
        (0.5, 0.4244363835020223),
        (0.924138873, 0.5410442246351816),
        (1.3, 0.4833975173848241),
        (2.0, 0.30134038892379195),
        (3.763695, 0.13815578905536083),
        (5.5, 0.09249323231075476),
        (7.9, 0.0638109032198449),
        (10.107305, 0.04971493810215809),
        (11.999, 0.04181638578445126),
        (12.0, 0.04181287645398826),
        (15.0, 0.033407906808639226),
        (30.0, 0.016675941401059175),
        (1000.0, 0.000500000250000375),
    ];
    const ERFCX: [(f64, f64); 15] = [
        (0.0, 1.0),
        (0.001, 0.9988726200811514),
        (0.1, 0.8964569799691267),
        (0.5, 0.6156903441929259),
        (1.0, 0.427583576155807),
        (1.824355, 0.27553288651991126),
        (3.99542, 0.137147930842568),
        (4.0, 0.13699945762506138),
        (6.3, 0.08846589935285219),
        (9.9, 0.05670245693883227),
        (11.999, 0.04685809919752628),
        (12.0, 0.04685422101489376),
        (15.0, 0.03752960638850576),
        (30.0, 0.01879588886141675),
        (1000.0, 0.0005641893014533876),
    ];

    /// The fitted forms within 6e-16 relative of the high-precision values
    /// (at most 2 units in the last place; 5.2e-16, at 1/2, is at an
    /// interval's end, where a fit's error peaks), the reference forms
    /// within 7e-16 (their exponentials and long sums round more).
    #[test]
    fn both_forms_match_high_precision_values() {
        for (x, want) in DAWSON {
            let fitted = ((dawson(x) - want) / want).abs();
            let reference = ((dawson_reference(x) - want) / want).abs();
            assert!(fitted < 6e-16, "F({x}): fitted {fitted:e}");
            assert!(reference < 7e-16, "F({x}): reference {reference:e}");
        }
        for (x, want) in ERFCX {
            let fitted = ((erfcx(x) - want) / want).abs();
            let reference = ((erfcx_reference(x) - want) / want).abs();
            assert!(fitted < 6e-16, "erfcx({x}): fitted {fitted:e}");
            assert!(reference < 7e-16, "erfcx({x}): reference {reference:e}");
        }
    }

    /// The fitted forms against the reference forms on a dense grid over
    /// every branch (and across each interval's ends): within 2e-15
    /// relative, the two forms' errors against the true values (up to
    /// 7e-16 for the reference forms, 6e-16 for the fitted ones, see
    /// above) together with some slack; odd, zero at infinity and NaN for
    /// NaN, as the reference forms are.
    #[test]
    fn fitted_forms_match_the_reference_forms() {
        let mut worst = (0.0f64, 0.0f64);
        for i in 0..=200_000 {
            let x = 13.0 * f64::from(i) / 200_000.0;
            for x in [x, x + 1e-13, (x - 1e-13).max(0.0)] {
                let (e, r) = (erfcx(x), erfcx_reference(x));
                worst.0 = worst.0.max(((e - r) / r).abs());
                let (d, r) = (dawson(x), dawson_reference(x));
                if x > 0.0 {
                    worst.1 = worst.1.max(((d - r) / r).abs());
                }
                assert_eq!(dawson(-x).to_bits(), (-d).to_bits());
            }
        }
        // 8.6e-16 and 1.6e-15 on this grid.
        assert!(worst.0 < 2e-15 && worst.1 < 2e-15, "{worst:?}");
        assert!(erfcx(f64::NAN).is_nan() && dawson(f64::NAN).is_nan());
        assert_eq!(erfcx(f64::INFINITY), 0.0);
        assert_eq!(dawson(f64::INFINITY), 0.0);
        assert_eq!(dawson(f64::NEG_INFINITY), 0.0);
        assert_eq!(dawson(1e-300), 1e-300);
        assert_eq!(erfcx(-1.0), erfcx_reference(-1.0));
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
