//! The integration methods as kernels whose type fixes the method, so that a
//! renderer's inner loop is compiled once per method with the per-segment
//! work inlined (no per-segment dispatch, no material passed through
//! memory). [`crate::ScalarIntegrator::dispatch`] hands a renderer the
//! kernel of its method.

use glam::Vec3A;

use crate::average::{average_opacity_weights, average_weights};
use crate::exact::exact_weights;
use crate::knots::{KnotSample, Material, TfKnots};
use crate::opacity::{lin_avg_opacity_weights, lin_opacity_weights};
use crate::ppi::ppi_weights;
use crate::preintegrated::PreintegrationTable;
use crate::psi::PsiTable;
use crate::reference;
use crate::segment::{grey_light, light_from_weights, SegmentLight};

/// One piece with linear material: the light between `front` and `back`
/// materials over `length` world units.
pub trait PieceKernel: Sync {
    fn piece(&self, front: &Material, back: &Material, length: f32) -> SegmentLight;
}

/// Partial pre-integration, eq. 5.5 with the Psi table. `GREY`: every
/// knot's attenuation is the same in all channels (transfer functions with
/// one opacity), so one weight computation serves the three channels.
#[derive(Clone, Copy)]
pub struct Ppi<'a, const GREY: bool> {
    pub table: &'a PsiTable,
}

/// Williams-Max-Stein closed form, eq. 3.28 (f64 inside).
#[derive(Clone, Copy)]
pub struct Exact<const GREY: bool>;

/// Averaged luminance and attenuation, eq. 3.16.
#[derive(Clone, Copy)]
pub struct Average<const GREY: bool>;

/// The light of a piece from per-channel weights, computed once when the
/// knots are grey.
#[inline(always)]
fn tau_light<const GREY: bool>(
    front: &Material,
    back: &Material,
    d: f32,
    weights: impl Fn(f32, f32) -> crate::segment::Weights,
) -> SegmentLight {
    if GREY {
        grey_light(back.lum, front.lum, back.tau * d, front.tau * d, weights)
    } else {
        light_from_weights(back.lum, front.lum, back.tau * d, front.tau * d, weights)
    }
}

/// Opacity methods (section 5.3) see lengths in unit distances.
#[derive(Clone, Copy)]
pub struct OpacityKernel {
    pub inv_unit_distance: f32,
    pub method: OpacityMethod,
}

/// The opacity-interpolating approximations.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum OpacityMethod {
    Average,
    LinAverage,
    Linear,
}

/// f64 quadrature of either model.
#[derive(Clone, Copy)]
pub struct Reference {
    pub inv_unit_distance: f32,
    pub opacity_model: bool,
}

impl<const GREY: bool> PieceKernel for Ppi<'_, GREY> {
    #[inline(always)]
    fn piece(&self, front: &Material, back: &Material, d: f32) -> SegmentLight {
        tau_light::<GREY>(front, back, d, |a, b| ppi_weights(self.table, a, b))
    }
}

impl<const GREY: bool> PieceKernel for Exact<GREY> {
    #[inline(always)]
    fn piece(&self, front: &Material, back: &Material, d: f32) -> SegmentLight {
        tau_light::<GREY>(front, back, d, exact_weights)
    }
}

impl<const GREY: bool> PieceKernel for Average<GREY> {
    #[inline(always)]
    fn piece(&self, front: &Material, back: &Material, d: f32) -> SegmentLight {
        tau_light::<GREY>(front, back, d, average_weights)
    }
}

impl PieceKernel for OpacityKernel {
    #[inline(always)]
    fn piece(&self, front: &Material, back: &Material, d: f32) -> SegmentLight {
        let units = d * self.inv_unit_distance;
        let weights = match self.method {
            OpacityMethod::Average => average_opacity_weights,
            OpacityMethod::LinAverage => lin_avg_opacity_weights,
            OpacityMethod::Linear => lin_opacity_weights,
        };
        light_from_weights(back.lum, front.lum, back.alpha, front.alpha, |ab, af| {
            weights(ab, af, units)
        })
    }
}

impl PieceKernel for Reference {
    fn piece(&self, front: &Material, back: &Material, d: f32) -> SegmentLight {
        let mut light = SegmentLight::CLEAR;
        let wide = |v: Vec3A, c: usize| f64::from(v[c]);
        for c in 0..3 {
            let (lb, lf) = (wide(back.lum, c), wide(front.lum, c));
            let r = if self.opacity_model {
                let units = f64::from(d) * f64::from(self.inv_unit_distance);
                reference::opacity_segment(lb, lf, wide(back.alpha, c), wide(front.alpha, c), units)
            } else {
                reference::attenuation_segment(
                    lb,
                    lf,
                    wide(back.tau, c),
                    wide(front.tau, c),
                    f64::from(d),
                )
            };
            light.emitted[c] = r.emitted as f32;
            light.transmittance[c] = r.transmittance as f32;
        }
        light
    }
}

/// A whole segment between two classified scalars.
pub trait SegmentKernel: Sync {
    fn segment(
        &self,
        knots: &TfKnots,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight;
}

/// A piece kernel applied to the pieces of a segment cut at the knots
/// (section 4.3), or to the whole segment when `split` is off.
#[derive(Clone, Copy)]
pub struct Split<P> {
    pub kernel: P,
    pub split: bool,
}

impl<P: PieceKernel> SegmentKernel for Split<P> {
    #[inline(always)]
    fn segment(
        &self,
        knots: &TfKnots,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight {
        // One interval (the common case) or no splitting: a single piece
        // with the samples' own materials.
        if front.interval == back.interval || !self.split {
            return self.kernel.piece(&front.material, &back.material, length);
        }
        let mut light = SegmentLight::CLEAR;
        knots.split(front.scalar, back.scalar, length, |p| {
            light = light.then(self.kernel.piece(&p.front, &p.back, p.length));
        });
        light
    }
}

/// Most samples one Riemann-sum segment takes (a bound on the work of one
/// call; the step is enlarged beyond it).
pub const RIEMANN_MAX_SAMPLES: usize = 1 << 16;

/// Eq. 3.13: homogeneous steps at the midpoints of equal sub-segments, each
/// `L (1 - exp(-tau h))`, composited front to back, the transfer function
/// sampled at each step's scalar.
#[derive(Clone, Copy)]
pub struct Riemann {
    pub step: f32,
}

impl SegmentKernel for Riemann {
    fn segment(
        &self,
        knots: &TfKnots,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight {
        let (s_front, s_back) = (front.scalar, back.scalar);
        let steps = ((length / self.step).ceil() as usize).clamp(1, RIEMANN_MAX_SAMPLES);
        let h = length / steps as f32;
        let mut light = SegmentLight::CLEAR;
        for k in 0..steps {
            let t = (k as f32 + 0.5) / steps as f32;
            let m = knots.at(s_front + (s_back - s_front) * t);
            let zeta = (-m.tau * h).exp();
            light = light.then(SegmentLight {
                emitted: m.lum * (Vec3A::ONE - zeta),
                transmittance: zeta,
            });
        }
        light
    }
}

/// Full pre-integration: a table lookup with the length correction.
#[derive(Clone, Copy)]
pub struct Preintegrated<'a> {
    pub table: &'a PreintegrationTable,
}

impl SegmentKernel for Preintegrated<'_> {
    #[inline(always)]
    fn segment(
        &self,
        _knots: &TfKnots,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight {
        self.table.lookup(front.scalar, back.scalar, length)
    }
}

/// An integrator with its method fixed at compile time: classify scalars
/// with [`Typed::sample`] / [`Typed::sample_near`], integrate segments
/// between samples with [`Typed::integrate_samples`].
#[derive(Clone, Copy)]
pub struct Typed<'a, K> {
    pub knots: &'a TfKnots,
    pub kernel: K,
}

impl<K: SegmentKernel> Typed<'_, K> {
    #[inline(always)]
    pub fn sample(&self, s: f32) -> KnotSample {
        self.knots.sample(s)
    }

    #[inline(always)]
    pub fn sample_near(&self, s: f32, near: &KnotSample) -> KnotSample {
        self.knots.sample_near(s, near)
    }

    /// The light of a segment `length` long between two classified scalars
    /// (front nearer the eye). Zero, negative and NaN lengths carry no
    /// material.
    #[inline(always)]
    pub fn integrate_samples(
        &self,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight {
        if length.is_nan() || length <= 0.0 {
            return SegmentLight::CLEAR;
        }
        self.kernel.segment(self.knots, front, back, length)
    }
}

/// What a renderer does with the integrator once its method's type is
/// known: see [`crate::ScalarIntegrator::dispatch`].
pub trait KernelVisitor {
    type Output;
    fn visit<K: SegmentKernel>(self, integrator: Typed<'_, K>) -> Self::Output;
}
