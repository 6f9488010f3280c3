//! Averaged luminance and attenuation (Shirley-Tuchman; Max, Hanrahan and
//! Crawfis; VTK's homogeneous integrator), eq. 3.16, and its opacity twin,
//! averaged luminance and opacity (Wilhelms and van Gelder).

use crate::fastmath::exp_f32_select;
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

/// [`average_weights`] of `N` segments at once, the same bits per lane: the
/// exponential without a branch ([`exp_f32_select`]), so that the lanes
/// are vector arithmetic.
#[inline(always)]
pub fn average_weights_lanes<const N: usize>(
    tau_d_back: &[f32; N],
    tau_d_front: &[f32; N],
) -> [Weights; N] {
    let mut zeta = [0.0f32; N];
    for ((z, &b), &f) in zeta.iter_mut().zip(tau_d_back).zip(tau_d_front) {
        *z = exp_f32_select(-0.5 * (b + f));
    }
    std::array::from_fn(|i| Weights {
        zeta: zeta[i],
        psi: 0.5 * (1.0 + zeta[i]),
    })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psi::test_tau_d;

    /// The lanes give each segment's single-segment weights to the bit,
    /// over the attenuations a walk produces (`tau D >= 0`, up to
    /// infinity) and NaN.
    #[test]
    fn lanes_give_the_single_segment_bits() {
        let values = test_tau_d(0x9e37_79b9, 4000);
        for (k, back) in values.chunks_exact(16).enumerate() {
            let back: [f32; 16] = back.try_into().expect("16 lanes");
            let front = std::array::from_fn(|i| values[(k * 13 + i * 5 + 1) % values.len()]);
            let lanes = average_weights_lanes(&back, &front);
            for i in 0..16 {
                let single = average_weights(back[i], front[i]);
                assert_eq!(
                    (lanes[i].zeta.to_bits(), lanes[i].psi.to_bits()),
                    (single.zeta.to_bits(), single.psi.to_bits()),
                    "at ({}, {})",
                    back[i],
                    front[i]
                );
            }
        }
    }
}
