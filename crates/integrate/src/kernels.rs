//! The integration methods as kernels whose type fixes the method, so that a
//! renderer's inner loop is compiled once per method with the per-segment
//! work inlined (no per-segment dispatch, no material passed through
//! memory). [`crate::ScalarIntegrator::dispatch`] hands a renderer the
//! kernel of its method.
//!
//! Each kernel also fixes how a scalar is classified ([`SegmentKernel::Sample`]):
//! grey knots as one `Vec4` ([`crate::grey`]), per-channel knots as a full
//! [`Material`], the table and sampling methods as the bare scalar.

use glam::{Vec3A, Vec4};
use tetray_wide::Wide;

use crate::average::{average_opacity_weights, average_weights, average_weights_lanes};
use crate::exact::{exact_weights, exact_weights_lanes};
use crate::grey::{GreyKnots, GreySample};
use crate::knots::{KnotSample, Material, TfKnots};
use crate::opacity::{lin_avg_opacity_weights, lin_opacity_weights};
use crate::ppi::{ppi_weights, ppi_weights_lanes};
use crate::preintegrated::PreintegrationTable;
use crate::psi::PsiTable;
use crate::reference;
use crate::segment::{SampledSegment, SegmentLight, Weights, light_from_weights};

/// Per-channel weights of eq. 5.5 from the end values of the method's
/// quantity (`tau D` or opacity) at the back and front.
pub trait WeightKernel: Sync {
    fn weights(&self, back: f32, front: f32, length: f32) -> Weights;
    /// [`WeightKernel::weights`] of `N` segments at once, the same bits per
    /// lane where bit `i` of `live` is set, anything elsewhere (a kernel may
    /// compute every lane as vector arithmetic; this one skips the lanes
    /// that are not live, which pays where a lane's weights cost more than
    /// the branch). `wide` is the token of the AVX2 vectors where the caller
    /// runs the x86-64-v3 build ([`tetray_wide::token`]); the bits are the
    /// same without it.
    #[inline(always)]
    fn weights_lanes<const N: usize>(
        &self,
        back: &[f32; N],
        front: &[f32; N],
        length: &[f32; N],
        live: u32,
        _wide: Option<Wide>,
    ) -> [Weights; N] {
        std::array::from_fn(|i| {
            if live >> i & 1 == 0 {
                Weights {
                    zeta: 1.0,
                    psi: 1.0,
                }
            } else {
                self.weights(back[i], front[i], length[i])
            }
        })
    }
    /// Whether the quantity is the attenuation (multiplied by the length
    /// before `weights`) or the opacity.
    const TAU: bool;
}

/// Partial pre-integration, eq. 5.5 with the Psi table.
#[derive(Clone, Copy)]
pub struct Ppi<'a> {
    pub table: &'a PsiTable,
}

/// Williams-Max-Stein closed form, eq. 3.28 (f64 inside).
#[derive(Clone, Copy)]
pub struct Exact;

/// Averaged luminance and attenuation, eq. 3.16.
#[derive(Clone, Copy)]
pub struct Average;

/// The opacity-interpolating approximations of section 5.3; lengths in unit
/// distances.
#[derive(Clone, Copy)]
pub struct OpacityKernel {
    pub inv_unit_distance: f32,
    pub method: OpacityMethod,
}

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum OpacityMethod {
    Average,
    LinAverage,
    Linear,
}

impl WeightKernel for Ppi<'_> {
    const TAU: bool = true;
    #[inline(always)]
    fn weights(&self, a: f32, b: f32, _length: f32) -> Weights {
        ppi_weights(self.table, a, b)
    }
    #[inline(always)]
    fn weights_lanes<const N: usize>(
        &self,
        back: &[f32; N],
        front: &[f32; N],
        _length: &[f32; N],
        _live: u32,
        wide: Option<Wide>,
    ) -> [Weights; N] {
        ppi_weights_lanes(self.table, back, front, wide)
    }
}

impl WeightKernel for Exact {
    const TAU: bool = true;
    #[inline(always)]
    fn weights(&self, a: f32, b: f32, _length: f32) -> Weights {
        exact_weights(a, b)
    }
    #[inline(always)]
    fn weights_lanes<const N: usize>(
        &self,
        back: &[f32; N],
        front: &[f32; N],
        _length: &[f32; N],
        live: u32,
        _wide: Option<Wide>,
    ) -> [Weights; N] {
        exact_weights_lanes(back, front, live)
    }
}

impl WeightKernel for Average {
    const TAU: bool = true;
    #[inline(always)]
    fn weights(&self, a: f32, b: f32, _length: f32) -> Weights {
        average_weights(a, b)
    }
    /// Every lane, as vector arithmetic (cheaper than skipping any).
    #[inline(always)]
    fn weights_lanes<const N: usize>(
        &self,
        back: &[f32; N],
        front: &[f32; N],
        _length: &[f32; N],
        _live: u32,
        _wide: Option<Wide>,
    ) -> [Weights; N] {
        average_weights_lanes(back, front)
    }
}

impl WeightKernel for OpacityKernel {
    const TAU: bool = false;
    #[inline(always)]
    fn weights(&self, alpha_back: f32, alpha_front: f32, length: f32) -> Weights {
        let units = length * self.inv_unit_distance;
        match self.method {
            OpacityMethod::Average => average_opacity_weights(alpha_back, alpha_front, units),
            OpacityMethod::LinAverage => lin_avg_opacity_weights(alpha_back, alpha_front, units),
            OpacityMethod::Linear => lin_opacity_weights(alpha_back, alpha_front, units),
        }
    }
}

/// f64 quadrature of either model, per channel.
#[derive(Clone, Copy)]
pub struct Reference {
    pub inv_unit_distance: f32,
    pub opacity_model: bool,
}

impl Reference {
    fn piece(&self, front: &Material, back: &Material, d: f32) -> SegmentLight {
        let mut light = SegmentLight::CLEAR;
        let wide = |v: Vec3A, c: usize| f64::from(v[c]);
        for c in 0..3 {
            let (lb, lf) = (wide(back.lum, c), wide(front.lum, c));
            let r = if self.opacity_model {
                let units = f64::from(d) * f64::from(self.inv_unit_distance);
                reference::opacity_segment(lb, lf, wide(back.alpha, c), wide(front.alpha, c), units)
            } else {
                let (tb, tf) = (wide(back.tau, c), wide(front.tau, c));
                reference::attenuation_segment(lb, lf, tb, tf, f64::from(d))
            };
            light.emitted[c] = r.emitted as f32;
            light.transmittance[c] = r.transmittance as f32;
        }
        light
    }
}

/// A whole segment between two classified scalars.
pub trait SegmentKernel: Sync {
    /// What the kernel keeps of a classified scalar.
    type Sample: Copy + Default;
    fn sample(&self, knots: &TfKnots, s: f32) -> Self::Sample;
    fn sample_near(&self, knots: &TfKnots, s: f32, near: &Self::Sample) -> Self::Sample;
    fn segment(
        &self,
        knots: &TfKnots,
        front: &Self::Sample,
        back: &Self::Sample,
        length: f32,
    ) -> SegmentLight;
    /// The light of `N` segments, one per ray in flight, written into
    /// `lights`: lane `i` as [`Typed::integrate_samples`] would give it
    /// where bit `i` of `live` is set, anything elsewhere. A kernel may
    /// integrate its lanes together, with the AVX2 vectors where `wide`
    /// holds their token (the same bits). (Written in place: an array of
    /// lights returned by value is copied whole on the way out.)
    #[inline(always)]
    fn segments<const N: usize>(
        &self,
        knots: &TfKnots,
        batch: &[SampledSegment<Self::Sample>; N],
        live: u32,
        lights: &mut [SegmentLight; N],
        _wide: Option<Wide>,
    ) {
        for (i, (light, s)) in lights.iter_mut().zip(batch).enumerate() {
            *light = if live >> i & 1 == 0 || !carries_material(s.length) {
                SegmentLight::CLEAR
            } else {
                self.segment(knots, &s.front, &s.back, s.length)
            };
        }
    }
}

/// Whether a segment of this length has material: zero, negative and NaN
/// lengths carry none.
#[inline(always)]
fn carries_material(length: f32) -> bool {
    !(length.is_nan() || length <= 0.0)
}

/// A weight kernel on grey knots: pieces cut at the knots (section 4.3)
/// unless `split` is off, one weight computation per piece.
#[derive(Clone, Copy)]
pub struct Grey<'a, W> {
    pub knots: &'a GreyKnots,
    pub kernel: W,
    pub split: bool,
}

impl<W: WeightKernel> Grey<'_, W> {
    /// Whether a segment between these samples is integrated as one piece:
    /// within one knot interval (the common case), or with no splitting.
    #[inline(always)]
    fn one_piece(&self, front: &GreySample, back: &GreySample) -> bool {
        front.interval() == back.interval() || !self.split
    }

    #[inline(always)]
    fn piece(&self, front: Vec4, back: Vec4, d: f32) -> SegmentLight {
        let scale = if W::TAU { d } else { 1.0 };
        let w = self.kernel.weights(back.w * scale, front.w * scale, d);
        w.light(Vec3A::from_vec4(back), Vec3A::from_vec4(front))
    }
}

impl<W: WeightKernel> SegmentKernel for Grey<'_, W> {
    type Sample = GreySample;

    #[inline(always)]
    fn sample(&self, _knots: &TfKnots, s: f32) -> GreySample {
        self.knots.sample(s)
    }

    #[inline(always)]
    fn sample_near(&self, _knots: &TfKnots, s: f32, near: &GreySample) -> GreySample {
        self.knots.sample_near(s, near)
    }

    #[inline(always)]
    fn segment(
        &self,
        _knots: &TfKnots,
        front: &GreySample,
        back: &GreySample,
        length: f32,
    ) -> SegmentLight {
        // A single piece with the samples' own materials.
        if self.one_piece(front, back) {
            return self.piece(front.material, back.material, length);
        }
        let mut light = SegmentLight::CLEAR;
        self.knots.split(front, back, length, |f, b, d| {
            light = light.then(self.piece(f, b, d));
        });
        light
    }

    /// The weights of every lane at once, as one piece each; the rare lane
    /// that crosses a knot is then integrated alone, piece by piece.
    #[inline(always)]
    fn segments<const N: usize>(
        &self,
        knots: &TfKnots,
        batch: &[SampledSegment<GreySample>; N],
        live: u32,
        lights: &mut [SegmentLight; N],
        wide: Option<Wide>,
    ) {
        let scale = |i: usize| if W::TAU { batch[i].length } else { 1.0 };
        let back: [f32; N] = std::array::from_fn(|i| batch[i].back.material.w * scale(i));
        let front: [f32; N] = std::array::from_fn(|i| batch[i].front.material.w * scale(i));
        // By index: `batch.map` would copy the whole batch first.
        let length: [f32; N] = std::array::from_fn(|i| batch[i].length);
        let weights = self
            .kernel
            .weights_lanes(&back, &front, &length, live, wide);
        // Every lane's light, live or not, so that the lanes' arithmetic
        // stays in vectors; then the rare lane without material or across
        // a knot is redone alone.
        for (i, light) in lights.iter_mut().enumerate() {
            *light = weights[i].light(batch[i].back.lum(), batch[i].front.lum());
        }
        // The lanes to redo, found without branches (a plain loop of
        // compares the compiler unrolls), then redone one by one.
        let mut redo = 0u32;
        for (i, s) in batch.iter().enumerate() {
            let whole = self.one_piece(&s.front, &s.back) & carries_material(s.length);
            redo |= u32::from(!whole) << i;
        }
        redo &= live;
        while redo != 0 {
            let i = redo.trailing_zeros() as usize;
            redo &= redo - 1;
            let s = &batch[i];
            lights[i] = if carries_material(s.length) {
                self.segment(knots, &s.front, &s.back, s.length)
            } else {
                SegmentLight::CLEAR
            };
        }
    }
}

/// A weight kernel on per-channel knots (attenuation differing by channel).
#[derive(Clone, Copy)]
pub struct Rgb<W> {
    pub kernel: W,
    pub split: bool,
}

impl<W: WeightKernel> Rgb<W> {
    #[inline(always)]
    fn piece(&self, front: &Material, back: &Material, d: f32) -> SegmentLight {
        let (qb, qf) = if W::TAU {
            (back.tau * d, front.tau * d)
        } else {
            (back.alpha, front.alpha)
        };
        light_from_weights(back.lum, front.lum, qb, qf, |b, f| {
            self.kernel.weights(b, f, d)
        })
    }
}

/// Material knots split at the knots: what [`Rgb`] and [`Reference`] share.
fn split_material(
    knots: &TfKnots,
    split: bool,
    front: &KnotSample,
    back: &KnotSample,
    length: f32,
    piece: impl Fn(&Material, &Material, f32) -> SegmentLight,
) -> SegmentLight {
    if front.interval == back.interval || !split {
        return piece(&front.material, &back.material, length);
    }
    let mut light = SegmentLight::CLEAR;
    knots.split(front.scalar, back.scalar, length, |p| {
        light = light.then(piece(&p.front, &p.back, p.length));
    });
    light
}

impl<W: WeightKernel> SegmentKernel for Rgb<W> {
    type Sample = KnotSample;

    #[inline(always)]
    fn sample(&self, knots: &TfKnots, s: f32) -> KnotSample {
        knots.sample(s)
    }

    #[inline(always)]
    fn sample_near(&self, knots: &TfKnots, s: f32, near: &KnotSample) -> KnotSample {
        knots.sample_near(s, near)
    }

    #[inline(always)]
    fn segment(
        &self,
        knots: &TfKnots,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight {
        split_material(knots, self.split, front, back, length, |f, b, d| {
            self.piece(f, b, d)
        })
    }
}

/// The f64 reference, cut at the knots like the other methods.
#[derive(Clone, Copy)]
pub struct ReferenceSplit {
    pub reference: Reference,
    pub split: bool,
}

impl SegmentKernel for ReferenceSplit {
    type Sample = KnotSample;

    fn sample(&self, knots: &TfKnots, s: f32) -> KnotSample {
        knots.sample(s)
    }

    fn sample_near(&self, knots: &TfKnots, s: f32, near: &KnotSample) -> KnotSample {
        knots.sample_near(s, near)
    }

    fn segment(
        &self,
        knots: &TfKnots,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight {
        split_material(knots, self.split, front, back, length, |f, b, d| {
            self.reference.piece(f, b, d)
        })
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
    type Sample = f32;

    fn sample(&self, _knots: &TfKnots, s: f32) -> f32 {
        s
    }

    fn sample_near(&self, _knots: &TfKnots, s: f32, _near: &f32) -> f32 {
        s
    }

    fn segment(&self, knots: &TfKnots, &s_front: &f32, &s_back: &f32, length: f32) -> SegmentLight {
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
    type Sample = f32;

    #[inline(always)]
    fn sample(&self, _knots: &TfKnots, s: f32) -> f32 {
        s
    }

    #[inline(always)]
    fn sample_near(&self, _knots: &TfKnots, s: f32, _near: &f32) -> f32 {
        s
    }

    #[inline(always)]
    fn segment(&self, _knots: &TfKnots, &front: &f32, &back: &f32, length: f32) -> SegmentLight {
        self.table.lookup(front, back, length)
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
    pub fn sample(&self, s: f32) -> K::Sample {
        self.kernel.sample(self.knots, s)
    }

    #[inline(always)]
    pub fn sample_near(&self, s: f32, near: &K::Sample) -> K::Sample {
        self.kernel.sample_near(self.knots, s, near)
    }

    /// The light of a segment `length` long between two classified scalars
    /// (front nearer the eye). Zero, negative and NaN lengths carry no
    /// material.
    #[inline(always)]
    pub fn integrate_samples(
        &self,
        front: &K::Sample,
        back: &K::Sample,
        length: f32,
    ) -> SegmentLight {
        if !carries_material(length) {
            return SegmentLight::CLEAR;
        }
        self.kernel.segment(self.knots, front, back, length)
    }

    /// [`Typed::integrate_samples`] of the segments of several rays at
    /// once: lane `i` where bit `i` of `live` is set, anything elsewhere;
    /// `wide` as in [`SegmentKernel::segments`].
    #[inline(always)]
    pub fn integrate_batch<const N: usize>(
        &self,
        batch: &[SampledSegment<K::Sample>; N],
        live: u32,
        lights: &mut [SegmentLight; N],
        wide: Option<Wide>,
    ) {
        self.kernel.segments(self.knots, batch, live, lights, wide)
    }
}

/// What a renderer does with the integrator once its method's type is
/// known: see [`crate::ScalarIntegrator::dispatch`].
pub trait KernelVisitor {
    type Output;
    fn visit<K: SegmentKernel>(self, integrator: Typed<'_, K>) -> Self::Output;
}
