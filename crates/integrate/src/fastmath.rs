//! Inlinable exponentials for the per-segment kernels: the platform's `expf`
//! and `exp` are library calls that the inner loops cannot inline, schedule
//! around or vectorize. The f32 one is accurate to 2 ulp (tested against
//! f64), the f64 one to 2 ulp of f64. And minimum, maximum and
//! clamp by plain comparisons for the inner loops: `f32::min`, `max` and
//! `clamp` spend three more instructions per call on NaN handling.

use glam::Vec4;

/// `1 / ln 2`, and `ln 2` split so that `k * LN2_HI` is exact for |k| < 2^10.
const LOG2_E: f32 = std::f32::consts::LOG2_E;
const LN2_HI: f32 = 0.693_145_75;
const LN2_LO: f32 = 1.428_606_8e-6;
/// `1.5 * 2^23`: adding and subtracting it rounds to the nearest integer.
const ROUNDER: f32 = 12_582_912.0;

/// `e^x` in f32. Below -87 it returns 0 (`e^-87` is under 2e-38), above 88
/// infinity; NaN stays NaN.
#[inline(always)]
pub fn exp_f32(x: f32) -> f32 {
    if x < -87.0 {
        return 0.0;
    }
    if x > 88.0 {
        return f32::INFINITY;
    }
    exp_in_range(x)
}

/// [`exp_f32`] without a branch, the same bits for every input: the
/// polynomial runs for every `x` and the out-of-range results are selected
/// after it, so that a loop of these over several segments vectorizes.
#[inline(always)]
pub fn exp_f32_select(x: f32) -> f32 {
    let v = exp_in_range(x);
    let v = if x > 88.0 { f32::INFINITY } else { v };
    if x < -87.0 { 0.0 } else { v }
}

/// `e^x` for `x` in `[-87, 88]` (and NaN); other `x` give anything.
#[inline(always)]
fn exp_in_range(x: f32) -> f32 {
    // x = k ln 2 + r, |r| <= ln 2 / 2 (Cody-Waite reduction).
    let rounded = x * LOG2_E + ROUNDER;
    let kf = rounded - ROUNDER;
    let r = (x - kf * LN2_HI) - kf * LN2_LO;
    // Taylor to r^7: truncation below 5e-9 relative for |r| <= 0.347.
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0
                    + r * (1.0 / 24.0
                        + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    // 2^k by building the exponent bits (k in [-126, 127] here), `k` from
    // the low bits of the rounded sum (exact for |k| < 2^22, with no
    // float-to-int conversion, so that it vectorizes).
    let k = rounded.to_bits().wrapping_sub(ROUNDER.to_bits());
    p * f32::from_bits(k.wrapping_add(127) << 23)
}

/// `1 / ln 2` in f64, and `ln 2 = LN2_HI_F64 + LN2_LO_F64` to about
/// `2^-90`, `LN2_HI_F64` with its low 21 bits zero so that `k * LN2_HI_F64`
/// is exact for `|k| < 2^11`.
const LOG2_E_F64: f64 = std::f64::consts::LOG2_E;
const LN2_HI_F64: f64 = 0.6931471803691238;
const LN2_LO_F64: f64 = 1.9082149292705877e-10;
/// `1.5 * 2^52`: adding and subtracting it rounds to the nearest integer.
const ROUNDER_F64: f64 = 6_755_399_441_055_744.0;
/// `1 / n!` for `n = 0..=13`.
const INVERSE_FACTORIALS: [f64; 14] = inverse_factorials();

const fn inverse_factorials<const N: usize>() -> [f64; N] {
    let mut terms = [0.0; N];
    let mut factorial = 1.0;
    let mut n = 0;
    while n < N {
        if n > 0 {
            factorial *= n as f64;
        }
        terms[n] = 1.0 / factorial;
        n += 1;
    }
    terms
}

/// `e^x` in f64 for `x <= 709`, without a branch (so that a loop of these
/// over several segments vectorizes): 0 below -708, where `e^x` is under
/// `4e-308` (an f32 weight sees nothing of it); NaN stays NaN. Separate
/// multiplications and additions, so the bits are the same with or
/// without fused multiply-add hardware.
#[inline(always)]
pub fn exp_f64_select(x: f64) -> f64 {
    // x = k ln 2 + r, |r| <= ln 2 / 2 (Cody-Waite reduction).
    let rounded = x * LOG2_E_F64 + ROUNDER_F64;
    let kf = rounded - ROUNDER_F64;
    let r = (x - kf * LN2_HI_F64) - kf * LN2_LO_F64;
    // Taylor to r^13: truncation below 5e-18 relative for |r| <= 0.347.
    let p = horner(&INVERSE_FACTORIALS, r);
    // 2^k from the exponent bits (k in [-1022, 1023] here), `k` from the
    // low bits of the rounded sum.
    let k = rounded.to_bits().wrapping_sub(ROUNDER_F64.to_bits());
    let v = p * f64::from_bits(k.wrapping_add(1023) << 52);
    if x < -708.0 { 0.0 } else { v }
}

/// `sum_k terms[k] v^k` by Horner's rule from the last term, in separate
/// multiplications and additions: the same bits with or without fused
/// multiply-add hardware (without it, `mul_add` is a library call several
/// times slower). Zero for no terms.
#[inline(always)]
pub fn horner(terms: &[f64], v: f64) -> f64 {
    match terms.split_last() {
        Some((&last, rest)) => rest.iter().rev().fold(last, |sum, &t| sum * v + t),
        None => 0.0,
    }
}

/// `f` of the lanes of `a` and `b`, four at a time in a `Vec4` (SSE or
/// AVX operations, whatever the compiler makes of plain loops; a last
/// partial group is padded with zeros).
#[inline(always)]
pub fn by_fours<const N: usize>(
    a: &[f32; N],
    b: &[f32; N],
    f: impl Fn(Vec4, Vec4) -> Vec4,
) -> [f32; N] {
    let mut out = [0.0; N];
    for start in (0..N).step_by(4) {
        let four = |v: &[f32; N]| {
            Vec4::from_array(std::array::from_fn(|k| {
                v.get(start + k).copied().unwrap_or(0.0)
            }))
        };
        let result = f(four(a), four(b)).to_array();
        for (o, r) in out[start..].iter_mut().zip(result) {
            *o = r;
        }
    }
    out
}

/// The smaller of `a` and `b` by one comparison (`a` when they are
/// unordered).
#[inline(always)]
pub fn min_f32(a: f32, b: f32) -> f32 {
    if b < a { b } else { a }
}

/// The larger of `a` and `b` by one comparison (`a` when they are
/// unordered).
#[inline(always)]
pub fn max_f32(a: f32, b: f32) -> f32 {
    if b > a { b } else { a }
}

/// `x` clamped into `[lo, hi]` (`lo <= hi`, or either bound NaN, which
/// then bounds nothing) by plain comparisons: a NaN `x` stays NaN, as with
/// `f32::clamp`, which would also panic on a bad range. Written as a
/// `max_f32` and a `min_f32`, each one SSE instruction (whose NaN rule
/// keeps `x`), where a chain of two tests compiles to branches.
#[inline(always)]
pub fn clamp_f32(x: f32, lo: f32, hi: f32) -> f32 {
    min_f32(max_f32(x, lo), hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_f64_exp_to_two_ulp() {
        let mut worst = 0.0f64;
        let n = 2_000_000;
        for i in 0..=n {
            let x = -87.0 + 175.0 * (i as f64 / n as f64);
            let x = x as f32;
            let want = f64::from(x).exp();
            let got = f64::from(exp_f32(x));
            worst = worst.max(((got - want) / want).abs());
        }
        // 2 ulp of f32 is 2.4e-7 relative.
        assert!(worst < 2.4e-7, "max relative error {worst}");
        assert_eq!(exp_f32(0.0), 1.0);
        assert_eq!(exp_f32(-100.0), 0.0);
        assert_eq!(exp_f32(100.0), f32::INFINITY);
        assert!(exp_f32(f32::NAN).is_nan());
    }

    /// Against the platform's `exp` (correctly rounded but in rare
    /// cases): within 2 units in the last place from -708 to 709, exact
    /// at 0, and the ends as documented.
    #[test]
    fn f64_exponential_within_two_ulp() {
        let n = 2_000_000;
        let mut worst = 0u64;
        for i in 0..=n {
            let x = -708.0 + 1417.0 * (f64::from(i) / f64::from(n));
            let (got, want) = (exp_f64_select(x), x.exp());
            worst = worst.max(got.to_bits().abs_diff(want.to_bits()));
        }
        for x in [-1e-300, -1e-17, -0.346, 0.346, -87.3, -0.5] {
            let (got, want) = (exp_f64_select(x), x.exp());
            worst = worst.max(got.to_bits().abs_diff(want.to_bits()));
        }
        assert!(worst <= 2, "{worst} ulp");
        assert_eq!(exp_f64_select(0.0), 1.0);
        assert_eq!(exp_f64_select(-708.01), 0.0);
        assert_eq!(exp_f64_select(f64::NEG_INFINITY), 0.0);
        assert!(exp_f64_select(f64::NAN).is_nan());
    }

    #[test]
    fn the_branch_free_exponential_gives_the_same_bits() {
        let mut x = vec![
            0.0f32,
            -0.0,
            -87.0,
            -87.000_01,
            88.0,
            88.000_01,
            -1e30,
            1e30,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MIN_POSITIVE,
        ];
        let n = 400_000;
        x.extend((0..=n).map(|i| (-100.0 + 200.0 * (i as f64 / n as f64)) as f32));
        for x in x {
            assert_eq!(
                exp_f32_select(x).to_bits(),
                exp_f32(x).to_bits(),
                "exp({x})"
            );
        }
    }

    #[test]
    fn plain_comparisons_agree_with_std_on_ordered_values() {
        let values = [-3.5f32, -0.0, 0.0, 0.25, 1.0, 7.0, f32::INFINITY];
        for &a in &values {
            for &b in &values {
                assert_eq!(min_f32(a, b), a.min(b), "min {a} {b}");
                assert_eq!(max_f32(a, b), a.max(b), "max {a} {b}");
                if a <= b {
                    for &x in &values {
                        assert_eq!(clamp_f32(x, a, b), x.clamp(a, b), "clamp {x} {a} {b}");
                    }
                }
            }
        }
        assert!(clamp_f32(f32::NAN, 0.0, 1.0).is_nan());
    }

    /// The clamp gives the bits of the two tests in turn (`lo` below it,
    /// `hi` above it, else `x`), signed zeros and NaN included, wherever
    /// `lo <= hi` or a bound is NaN.
    #[test]
    fn clamp_has_the_bits_of_two_tests() {
        let values = [
            f32::NEG_INFINITY,
            -3.5,
            -0.0,
            0.0,
            1e-30,
            0.25,
            1.0,
            7.0,
            f32::INFINITY,
            f32::NAN,
        ];
        let tests = |x: f32, lo: f32, hi: f32| {
            if x < lo {
                lo
            } else if x > hi {
                hi
            } else {
                x
            }
        };
        for &lo in &values {
            for &hi in &values {
                if lo > hi {
                    continue;
                }
                for &x in &values {
                    let (got, want) = (clamp_f32(x, lo, hi), tests(x, lo, hi));
                    assert!(
                        got.to_bits() == want.to_bits() || got.is_nan() && want.is_nan(),
                        "clamp {x} {lo} {hi}: {got} against {want}"
                    );
                }
            }
        }
    }
}
