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

use crate::segment::{light_from_weights, SegmentLight, SegmentParams, Weights};
use crate::special::{dawson, erfcx};

/// Below this `|c|` the series in `c` is used: its first omitted term is
/// below `|c|^5 / 120 / 11 < 1e-18`, while the closed forms' `1/sqrt|c|`
/// amplification of rounding stays below 32.
const SERIES_BELOW: f64 = 1e-3;

/// `sqrt(pi) / 2`.
const SQRT_PI_2: f64 = 0.886_226_925_452_758;

/// `(zeta, Psi)` in f64 for `a = tau_b D >= 0`, `b = tau_f D >= 0`.
pub fn exact_zeta_psi(a: f64, b: f64) -> (f64, f64) {
    if a.is_nan() || b.is_nan() || a < 0.0 || b < 0.0 {
        return (f64::NAN, f64::NAN);
    }
    if a.is_infinite() || b.is_infinite() {
        return (0.0, 0.0);
    }
    let zeta = (-0.5 * (a + b)).exp();
    let c = 0.5 * (a - b);
    let psi = if c.abs() < SERIES_BELOW {
        psi_series(b, c)
    } else if c > 0.0 {
        let k = c.sqrt();
        SQRT_PI_2 / k * (erfcx(b / (2.0 * k)) - zeta * erfcx(a / (2.0 * k)))
    } else {
        let k = (-c).sqrt();
        (dawson(b / (2.0 * k)) - zeta * dawson(a / (2.0 * k))) / k
    };
    (zeta, psi)
}

/// Psi for small `|c|`: `sum_{n=0}^{4} (-c)^n / n! M_2n(b)`.
fn psi_series(b: f64, c: f64) -> f64 {
    let m = moments(b);
    let mut sum = 0.0;
    let mut coefficient = 1.0;
    for n in 0..5 {
        sum += coefficient * m[2 * n];
        coefficient *= -c / (n + 1) as f64;
    }
    sum
}

/// `M_k(b) = int_0^1 x^k exp(-b x) dx` for `k = 0..=8`.
fn moments(b: f64) -> [f64; 9] {
    let mut m = [0.0; 9];
    if b <= 2.0 {
        // sum_j (-b)^j / (j! (k + j + 1)); terms fall below 1e-18 by j = 30.
        for (k, mk) in m.iter_mut().enumerate() {
            let mut power = 1.0;
            let mut sum = 0.0;
            for j in 0..40 {
                let term = power / (k + j + 1) as f64;
                sum += term;
                if term.abs() < 1e-18 * sum.abs() {
                    break;
                }
                power *= -b / (j + 1) as f64;
            }
            *mk = sum;
        }
    } else {
        // Forward recurrence M_k = (k M_{k-1} - exp(-b)) / b: it multiplies
        // errors by k / b per step, at most 8!/2^8 overall, and every M_k
        // with k > 0 is damped by a power of c < 1e-3 in the sum.
        let e = (-b).exp();
        m[0] = -(-b).exp_m1() / b;
        for k in 1..9 {
            m[k] = (k as f64 * m[k - 1] - e) / b;
        }
    }
    m
}

/// Eq. 3.28 weights rounded to f32 for one channel.
#[inline]
pub fn exact_weights(tau_d_back: f32, tau_d_front: f32) -> Weights {
    let (zeta, psi) = exact_zeta_psi(f64::from(tau_d_back), f64::from(tau_d_front));
    Weights {
        zeta: zeta as f32,
        psi: psi as f32,
    }
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
