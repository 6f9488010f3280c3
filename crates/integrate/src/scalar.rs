//! [`ScalarIntegrator`]: the light of a ray segment across which the scalar
//! varies linearly, for a transfer function and a method. This is what the
//! ray casters call once per cell.

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec3;

use crate::IntegrateError;
use crate::grey::{GreyKnots, Lane};
use crate::kernels::{
    Average, Exact, Grey, KernelVisitor, OpacityKernel, OpacityMethod, Ppi, Preintegrated,
    Reference, ReferenceSplit, Rgb, Riemann, SegmentKernel, Typed,
};
use crate::knots::{Material, OpacityMode, TfKnots};
use crate::preintegrated::PreintegrationTable;
use crate::psi::{GammaSpacing, PsiTable};
use crate::segment::{SegmentLight, SegmentParams};
use crate::tf::TransferFunction;
use tetray_core::defaults::{PREINTEGRATION_TABLE_SIZE, PSI_TABLE_SIZE};
use tetray_core::method::Method;

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
            psi_table_size: PSI_TABLE_SIZE,
            psi_spacing: GammaSpacing::default(),
            riemann_step: 0.25,
            preintegration_table_size: PREINTEGRATION_TABLE_SIZE,
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
    /// The knots in 4-lane form for the attenuation and the opacity
    /// methods, when they are grey.
    grey_tau: Option<GreyKnots>,
    grey_alpha: Option<GreyKnots>,
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
            grey_tau: GreyKnots::new(&knots, Lane::Tau),
            grey_alpha: GreyKnots::new(&knots, Lane::Alpha),
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
            lum: lum.into(),
            tau: tau.into(),
            alpha: (Vec3::ONE - (-tau * u).exp())
                .min(Vec3::splat(crate::opacity::ALPHA_MAX))
                .into(),
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

    /// The opacity unit distance (world units).
    pub fn unit_distance(&self) -> f32 {
        self.unit_distance
    }

    /// The Riemann sum's step (world units).
    pub fn riemann_step(&self) -> f32 {
        self.riemann_step
    }

    /// Whether segments are cut at the knots.
    pub fn splits_at_knots(&self) -> bool {
        self.split
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
    /// `s_front` (the end nearer the eye) to `s_back`. Dispatches on the
    /// method per call: inner loops should use [`ScalarIntegrator::dispatch`].
    pub fn integrate(&self, s_front: f32, s_back: f32, length: f32) -> SegmentLight {
        struct One {
            s_front: f32,
            s_back: f32,
            length: f32,
        }
        impl KernelVisitor for One {
            type Output = SegmentLight;
            fn visit<K: SegmentKernel>(self, integrator: Typed<'_, K>) -> SegmentLight {
                let front = integrator.sample(self.s_front);
                let back = integrator.sample(self.s_back);
                integrator.integrate_samples(&front, &back, self.length)
            }
        }
        self.dispatch(One {
            s_front,
            s_back,
            length,
        })
    }

    /// Calls `visitor` with this integrator's method fixed in its type, so
    /// that the visitor's loops are compiled for that method alone.
    pub fn dispatch<V: KernelVisitor>(&self, visitor: V) -> V::Output {
        let knots = &self.knots;
        let split = self.split;
        let inv_unit_distance = 1.0 / self.unit_distance;
        let opacity = |method| OpacityKernel {
            inv_unit_distance,
            method,
        };
        let reference = |opacity_model| ReferenceSplit {
            reference: Reference {
                inv_unit_distance,
                opacity_model,
            },
            split,
        };
        macro_rules! weights {
            ($grey:expr, $kernel:expr) => {
                match $grey {
                    Some(grey) => visitor.visit(Typed {
                        knots,
                        kernel: Grey {
                            knots: grey,
                            kernel: $kernel,
                            split,
                        },
                    }),
                    None => visitor.visit(Typed {
                        knots,
                        kernel: Rgb {
                            kernel: $kernel,
                            split,
                        },
                    }),
                }
            };
        }
        let tau = self.grey_tau.as_ref();
        let alpha = self.grey_alpha.as_ref();
        match self.method {
            Method::Ppi => {
                let table = self.psi.as_deref().expect("built with the integrator");
                weights!(tau, Ppi { table })
            }
            Method::Exact => weights!(tau, Exact),
            Method::Average => weights!(tau, Average),
            Method::AverageOpacity => weights!(alpha, opacity(OpacityMethod::Average)),
            Method::LinAvgOpacity => weights!(alpha, opacity(OpacityMethod::LinAverage)),
            Method::LinOpacity => weights!(alpha, opacity(OpacityMethod::Linear)),
            Method::Reference => visitor.visit(Typed {
                knots,
                kernel: reference(false),
            }),
            Method::ReferenceOpacity => visitor.visit(Typed {
                knots,
                kernel: reference(true),
            }),
            Method::Riemann => visitor.visit(Typed {
                knots,
                kernel: Riemann {
                    step: self.riemann_step,
                },
            }),
            Method::Preintegrated => {
                let table = self
                    .preintegration
                    .as_ref()
                    .expect("built with the integrator");
                visitor.visit(Typed {
                    knots,
                    kernel: Preintegrated { table },
                })
            }
        }
    }
}

fn check_length(value: f32, error: fn(f32) -> IntegrateError) -> Result<(), IntegrateError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(error(value))
    }
}
