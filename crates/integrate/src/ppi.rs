//! Partial pre-integration (dissertation section 5.2): eq. 5.5 with
//! `zeta = exp(-(tau_b D + tau_f D)/2)` (eq. 5.6) and Psi looked up in the
//! table of [`crate::psi::PsiTable`].

use crate::fastmath::{clamp_f32, exp_f32};
use crate::psi::PsiTable;
use crate::segment::{light_from_weights, SegmentLight, SegmentParams, Weights};

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
