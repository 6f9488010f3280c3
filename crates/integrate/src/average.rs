//! Averaged luminance and attenuation (Shirley-Tuchman; Max, Hanrahan and
//! Crawfis; VTK's homogeneous integrator), eq. 3.16, and its opacity twin,
//! averaged luminance and opacity (Wilhelms and van Gelder).

use crate::segment::Weights;

/// Eq. 3.16 for `a = tau_b D`, `b = tau_f D`: a homogeneous segment with the
/// mean attenuation, `I = I_0 zeta + (L_b + L_f)/2 (1 - zeta)`, which is eq.
/// 5.5 with `Psi = (1 + zeta) / 2`.
#[inline(always)]
pub fn average_weights(tau_d_back: f32, tau_d_front: f32) -> Weights {
    let zeta = crate::fastmath::exp_f32(-0.5 * (tau_d_back + tau_d_front));
    Weights {
        zeta,
        psi: 0.5 * (1.0 + zeta),
    }
}

/// Averaged luminance and opacity: a homogeneous segment whose opacity per
/// unit distance is the mean `(alpha_b + alpha_f) / 2`, over `length_units`
/// unit distances.
#[inline]
pub fn average_opacity_weights(alpha_back: f32, alpha_front: f32, length_units: f32) -> Weights {
    let alpha = crate::opacity::clamp_alpha(0.5 * (alpha_back + alpha_front));
    let zeta = (1.0 - alpha).powf(length_units);
    Weights {
        zeta,
        psi: 0.5 * (1.0 + zeta),
    }
}
