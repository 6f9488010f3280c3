//! Linear luminance and attenuation in closed form (Williams, Max and Stein;
//! dissertation eq. 3.28), evaluated in f64 through eq. 5.5:
//! `I = I_0 zeta + L_b (Psi - zeta) + L_f (1 - Psi)`, which is eq. 3.28
//! regrouped by luminance, with `zeta = exp(-(a + b)/2)` and Psi in the
//! numerically stable scaled forms below (`a = tau_b D`, `b = tau_f D`,
//! `c = (a - b)/2`):
//!
//! - back more opaque (`c > 0`, the erf branch, eq. 3.25), with
//!   `erf(B) - erf(A) = exp(-A^2) (erfcx(A) - exp(A^2 - B^2) erfcx(B))` and
//!   `A^2 - B^2 = -(a + b)/2`:
//!   `Psi = sqrt(pi) / (2 sqrt c) (erfcx(b / 2 sqrt c) - zeta erfcx(a / 2 sqrt c))`;
//! - front more opaque (`c < 0`, the Dawson branch, eq. 3.27), `k = sqrt(-c)`:
//!   `Psi = (F(b / 2k) - zeta F(a / 2k)) / k`;
//! - nearly constant attenuation (`|c|` small, eq. 3.21 and its neighbourhood):
//!   `Psi = sum_n (-c)^n / n! M_2n(b)` with the moments
//!   `M_k(b) = int_0^1 x^k exp(-b x) dx`; at `a = b = 0` this gives
//!   `Psi = 1`, `I = I_0` (the `tau D -> 0` limit).

use crate::fastmath::{exp_f64_select, horner};
use crate::segment::{SegmentLight, SegmentParams, Weights, light_from_weights};
use crate::special::{dawson, erfcx};

/// Below this `|c|` the series in `c` is used: its first omitted term is
/// below `|c|^5 / 120 / 11 < 1e-18`, while the closed forms' `1/sqrt|c|`
/// amplification of rounding stays below 32.
const SERIES_BELOW: f64 = 1e-3;

/// `sqrt(pi) / 2`.
const SQRT_PI_2: f64 = 0.886_226_925_452_758;

/// `(zeta, Psi)` in f64 for `a = tau_b D >= 0`, `b = tau_f D >= 0`.
pub fn exact_zeta_psi(a: f64, b: f64) -> (f64, f64) {
    out_of_domain(a, b).unwrap_or_else(|| {
        let zeta = exp_f64_select(-0.5 * (a + b));
        (zeta, psi_given_zeta(a, b, zeta))
    })
}

/// [`exact_zeta_psi`] where `a` or `b` is not a finite non-negative
/// number: NaN for a NaN or a negative value, `(0, 0)` (nothing passes)
/// for an infinity; `None` where the closed forms apply.
#[inline(always)]
fn out_of_domain(a: f64, b: f64) -> Option<(f64, f64)> {
    if a.is_nan() || b.is_nan() || a < 0.0 || b < 0.0 {
        Some((f64::NAN, f64::NAN))
    } else if a.is_infinite() || b.is_infinite() {
        Some((0.0, 0.0))
    } else {
        None
    }
}

/// Psi for finite `a, b >= 0` and `zeta = exp(-(a + b)/2)`: the series in
/// `c` or one of the two closed forms.
#[inline]
fn psi_given_zeta(a: f64, b: f64, zeta: f64) -> f64 {
    let c = 0.5 * (a - b);
    if c.abs() < SERIES_BELOW {
        psi_series(b, c, zeta)
    } else if c > 0.0 {
        let k = c.sqrt();
        SQRT_PI_2 / k * (erfcx(b / (2.0 * k)) - zeta * erfcx(a / (2.0 * k)))
    } else {
        let k = (-c).sqrt();
        (dawson(b / (2.0 * k)) - zeta * dawson(a / (2.0 * k))) / k
    }
}

/// Psi for small `|c|`: `sum_{n=0}^{4} (-c)^n / n! M_2n(b)`, given
/// `zeta = exp(-(b + c))` (`(a + b) / 2 = b + c`).
fn psi_series(b: f64, c: f64, zeta: f64) -> f64 {
    let m = even_moments(b, c, zeta);
    let mut sum = 0.0;
    let mut coefficient = 1.0;
    for (n, &m2n) in m.iter().enumerate() {
        sum += coefficient * m2n;
        coefficient *= -c / (n + 1) as f64;
    }
    sum
}

/// The terms `(-1)^j / (j! (j + 9))` of `M_8(b) = sum_j t_j b^j`, `j <= 27`,
/// dealt into four chains (`j = 4 i + r` in chain `r`) so that `M_8` is
/// four independent Horner sums in `b^4`. At `b = 2` the first omitted term
/// is below `2^28 / 28! / 37 < 3e-23`, under `1e-20` of `M_8(2) > 0.01`.
const M8_CHAINS: [[f64; 7]; 4] = m8_chains();

const fn m8_chains() -> [[f64; 7]; 4] {
    let terms: [f64; 28] = moment_terms(8);
    let mut chains = [[0.0; 7]; 4];
    let mut j = 0;
    while j < 28 {
        chains[j % 4][j / 4] = terms[j];
        j += 1;
    }
    chains
}

/// The first `J` terms `(-1)^j / (j! (j + k + 1))` of the series
/// `M_k(b) = sum_j t_j b^j`.
const fn moment_terms<const J: usize>(k: usize) -> [f64; J] {
    let mut terms = [0.0; J];
    let mut factorial = 1.0;
    let mut j = 0;
    while j < J {
        if j > 0 {
            factorial *= j as f64;
        }
        let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
        terms[j] = sign / (factorial * (j + k + 1) as f64);
        j += 1;
    }
    terms
}

/// `M_0, M_2, ..., M_2(N-1)` from the last of them, `top`, by the backward
/// recurrence `M_{k-1} = (b M_k + exp(-b)) / k` two steps at a time:
/// `M_{k-2} = (b^2 M_k + exp(-b) (b + k)) / (k (k - 1))`, which multiplies
/// errors by `b / k` per step (`e` is `exp(-b)`).
#[inline(always)]
fn moments_down<const N: usize>(top: f64, b: f64, e: f64) -> [f64; N] {
    let b2 = b * b;
    let mut m = [top; N];
    for n in (1..N).rev() {
        let k = (2 * n) as f64;
        m[n - 1] = (b2 * m[n] + e * (b + k)) * (1.0 / (k * (k - 1.0)));
    }
    m
}

/// `M_0, M_2, ..., M_2(N-1)` by the forward recurrence
/// `M_k = (k M_{k-1} - exp(-b)) / b` two steps at a time:
/// `M_k = (k (k - 1) M_{k-2} - exp(-b) (b + k)) / b^2` from
/// `M_0 = (1 - exp(-b)) / b`, which multiplies errors by `k / b` per step.
#[inline(always)]
fn moments_up<const N: usize>(b: f64, e: f64) -> [f64; N] {
    let inv_b2 = 1.0 / (b * b);
    let mut m = [(1.0 - e) / b; N];
    for n in 1..N {
        let k = (2 * n) as f64;
        m[n] = (k * (k - 1.0) * m[n - 1] - e * (b + k)) * inv_b2;
    }
    m
}

/// `M_k(b) = int_0^1 x^k exp(-b x) dx` for `k = 0, 2, 4, 6, 8`, given
/// `|c| < 1e-3` and `zeta = exp(-(b + c))`: then `exp(-b)` is `zeta exp(c)`,
/// with `exp(c)` to its `c^5` term (`c^6 / 720 < 2e-21`).
fn even_moments(b: f64, c: f64, zeta: f64) -> [f64; 5] {
    let e = zeta * (1.0 + c * (1.0 + c * (0.5 + c * (1.0 / 6.0 + c * (1.0 / 24.0 + c / 120.0)))));
    if b <= 2.0 {
        // M_8 by its series, then the backward recurrence: errors shrink
        // by at most 2^8 / 8! overall.
        let b2 = b * b;
        let b4 = b2 * b2;
        let q = M8_CHAINS.map(|chain| horner(&chain, b4));
        let m8 = (q[0] + b * q[1]) + b2 * (q[2] + b * q[3]);
        moments_down(m8, b, e)
    } else {
        // The forward recurrence grows errors by at most 8!/2^8 overall,
        // and every M_k with k > 0 is damped by a power of c < 1e-3 in the
        // sum.
        moments_up(b, e)
    }
}

/// Eq. 3.28 weights rounded to f32 for one channel: [`exact_zeta_psi`],
/// except that nearly constant attenuation (the common segment of a fine
/// mesh) takes `psi_near_constant`, whose error is far below f32's
/// rounding.
#[inline]
pub fn exact_weights(tau_d_back: f32, tau_d_front: f32) -> Weights {
    let (a, b) = (f64::from(tau_d_back), f64::from(tau_d_front));
    let (zeta, psi) = match near_constant(a, b) {
        Some(c) => {
            let zeta = exp_f64_select(-0.5 * (a + b));
            (zeta, psi_near_constant(b, c, zeta))
        }
        None => exact_zeta_psi(a, b),
    };
    Weights {
        zeta: zeta as f32,
        psi: psi as f32,
    }
}

/// `c = (a - b) / 2` where [`psi_near_constant`] applies: `|c| < 1e-3`,
/// `a` and `b` not negative. `None` for a NaN, an infinity (c is then one
/// or NaN) and a negative value, which [`exact_zeta_psi`] answers.
#[inline(always)]
fn near_constant(a: f64, b: f64) -> Option<f64> {
    let c = 0.5 * (a - b);
    (c.abs() < SERIES_BELOW && a >= 0.0 && b >= 0.0).then_some(c)
}

/// [`exact_weights`] of `N` segments, the same bits per lane where bit
/// `i` of `live` is set (anything elsewhere). The nearly constant
/// segments, nearly all of them on a fine mesh, are computed for every
/// lane as vector arithmetic (the exponential and both of
/// `psi_near_constant`'s moment recurrences run without a branch); the
/// other live lanes take the closed forms alone, with their lane's
/// exponential.
#[inline(always)]
pub fn exact_weights_lanes<const N: usize>(
    back: &[f32; N],
    front: &[f32; N],
    live: u32,
) -> [Weights; N] {
    // Plain loops, each filling an array: `array::from_fn` with closures
    // this large is left out of line (neither vectorized nor compiled for
    // the walk's instruction set), and a loop that stores conditionally is
    // not vectorized.
    let mut zeta = [0.0; N];
    for (i, z) in zeta.iter_mut().enumerate() {
        *z = exp_f64_select(-0.5 * (f64::from(back[i]) + f64::from(front[i])));
    }
    let mut psi = [0.0; N];
    for (i, p) in psi.iter_mut().enumerate() {
        let (a, b) = (f64::from(back[i]), f64::from(front[i]));
        *p = psi_near_constant(b, 0.5 * (a - b), zeta[i]);
    }
    let mut weights = [Weights {
        zeta: 1.0,
        psi: 1.0,
    }; N];
    for (i, w) in weights.iter_mut().enumerate() {
        let (a, b) = (f64::from(back[i]), f64::from(front[i]));
        if near_constant(a, b).is_some() {
            *w = Weights {
                zeta: zeta[i] as f32,
                psi: psi[i] as f32,
            };
        } else if live >> i & 1 != 0 {
            // `exact_zeta_psi`'s own steps, with the lane's exponential.
            *w = if out_of_domain(a, b).is_none() {
                Weights {
                    zeta: zeta[i] as f32,
                    psi: psi_given_zeta(a, b, zeta[i]) as f32,
                }
            } else {
                exact_weights(back[i], front[i])
            };
        }
    }
    weights
}

/// The terms `(-1)^j / (j! (j + 7))` of `M_6(b) = sum_j t_j b^j`, `j <= 10`.
/// At `b = 1/2` the first omitted term is below `2^-11 / 11! / 18 < 7e-13`,
/// about `1e-11` of `M_6`; `M_4`, `M_2` and `M_0`, which come from `M_6`,
/// take it times `b^2 / 30`, `b^4 / 360` and `b^6 / 720`.
const M6_TERMS: [f64; 11] = moment_terms(6);

/// Psi for `|c| < 1e-3` to about `1e-14` relative, where [`psi_series`]
/// goes to `1e-18`: `sum_{n=0}^{3} (-c)^n / n! M_2n(b)`, whose first
/// omitted term is at most `c^4 / 24 M_8 < 4.2e-14 M_8`, with `M_8 <= M_0`
/// (the weight `x^8` is at most 1). No f32 weight moves by more than one
/// rounding step.
#[inline(always)]
fn psi_near_constant(b: f64, c: f64, zeta: f64) -> f64 {
    // exp(-b) = zeta exp(c), exp(c) to its c^4 term (c^5 / 120 < 1e-17).
    let e = zeta * (1.0 + c * (1.0 + c * (0.5 + c * (1.0 / 6.0 + c * (1.0 / 24.0)))));
    // Both recurrences run and one is taken, so that lanes of these
    // vectorize (see `exact_weights_lanes`). Up to b = 1/2: M_6 by its
    // series, then the backward recurrence, which damps errors. Above:
    // the forward recurrence, which multiplies rounding by at most
    // k! / b^k in M_k (8 in M_2, 46080 in M_6 at b = 1/2), and Psi takes
    // M_k times |c|^(k/2) / (k/2)! (1.7e-10 for M_6).
    let m6 = horner(&M6_TERMS, b);
    let down: [f64; 4] = moments_down(m6, b, e);
    let up: [f64; 4] = moments_up(b, e);
    let [m0, m2, m4, m6] = std::array::from_fn(|k| if b <= 0.5 { down[k] } else { up[k] });
    m0 - c * (m2 - c * (0.5 * m4 - c * (1.0 / 6.0) * m6))
}

/// The exact light of a segment with linear luminance and attenuation.
pub fn exact_segment(p: &SegmentParams) -> SegmentLight {
    let d = p.length;
    light_from_weights(
        p.lum_back.into(),
        p.lum_front.into(),
        (p.tau_back * d).into(),
        (p.tau_front * d).into(),
        exact_weights,
    )
}

/// Eq. 3.28 in f64 for one channel: `I(D)` given `I_0`.
pub fn exact_intensity(i0: f64, lb: f64, lf: f64, tau_b: f64, tau_f: f64, d: f64) -> f64 {
    let (zeta, psi) = exact_zeta_psi(tau_b * d, tau_f * d);
    i0 * zeta + lb * (psi - zeta) + lf * (1.0 - psi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psi::psi;
    use glam::Vec3;

    #[test]
    fn closed_forms_match_quadrature_on_every_branch() {
        let values = [
            0.0, 1e-9, 1e-4, 9.99e-4, 1e-3, 0.002, 0.1, 0.5, 1.0, 1.0005, 2.0, 4.0, 10.0, 35.0,
            100.0, 1e3, 1e5,
        ];
        for &a in &values {
            for &b in &values {
                let (_, closed) = exact_zeta_psi(a, b);
                let quad = psi(a, b);
                assert!(
                    (closed - quad).abs() < 2e-14 * quad.max(1e-3),
                    "Psi({a}, {b}): closed {closed}, quadrature {quad}"
                );
            }
        }
    }

    #[test]
    fn moments_match_gauss_legendre() {
        // 16-point Gauss-Legendre integrates x^k exp(-b x) on [0, 1] to
        // about 1e-16 for these b (the integrand's 32nd derivative is at
        // most (k + b)^32 / 32!-small against the rule's error constant).
        for i in 0..=600 {
            let b = 6.0 * f64::from(i) / 600.0;
            for &c in &[0.0, 9e-4, -9e-4] {
                let zeta = (-(b + c)).exp();
                let m = even_moments(b, c, zeta);
                for (n, &mk) in m.iter().enumerate() {
                    let k = 2 * n;
                    let quad = crate::special::gauss_legendre_panel(0.0, 1.0, |x| {
                        x.powi(k as i32) * (-b * x).exp()
                    });
                    // The forward recurrence above b = 2 multiplies
                    // rounding by up to k! / b^k (158 for M_8 at b = 2);
                    // such an M_k enters Psi times c^(k/2) <= 1e-6.
                    let tolerance = if b <= 2.0 || k <= 2 { 1e-14 } else { 1e-11 };
                    assert!(
                        (mk - quad).abs() < tolerance * quad,
                        "M_{k}({b}) with c = {c}: {mk} against {quad}"
                    );
                }
            }
        }
    }

    /// The short series of `exact_weights` against the full one, over
    /// every `b` and `|c| < 1e-3` on a grid dense at both ends: within
    /// `2e-14` of Psi in f64 (its truncation is under `4.2e-14` of Psi at
    /// worst), and the f32 weights differ by at most one rounding step.
    #[test]
    fn near_constant_series_matches_the_full_series() {
        let mut worst = 0.0f64;
        let mut f32_steps = 0;
        for i in 0..=4000 {
            let b = if i <= 2000 {
                f64::from(i) / 2000.0 * 1.5
            } else {
                1.5 * 1.003f64.powi(i - 2000)
            };
            for &c in &[-9.99e-4, -5e-4, -1e-5, 0.0, 1e-7, 3e-4, 9.99e-4] {
                if b + 2.0 * c < 0.0 {
                    continue;
                }
                let zeta = (-(b + c)).exp();
                let full = psi_series(b, c, zeta);
                let short = psi_near_constant(b, c, zeta);
                worst = worst.max((short - full).abs() / full);
                let (x, y) = ((short as f32).to_bits(), (full as f32).to_bits());
                assert!(x.abs_diff(y) <= 1, "Psi({b}, {c}): {short} against {full}");
                f32_steps += usize::from(x != y);
            }
        }
        // 4.7e-15 on this grid.
        assert!(worst < 2e-14, "worst relative difference {worst:e}");
        // Only a value within 2e-14 of an f32 rounding boundary can differ
        // (none on this grid).
        assert!(f32_steps < 5, "{f32_steps} f32 weights differ");
    }

    /// The lanes give each live lane the bits of [`exact_weights`], over
    /// nearly constant and other segments, both moment recurrences, the
    /// exponential's zero, and NaN, infinite and negative values; a lane
    /// that is not live gives ones unless it is nearly constant.
    #[test]
    fn lanes_have_the_bits_of_one_segment_at_a_time() {
        let specials = [0.0, 1e-30, 0.3, 0.5, 0.500_5, 2.0, 1500.0, 1e30];
        let odd = [f32::NAN, f32::INFINITY, -1.0, -1e-4];
        let mut values: Vec<f32> = specials.to_vec();
        values.extend(odd);
        let mut state = 0x9e37_79b9u32;
        for _ in 0..4000 {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            let base = (state >> 8) as f32 / (1u32 << 24) as f32 * 8.0;
            // Nearly constant (|c| up to 2e-3) or not (up to 2).
            let spread = if state & 0x100 == 0 { 0.004 } else { 4.0 };
            let offset = ((state & 0xff) as f32 / 255.0 - 0.5) * spread;
            values.push(base);
            values.push(base + offset);
        }
        let (mut near, mut general) = (0, 0);
        for chunk in values.chunks_exact(32) {
            let back: [f32; 16] = std::array::from_fn(|i| chunk[2 * i]);
            let front: [f32; 16] = std::array::from_fn(|i| chunk[2 * i + 1]);
            for live in [u32::MAX, 0x5555, 0] {
                let lanes = exact_weights_lanes(&back, &front, live);
                for i in 0..16 {
                    let one = exact_weights(back[i], front[i]);
                    let is_near = near_constant(back[i].into(), front[i].into()).is_some();
                    near += usize::from(is_near);
                    general += usize::from(!is_near && back[i] >= 0.0 && front[i] >= 0.0);
                    let want = if live >> i & 1 != 0 || is_near {
                        (one.zeta.to_bits(), one.psi.to_bits())
                    } else {
                        (1f32.to_bits(), 1f32.to_bits())
                    };
                    let got = (lanes[i].zeta.to_bits(), lanes[i].psi.to_bits());
                    let both_nan = lanes[i].psi.is_nan() && one.psi.is_nan();
                    assert!(got == want || both_nan, "({}, {})", back[i], front[i]);
                }
            }
        }
        assert!(near > 3000, "only {near} nearly constant lanes");
        assert!(general > 3000, "only {general} lanes in the closed forms");
    }

    #[test]
    fn constant_attenuation_is_eq_3_21() {
        for &(tau, d) in &[(0.5, 2.0), (3.0, 0.1), (1e-3, 1.0), (40.0, 1.0)] {
            let td: f64 = tau * d;
            let e = (-td).exp();
            let (lb, lf, i0) = (0.3, 0.8, 0.25);
            let expected = i0 * e + lb * (1.0 / td - e / td - e) + lf * (1.0 + e / td - 1.0 / td);
            let got = exact_intensity(i0, lb, lf, tau, tau, d);
            assert!((got - expected).abs() < 1e-12, "{got} vs {expected}");
        }
        // tau D = 0: nothing happens (eq. 3.28, last case).
        assert_eq!(exact_intensity(0.4, 1.0, 1.0, 0.0, 0.0, 5.0), 0.4);
    }

    #[test]
    fn large_optical_depth_sees_only_the_front() {
        // Opaque segment: the eye sees the front luminance, nothing passes.
        let v = exact_intensity(1.0, 0.2, 0.9, 1e4, 1e4, 1.0);
        assert!((v - 0.9).abs() < 1e-4);
        let light = exact_segment(&SegmentParams {
            lum_back: Vec3::splat(0.2),
            lum_front: Vec3::splat(0.9),
            tau_back: Vec3::splat(1e6),
            tau_front: Vec3::splat(1e6),
            length: 1.0,
        });
        assert!(light.emitted.is_finite() && light.transmittance == glam::Vec3A::ZERO);
    }
}
