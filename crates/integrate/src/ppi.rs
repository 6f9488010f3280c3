//! Partial pre-integration (dissertation section 5.2): eq. 5.5 with
//! `zeta = exp(-(tau_b D + tau_f D)/2)` (eq. 5.6) and Psi looked up in the
//! table of [`crate::psi::PsiTable`].

use crate::psi::PsiTable;
use crate::segment::{light_from_weights, SegmentLight, SegmentParams, Weights};

/// Eq. 5.5 weights for one channel. Psi is a mean transmittance between
/// the segment and the eye, so it lies in `[zeta, 1]`; the clamp keeps
/// bilinear rounding from emitting negative light.
#[inline]
pub fn ppi_weights(table: &PsiTable, tau_d_back: f32, tau_d_front: f32) -> Weights {
    let zeta = (-0.5 * (tau_d_back + tau_d_front)).exp();
    let psi = table.lookup(tau_d_back, tau_d_front).max(zeta).min(1.0);
    Weights { zeta, psi }
}

/// The light of one segment by partial pre-integration.
pub fn ppi_segment(table: &PsiTable, p: &SegmentParams) -> SegmentLight {
    let d = p.length;
    light_from_weights(
        p.lum_back,
        p.lum_front,
        p.tau_back * d,
        p.tau_front * d,
        |a, b| ppi_weights(table, a, b),
    )
}
