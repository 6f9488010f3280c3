//! Linear luminance with linearly interpolated opacity (section 5.3): the
//! rough approximation of 5.3.1 (average opacity for zeta and Psi) and the
//! improved one of 5.3.2 (eq. 5.13 for zeta, the weighted opacity of
//! eq. 5.14 for Psi).

use crate::segment::Weights;

/// Opacities are kept below 1: a fully opaque unit distance would need an
/// infinite attenuation. `1 - 1e-6` passes 1e-6 of the light per unit
/// distance (an attenuation of 13.8 per unit distance).
pub const ALPHA_MAX: f32 = 1.0 - 1e-6;

/// `alpha` clamped to `[0, ALPHA_MAX]` (NaN stays NaN).
#[inline]
pub fn clamp_alpha(alpha: f32) -> f32 {
    alpha.clamp(0.0, ALPHA_MAX)
}

/// Psi of a homogeneous segment of optical depth `tau_d`:
/// `(1 - exp(-tau_d)) / tau_d`, with its limit 1 at 0 (section 5.3.1).
#[inline]
pub fn psi_homogeneous(tau_d: f32) -> f32 {
    if tau_d < 1e-4 {
        // Taylor: 1 - x/2 + x^2/6, exact to f32 below 1e-4.
        1.0 - tau_d * (0.5 - tau_d / 6.0)
    } else {
        -(-tau_d).exp_m1() / tau_d
    }
}

/// Section 5.3.1, "linear luminance, average opacity": zeta and Psi of a
/// homogeneous segment whose opacity is the mean of the two ends.
#[inline]
pub fn lin_avg_opacity_weights(alpha_back: f32, alpha_front: f32, length_units: f32) -> Weights {
    let alpha = clamp_alpha(0.5 * (alpha_back + alpha_front));
    let tau_d = -length_units * (-alpha).ln_1p();
    Weights {
        zeta: (-tau_d).exp(),
        psi: psi_homogeneous(tau_d),
    }
}

/// Coefficient of the parabola fitted to zeta over `alpha_b + alpha_f = 1`
/// (eq. 5.13).
const ZETA_PARABOLA: f32 = 0.108_165;
/// Weights of the back and front opacity that minimise the l2 error of Psi
/// (eq. 5.14).
const PSI_BACK_WEIGHT: f32 = 0.27;
const PSI_FRONT_WEIGHT: f32 = 0.73;

/// Section 5.3.2, "linear luminance and opacity": zeta from the mean
/// opacity plus the parabola of eq. 5.13, Psi from the front-weighted
/// opacity of eq. 5.14.
#[inline]
pub fn lin_opacity_weights(alpha_back: f32, alpha_front: f32, length_units: f32) -> Weights {
    let (ab, af) = (clamp_alpha(alpha_back), clamp_alpha(alpha_front));
    let diff = ab - af;
    let alpha_zeta = clamp_alpha(0.5 * (ab + af) + ZETA_PARABOLA * diff * diff);
    // (1 - alpha)^units: ln_1p(-alpha) is negative.
    let zeta = (length_units * (-alpha_zeta).ln_1p()).exp();
    let alpha_psi = clamp_alpha(PSI_BACK_WEIGHT * ab + PSI_FRONT_WEIGHT * af);
    let tau_d_psi = -length_units * (-alpha_psi).ln_1p();
    Weights {
        zeta,
        psi: psi_homogeneous(tau_d_psi),
    }
}
