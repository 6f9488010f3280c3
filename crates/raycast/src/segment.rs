//! What the walk asks of an integrator: the light of one ray segment
//! (dissertation ch. 2), one segment or several in flight at once.

use glam::Vec3A;
use tetray_integrate::{SampledSegment, SegmentLight};
use tetray_wide::Wide;

/// The light of one ray segment, front (nearer the eye) to back.
///
/// The walk classifies the scalar at every face it crosses once
/// ([`SegmentIntegrator::sample`]) and passes the classified values of both
/// ends to [`SegmentIntegrator::segment`]: the back of one segment is the
/// front of the next.
pub trait SegmentIntegrator: Sync {
    /// What the integrator keeps of a scalar value.
    type Sample: Copy + Default;

    /// Classifies the scalar `s`.
    fn sample(&self, s: f32) -> Self::Sample;

    /// Classifies `s`, known to be close to the value of `near`.
    #[inline]
    fn sample_near(&self, s: f32, near: &Self::Sample) -> Self::Sample {
        let _ = near;
        self.sample(s)
    }

    /// Emitted light reaching the segment's front end and the segment's
    /// transmittance, for a scalar linear from `front` to `back` over
    /// `length` world units.
    fn segment(&self, front: &Self::Sample, back: &Self::Sample, length: f32) -> (Vec3A, Vec3A);

    /// [`SegmentIntegrator::segment`] of the segments of several rays in
    /// flight, written into `lights`: lane `i` where bit `i` of `live` is
    /// set, anything elsewhere. An integrator may integrate its lanes
    /// together, to the same bits, with the AVX2 vectors where `wide`
    /// holds their token ([`tetray_wide::token`]).
    #[inline(always)]
    fn segments<const N: usize>(
        &self,
        batch: &[SampledSegment<Self::Sample>; N],
        live: u32,
        lights: &mut [SegmentLight; N],
        _wide: Option<Wide>,
    ) {
        for (i, (light, s)) in lights.iter_mut().zip(batch).enumerate() {
            *light = if live >> i & 1 == 0 {
                SegmentLight::CLEAR
            } else {
                let (emitted, transmittance) = self.segment(&s.front, &s.back, s.length);
                SegmentLight {
                    emitted,
                    transmittance,
                }
            };
        }
    }
}

/// An integrator with its method fixed in its type (see
/// `ScalarIntegrator::dispatch`): the walk's inner loop is compiled per
/// method.
impl<K: tetray_integrate::SegmentKernel> SegmentIntegrator for tetray_integrate::Typed<'_, K> {
    type Sample = K::Sample;

    #[inline(always)]
    fn sample(&self, s: f32) -> Self::Sample {
        tetray_integrate::Typed::sample(self, s)
    }

    #[inline(always)]
    fn sample_near(&self, s: f32, near: &Self::Sample) -> Self::Sample {
        tetray_integrate::Typed::sample_near(self, s, near)
    }

    #[inline(always)]
    fn segment(&self, front: &Self::Sample, back: &Self::Sample, length: f32) -> (Vec3A, Vec3A) {
        let light = self.integrate_samples(front, back, length);
        (light.emitted, light.transmittance)
    }

    #[inline(always)]
    fn segments<const N: usize>(
        &self,
        batch: &[SampledSegment<Self::Sample>; N],
        live: u32,
        lights: &mut [SegmentLight; N],
        wide: Option<Wide>,
    ) {
        self.integrate_batch(batch, live, lights, wide)
    }
}
