//! One ray segment: its inputs (luminance and attenuation or opacity at the
//! back and front ends, linear in between) and its light.

use glam::{Vec3, Vec3A};

/// A segment with linear luminance and linear attenuation (dissertation
/// eq. 2.19-2.20). `tau_*` is per unit length, `length` in the same unit.
/// Every quantity may differ per RGB channel (Williams-Max's model).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentParams {
    pub lum_back: Vec3,
    pub lum_front: Vec3,
    pub tau_back: Vec3,
    pub tau_front: Vec3,
    pub length: f32,
}

/// A segment with linear luminance and linear opacity (section 5.3):
/// `alpha_*` is the opacity of one unit distance of material, `length_units`
/// the segment length in unit distances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpacityParams {
    pub lum_back: Vec3,
    pub lum_front: Vec3,
    pub alpha_back: Vec3,
    pub alpha_front: Vec3,
    pub length_units: f32,
}

impl SegmentParams {
    /// The opacity-model view of this segment with unit distance `u`:
    /// `alpha = 1 - exp(-tau u)`, the opacity of `u` of material (eq. 5.11).
    pub fn to_opacity(&self, unit_distance: f32) -> OpacityParams {
        let alpha = |tau: Vec3| Vec3::ONE - (-tau * unit_distance).exp();
        OpacityParams {
            lum_back: self.lum_back,
            lum_front: self.lum_front,
            alpha_back: alpha(self.tau_back),
            alpha_front: alpha(self.tau_front),
            length_units: self.length / unit_distance,
        }
    }
}

/// Light of a segment: what it emits towards the eye (premultiplied, at its
/// front end) and the fraction of light from behind that passes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentLight {
    pub emitted: Vec3A,
    pub transmittance: Vec3A,
}

impl SegmentLight {
    /// No material: nothing emitted, everything passes.
    pub const CLEAR: SegmentLight = SegmentLight {
        emitted: Vec3A::ZERO,
        transmittance: Vec3A::ONE,
    };

    /// The light leaving the front of the segment when `incoming` enters
    /// its back: `I(D) = I_0 T + emitted` (eq. 2.8, Porter-Duff over).
    pub fn over(&self, incoming: Vec3) -> Vec3 {
        Vec3::from(Vec3A::from(incoming) * self.transmittance + self.emitted)
    }

    /// This segment in front of `behind` (front-to-back compositing, eq. 2.13).
    #[inline]
    pub fn then(self, behind: SegmentLight) -> SegmentLight {
        SegmentLight {
            emitted: self.emitted + self.transmittance * behind.emitted,
            transmittance: self.transmittance * behind.transmittance,
        }
    }

    /// Opacity `1 - T`, averaged over the channels.
    pub fn alpha(&self) -> f32 {
        1.0 - self.transmittance.element_sum() / 3.0
    }
}

/// A segment between two classified scalars (front nearer the eye),
/// `length` world units long: what a walk hands an integrator, one per ray
/// when several rays are integrated at once.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SampledSegment<S> {
    pub front: S,
    pub back: S,
    pub length: f32,
}

/// The two numbers of eq. 5.5 for one channel: the transmittance `zeta` and
/// `Psi`. With them, `I(D) = I_0 zeta + L_b (Psi - zeta) + L_f (1 - Psi)`.
/// Every method but the Riemann sum and the table methods reduces to these.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    pub zeta: f32,
    pub psi: f32,
}

impl Weights {
    /// Emitted light of eq. 5.5 for luminances at the back and front.
    #[inline(always)]
    pub fn emitted(self, lum_back: Vec3A, lum_front: Vec3A) -> Vec3A {
        lum_front * (1.0 - self.psi) + lum_back * (self.psi - self.zeta)
    }

    /// The light of a segment whose channels all share these weights.
    #[inline(always)]
    pub fn light(self, lum_back: Vec3A, lum_front: Vec3A) -> SegmentLight {
        SegmentLight {
            emitted: self.emitted(lum_back, lum_front),
            transmittance: Vec3A::splat(self.zeta),
        }
    }

    /// The light of a segment with per-channel weights.
    #[inline]
    pub fn light_rgb(w: [Weights; 3], lum_back: Vec3A, lum_front: Vec3A) -> SegmentLight {
        let zeta = Vec3A::new(w[0].zeta, w[1].zeta, w[2].zeta);
        let psi = Vec3A::new(w[0].psi, w[1].psi, w[2].psi);
        SegmentLight {
            emitted: lum_front * (Vec3A::ONE - psi) + lum_back * (psi - zeta),
            transmittance: zeta,
        }
    }
}

/// Whether all three channels of `v` are equal (a grey attenuation needs
/// one weight computation instead of three).
#[inline(always)]
pub(crate) fn is_grey(v: Vec3A) -> bool {
    v.x == v.y && v.y == v.z
}

/// The weights of a segment, per channel or once when both ends are grey.
#[inline(always)]
pub(crate) fn light_from_weights(
    lum_back: Vec3A,
    lum_front: Vec3A,
    back: Vec3A,
    front: Vec3A,
    weights: impl Fn(f32, f32) -> Weights,
) -> SegmentLight {
    if is_grey(back) && is_grey(front) {
        weights(back.x, front.x).light(lum_back, lum_front)
    } else {
        let w = [0, 1, 2].map(|c| weights(back[c], front[c]));
        Weights::light_rgb(w, lum_back, lum_front)
    }
}
