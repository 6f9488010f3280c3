//! The f64 reference: the volume rendering integral (eq. 2.2) of one segment
//! by adaptive Gauss-Legendre quadrature, straight from its definition,
//! sharing no formula with the methods it checks.
//!
//! With `x` the distance from the segment's front end (`x = 0` at the eye
//! side), the light reaching the front is
//! `I = I_0 exp(-int_0^D tau) + int_0^D L(x) tau(x) exp(-int_0^x tau) dx`.
//! The optical depth `int_0^x tau` has a closed form for both models: linear
//! attenuation (a quadratic) and linear opacity (`tau = -ln(1 - alpha)`).

use crate::special::gauss_legendre_panel;

/// Deepest bisection of the adaptive quadrature (a panel of `D / 2^40`
/// resolves any optical depth a f64 exponential can tell apart from 0).
const MAX_DEPTH: u32 = 40;

/// Emitted light and transmittance of one channel of a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceLight {
    pub emitted: f64,
    pub transmittance: f64,
}

impl ReferenceLight {
    /// `I(D)` for incoming light `i0`.
    pub fn over(&self, i0: f64) -> f64 {
        i0 * self.transmittance + self.emitted
    }
}

/// Linear luminance and attenuation: `tau_*` per unit length, `length` in
/// that unit (dissertation eq. 2.19-2.20).
pub fn attenuation_segment(
    lum_back: f64,
    lum_front: f64,
    tau_back: f64,
    tau_front: f64,
    length: f64,
) -> ReferenceLight {
    let d = length;
    if d <= 0.0 {
        return ReferenceLight {
            emitted: 0.0,
            transmittance: 1.0,
        };
    }
    let slope = (tau_back - tau_front) / d;
    let depth = |x: f64| tau_front * x + 0.5 * slope * x * x;
    let lum = |x: f64| lum_front + (lum_back - lum_front) * (x / d);
    let tau = |x: f64| tau_front + slope * x;
    let emitted = adaptive(
        |x| lum(x) * tau(x) * (-depth(x)).exp(),
        0.0,
        d,
        1e-13 * lum_back.abs().max(lum_front.abs()),
    );
    ReferenceLight {
        emitted,
        transmittance: (-depth(d)).exp(),
    }
}

/// Linear luminance and opacity (section 5.3): `alpha_*` the opacity of one
/// unit distance of material (below 1), `length_units` in unit distances.
/// The attenuation is `tau(x) = -ln(1 - alpha(x))` per unit distance.
pub fn opacity_segment(
    lum_back: f64,
    lum_front: f64,
    alpha_back: f64,
    alpha_front: f64,
    length_units: f64,
) -> ReferenceLight {
    let d = length_units;
    if d <= 0.0 {
        return ReferenceLight {
            emitted: 0.0,
            transmittance: 1.0,
        };
    }
    let beta_front = 1.0 - alpha_front;
    let beta_slope = (alpha_front - alpha_back) / d;
    let beta = |x: f64| beta_front + beta_slope * x;
    // int_0^x -ln(beta(t)) dt = -x ln(beta_f) - x h(r), r = slope x / beta_f,
    // h(r) = ((1 + r) ln(1 + r) - r) / r.
    let depth = |x: f64| {
        let r = beta_slope * x / beta_front;
        let h = if r.abs() < 1e-3 {
            r * (0.5 - r * (1.0 / 6.0 - r * (1.0 / 12.0 - r / 20.0)))
        } else {
            ((1.0 + r) * r.ln_1p() - r) / r
        };
        -x * beta_front.ln() - x * h
    };
    let lum = |x: f64| lum_front + (lum_back - lum_front) * (x / d);
    let emitted = adaptive(
        |x| lum(x) * -beta(x).ln() * (-depth(x)).exp(),
        0.0,
        d,
        1e-13 * lum_back.abs().max(lum_front.abs()),
    );
    ReferenceLight {
        emitted,
        transmittance: (-depth(d)).exp(),
    }
}

/// `int_a^b f` to about `tolerance` absolute: a 16-point Gauss-Legendre
/// panel is accepted when its two halves agree with it.
pub fn adaptive(f: impl Fn(f64) -> f64 + Copy, a: f64, b: f64, tolerance: f64) -> f64 {
    let whole = gauss_legendre_panel(a, b, f);
    refine(f, a, b, whole, tolerance.max(f64::MIN_POSITIVE), 0)
}

fn refine(f: impl Fn(f64) -> f64 + Copy, a: f64, b: f64, whole: f64, tol: f64, depth: u32) -> f64 {
    let mid = 0.5 * (a + b);
    let left = gauss_legendre_panel(a, mid, f);
    let right = gauss_legendre_panel(mid, b, f);
    let halves = left + right;
    // Accept when the halves agree to the tolerance or to rounding (the
    // tolerance halves with each bisection, rounding does not).
    let agreement = (halves - whole).abs();
    let rounding = 4.0 * f64::EPSILON * (left.abs() + right.abs());
    if agreement <= tol.max(rounding) || depth >= MAX_DEPTH || mid <= a || mid >= b {
        return halves;
    }
    refine(f, a, mid, left, 0.5 * tol, depth + 1) + refine(f, mid, b, right, 0.5 * tol, depth + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn homogeneous_segment_is_beer_lambert() {
        // Eq. 2.17: I = I_0 e^{-tau D} + L (1 - e^{-tau D}).
        for &(tau, d) in &[
            (0.0f64, 1.0f64),
            (1e-6, 3.0),
            (0.7, 2.0),
            (50.0, 1.0),
            (1e4, 0.5),
        ] {
            let light = attenuation_segment(0.6, 0.6, tau, tau, d);
            let t = (-tau * d).exp();
            assert!((light.transmittance - t).abs() < 1e-15);
            assert!((light.emitted - 0.6 * (1.0 - t)).abs() < 1e-14, "{tau} {d}");
        }
    }

    #[test]
    fn constant_opacity_is_attenuation_minus_log() {
        let alpha: f64 = 0.3;
        let tau = -(1.0 - alpha).ln();
        let a = opacity_segment(0.2, 0.9, alpha, alpha, 2.5);
        let b = attenuation_segment(0.2, 0.9, tau, tau, 2.5);
        assert!((a.emitted - b.emitted).abs() < 1e-14);
        assert!((a.transmittance - (1.0 - alpha).powf(2.5)).abs() < 1e-15);
    }

    #[test]
    fn emission_only_limit_and_pure_absorption() {
        // L = 0: only absorption, T = exp(-D (tau_b + tau_f) / 2) (eq. 5.6).
        let light = attenuation_segment(0.0, 0.0, 2.0, 0.5, 1.5);
        assert_eq!(light.emitted, 0.0);
        assert!((light.transmittance - (-1.5f64 * 1.25).exp()).abs() < 1e-15);
    }
}
