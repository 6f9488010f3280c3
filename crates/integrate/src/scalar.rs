//! [`ScalarIntegrator`]: the light of a ray segment across which the scalar
//! varies linearly, for a transfer function and a method. This is what the
//! ray casters call once per cell.

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec3;

use crate::average::{average_opacity_weights, average_weights};
use crate::exact::exact_weights;
use crate::knots::{KnotSample, Material, OpacityMode, Piece, TfKnots};
use crate::method::Method;
use crate::opacity::{lin_avg_opacity_weights, lin_opacity_weights};
use crate::ppi::ppi_weights;
use crate::preintegrated::PreintegrationTable;
use crate::psi::{GammaSpacing, PsiTable, PSI_TABLE_DEFAULT};
use crate::reference;
use crate::segment::{light_from_weights, SegmentLight, SegmentParams};
use crate::tf::TransferFunction;
use crate::IntegrateError;

/// Most samples one Riemann-sum segment takes (a bound on the work of one
/// call; the step is enlarged beyond it).
pub const RIEMANN_MAX_SAMPLES: usize = 1 << 16;

/// Settings of a [`ScalarIntegrator`].
#[derive(Debug, Clone, PartialEq)]
pub struct IntegratorOptions {
    /// Opacity unit distance `u` (world units): a transfer-function opacity
    /// is the opacity of `u` of material.
    pub unit_distance: f32,
    pub opacity_mode: OpacityMode,
    /// Psi table nodes per axis.
    pub psi_table_size: usize,
    pub psi_spacing: GammaSpacing,
    /// Step of the Riemann sum (world units).
    pub riemann_step: f32,
    /// Full pre-integration: table nodes per axis, the segment length it
    /// holds (world units), and its scalar range (default: the transfer
    /// function's).
    pub preintegration_table_size: usize,
    pub preintegration_length: f32,
    pub scalar_range: Option<(f32, f32)>,
    /// Cut segments at transfer-function knots (adaptive transfer function
    /// sampling, section 4.3). Off only to study what it buys.
    pub split_at_knots: bool,
}

impl Default for IntegratorOptions {
    fn default() -> Self {
        IntegratorOptions {
            unit_distance: 1.0,
            opacity_mode: OpacityMode::Exact,
            psi_table_size: PSI_TABLE_DEFAULT,
            psi_spacing: GammaSpacing::default(),
            riemann_step: 0.25,
            preintegration_table_size: 256,
            preintegration_length: 1.0,
            scalar_range: None,
            split_at_knots: true,
        }
    }
}

/// Integrates segments with a linear scalar through a transfer function.
#[derive(Debug, Clone)]
pub struct ScalarIntegrator {
    method: Method,
    knots: TfKnots,
    unit_distance: f32,
    split: bool,
    riemann_step: f32,
    psi: Option<Arc<PsiTable>>,
    preintegration: Option<PreintegrationTable>,
    setup_time: Duration,
}

impl ScalarIntegrator {
    /// Sets up `method` for `tf`, building the tables it needs (the Psi
    /// table is shared process-wide; the pre-integration table is rebuilt
    /// for every transfer function).
    pub fn new(
        method: Method,
        tf: &TransferFunction,
        options: &IntegratorOptions,
    ) -> Result<ScalarIntegrator, IntegrateError> {
        check_length(options.unit_distance, IntegrateError::UnitDistance)?;
        let knots = TfKnots::new(tf, options.unit_distance, options.opacity_mode);
        let range = options.scalar_range.unwrap_or_else(|| tf.scalar_range());
        Self::from_knots(method, knots, range, options)
    }

    /// Sets up `method` for knots given directly; `range` is the scalar
    /// range of the pre-integration table.
    pub fn from_knots(
        method: Method,
        knots: TfKnots,
        range: (f32, f32),
        options: &IntegratorOptions,
    ) -> Result<ScalarIntegrator, IntegrateError> {
        let start = Instant::now();
        check_length(options.unit_distance, IntegrateError::UnitDistance)?;
        check_length(options.riemann_step, IntegrateError::RiemannStep)?;
        let psi = match method {
            Method::Ppi if options.psi_spacing == GammaSpacing::default() => {
                Some(PsiTable::shared(options.psi_table_size)?)
            }
            Method::Ppi => Some(Arc::new(PsiTable::build(
                options.psi_table_size,
                options.psi_spacing,
            )?)),
            _ => None,
        };
        let preintegration = match method {
            Method::Preintegrated => Some(PreintegrationTable::build(
                &knots,
                range,
                options.preintegration_table_size,
                options.preintegration_length,
            )?),
            _ => None,
        };
        Ok(ScalarIntegrator {
            method,
            knots,
            unit_distance: options.unit_distance,
            split: options.split_at_knots,
            riemann_step: options.riemann_step,
            psi,
            preintegration,
            setup_time: start.elapsed(),
        })
    }

    /// An integrator of a single segment given by its end materials: the
    /// knots are `back` at scalar 0 and `front` at scalar 1, so
    /// `integrate(1.0, 0.0, length)` is that segment. Opacities for the
    /// opacity methods are `1 - exp(-tau u)`.
    pub fn for_segment(
        method: Method,
        params: &SegmentParams,
        options: &IntegratorOptions,
    ) -> Result<ScalarIntegrator, IntegrateError> {
        let u = options.unit_distance;
        check_length(u, IntegrateError::UnitDistance)?;
        let material = |lum: Vec3, tau: Vec3| Material {
            lum,
            tau,
            alpha: (Vec3::ONE - (-tau * u).exp()).min(Vec3::splat(crate::opacity::ALPHA_MAX)),
        };
        let knots = TfKnots::from_materials(vec![
            (0.0, material(params.lum_back, params.tau_back)),
            (1.0, material(params.lum_front, params.tau_front)),
        ]);
        Self::from_knots(method, knots, (0.0, 1.0), options)
    }

    pub fn method(&self) -> Method {
        self.method
    }

    pub fn knots(&self) -> &TfKnots {
        &self.knots
    }

    /// The Psi table (partial pre-integration only).
    pub fn psi_table(&self) -> Option<&PsiTable> {
        self.psi.as_deref()
    }

    /// The pre-integration table (full pre-integration only).
    pub fn preintegration_table(&self) -> Option<&PreintegrationTable> {
        self.preintegration.as_ref()
    }

    /// Time spent building tables in the constructor.
    pub fn setup_time(&self) -> Duration {
        self.setup_time
    }

    /// The light of a segment `length` long whose scalar goes linearly from
    /// `s_front` (the end nearer the eye) to `s_back`.
    #[inline]
    pub fn integrate(&self, s_front: f32, s_back: f32, length: f32) -> SegmentLight {
        self.integrate_samples(&self.sample(s_front), &self.sample(s_back), length)
    }

    /// A scalar classified for [`ScalarIntegrator::integrate_samples`].
    #[inline]
    pub fn sample(&self, s: f32) -> KnotSample {
        self.knots.sample(s)
    }

    /// [`ScalarIntegrator::sample`] of a scalar close to `near`'s.
    #[inline]
    pub fn sample_near(&self, s: f32, near: &KnotSample) -> KnotSample {
        self.knots.sample_near(s, near)
    }

    /// [`ScalarIntegrator::integrate`] with both end scalars classified (a
    /// ray walk classifies each face crossing once, for the two segments
    /// meeting there).
    #[inline]
    pub fn integrate_samples(
        &self,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
    ) -> SegmentLight {
        // Zero, negative and NaN lengths carry no material.
        if length.is_nan() || length <= 0.0 {
            return SegmentLight::CLEAR;
        }
        match self.method {
            Method::Riemann => self.riemann(front.scalar, back.scalar, length),
            Method::Preintegrated => match &self.preintegration {
                Some(table) => table.lookup(front.scalar, back.scalar, length),
                None => unreachable!("built with the integrator"),
            },
            _ if self.split => {
                let mut light = SegmentLight::CLEAR;
                self.knots
                    .split_samples(front, back, length, |p| light = light.then(self.piece(p)));
                light
            }
            _ => self.piece(&Piece {
                front: front.material,
                back: back.material,
                length,
            }),
        }
    }

    /// One piece with linear material.
    #[inline]
    fn piece(&self, p: &Piece) -> SegmentLight {
        let (front, back, d) = (&p.front, &p.back, p.length);
        let units = d / self.unit_distance;
        let tau = |w: fn(f32, f32) -> crate::segment::Weights| {
            light_from_weights(back.lum, front.lum, back.tau * d, front.tau * d, w)
        };
        let opacity = |w: fn(f32, f32, f32) -> crate::segment::Weights| {
            light_from_weights(back.lum, front.lum, back.alpha, front.alpha, |ab, af| {
                w(ab, af, units)
            })
        };
        match self.method {
            Method::Ppi => {
                let table = self.psi.as_deref().expect("built with the integrator");
                light_from_weights(back.lum, front.lum, back.tau * d, front.tau * d, |a, b| {
                    ppi_weights(table, a, b)
                })
            }
            Method::Exact => tau(exact_weights),
            Method::Average => tau(average_weights),
            Method::AverageOpacity => opacity(average_opacity_weights),
            Method::LinAvgOpacity => opacity(lin_avg_opacity_weights),
            Method::LinOpacity => opacity(lin_opacity_weights),
            Method::Reference => reference_light(p, |c| {
                reference::attenuation_segment(
                    f64::from(back.lum[c]),
                    f64::from(front.lum[c]),
                    f64::from(back.tau[c]),
                    f64::from(front.tau[c]),
                    f64::from(d),
                )
            }),
            Method::ReferenceOpacity => reference_light(p, |c| {
                reference::opacity_segment(
                    f64::from(back.lum[c]),
                    f64::from(front.lum[c]),
                    f64::from(back.alpha[c]),
                    f64::from(front.alpha[c]),
                    f64::from(units),
                )
            }),
            Method::Riemann | Method::Preintegrated => unreachable!("not split into pieces"),
        }
    }

    /// Eq. 3.13: homogeneous steps at the midpoints of equal sub-segments,
    /// each `L (1 - exp(-tau h))`, composited front to back. The transfer
    /// function is sampled at each step's scalar.
    fn riemann(&self, s_front: f32, s_back: f32, length: f32) -> SegmentLight {
        let steps = ((length / self.riemann_step).ceil() as usize).clamp(1, RIEMANN_MAX_SAMPLES);
        let h = length / steps as f32;
        let mut light = SegmentLight::CLEAR;
        for k in 0..steps {
            let t = (k as f32 + 0.5) / steps as f32;
            let m = self.knots.at(s_front + (s_back - s_front) * t);
            let zeta = (-m.tau * h).exp();
            light = light.then(SegmentLight {
                emitted: m.lum * (Vec3::ONE - zeta),
                transmittance: zeta,
            });
        }
        light
    }
}

/// A piece integrated per channel in f64.
fn reference_light(_p: &Piece, channel: impl Fn(usize) -> reference::ReferenceLight) -> SegmentLight {
    let mut light = SegmentLight::CLEAR;
    for c in 0..3 {
        let r = channel(c);
        light.emitted[c] = r.emitted as f32;
        light.transmittance[c] = r.transmittance as f32;
    }
    light
}

fn check_length(value: f32, error: fn(f32) -> IntegrateError) -> Result<(), IntegrateError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(error(value))
    }
}
