//! Partial pre-integration (dissertation section 5.2): eq. 5.5 with
//! `zeta = exp(-(tau_b D + tau_f D)/2)` (eq. 5.6) and Psi looked up in the
//! table of [`crate::psi::PsiTable`].

use glam::Vec4;
use tetray_wide::Wide;

use crate::fastmath::{by_fours, clamp_f32, exp_f32, exp_f32_select};
use crate::psi::PsiTable;
use crate::segment::{SegmentLight, SegmentParams, Weights, light_from_weights};

/// Eq. 5.5 weights for one channel. Psi is a mean transmittance between
/// the segment and the eye, so it lies in `[zeta, 1]`; the clamp keeps
/// bilinear rounding from emitting negative light.
#[inline(always)]
pub fn ppi_weights(table: &PsiTable, tau_d_back: f32, tau_d_front: f32) -> Weights {
    let zeta = exp_f32(-0.5 * (tau_d_back + tau_d_front));
    let psi = table.lookup(tau_d_back, tau_d_front);
    let psi = clamp_f32(psi, zeta, 1.0);
    Weights { zeta, psi }
}

/// [`ppi_weights`] of `N` segments at once, the same bits per lane: the
/// exponentials and table coordinates of all lanes as vector arithmetic,
/// the table read by AVX2 gathers where `wide` holds their token.
#[inline(always)]
pub fn ppi_weights_lanes<const N: usize>(
    table: &PsiTable,
    tau_d_back: &[f32; N],
    tau_d_front: &[f32; N],
    wide: Option<Wide>,
) -> [Weights; N] {
    let mut zeta = [0.0f32; N];
    for ((z, &b), &f) in zeta.iter_mut().zip(tau_d_back).zip(tau_d_front) {
        *z = exp_f32_select(-0.5 * (b + f));
    }
    let psi = table.lookup_lanes(tau_d_back, tau_d_front, wide);
    // `clamp_f32(psi, zeta, 1)` as the SSE max and min (each the second
    // operand when unordered): the same bits whenever `zeta <= 1`, which
    // non-negative attenuations guarantee.
    let psi = by_fours(&zeta, &psi, |zeta, psi| Vec4::ONE.min(zeta.max(psi)));
    std::array::from_fn(|i| Weights {
        zeta: zeta[i],
        psi: psi[i],
    })
}

/// The light of one segment by partial pre-integration.
pub fn ppi_segment(table: &PsiTable, p: &SegmentParams) -> SegmentLight {
    let d = p.length;
    light_from_weights(
        p.lum_back.into(),
        p.lum_front.into(),
        (p.tau_back * d).into(),
        (p.tau_front * d).into(),
        |a, b| ppi_weights(table, a, b),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psi::{GammaSpacing, test_tau_d};

    /// The lanes give each segment's single-segment weights to the bit, over
    /// the attenuations a walk produces (`tau D >= 0`, up to infinity) and
    /// NaN, with both table spacings.
    #[test]
    fn lanes_give_the_single_segment_bits() {
        let values = test_tau_d(0x2545_f491, 4000);
        for spacing in [GammaSpacing::Uniform, GammaSpacing::Quadratic] {
            let table = PsiTable::build(64, spacing).expect("table");
            for (k, back) in values.chunks_exact(16).enumerate() {
                let back: [f32; 16] = back.try_into().expect("16 lanes");
                let front = std::array::from_fn(|i| values[(k * 11 + i * 7 + 3) % values.len()]);
                for wide in [None, tetray_wide::token(true)] {
                    let lanes =
                        tetray_wide::run(true, || ppi_weights_lanes(&table, &back, &front, wide));
                    for i in 0..16 {
                        let single = ppi_weights(&table, back[i], front[i]);
                        assert_eq!(
                            (lanes[i].zeta.to_bits(), lanes[i].psi.to_bits()),
                            (single.zeta.to_bits(), single.psi.to_bits()),
                            "{spacing:?} at ({}, {})",
                            back[i],
                            front[i]
                        );
                    }
                }
            }
        }
    }
}
