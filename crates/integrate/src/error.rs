//! Errors of the integration crate.

use crate::tf::TfError;
use tetray_core::method::UnknownMethod;

/// Why an integrator could not be set up.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IntegrateError {
    #[error("Psi table size {size} is out of range ({min}..={max} nodes per axis)")]
    PsiTableSize { size: usize, min: usize, max: usize },
    #[error("pre-integration table size {size} is out of range ({min}..={max} nodes per axis)")]
    PreintegrationTableSize { size: usize, min: usize, max: usize },
    #[error("unit distance {0} must be a positive finite length")]
    UnitDistance(f32),
    #[error("Riemann step {0} must be a positive finite length")]
    RiemannStep(f32),
    #[error("pre-integration segment length {0} must be a positive finite length")]
    PreintegrationLength(f32),
    #[error("scalar range [{lo}, {hi}] must be finite with lo <= hi")]
    ScalarRange { lo: f32, hi: f32 },
    #[error(transparent)]
    Method(#[from] UnknownMethod),
    #[error(transparent)]
    TransferFunction(#[from] TfError),
}
