//! The volume rendering integral along one ray segment (dissertation
//! chapters 2, 3 and 5), by every method the project compares:
//!
//! | method | module | model |
//! | --- | --- | --- |
//! | averaged luminance and attenuation (eq. 3.16) | [`average`] | linear attenuation |
//! | averaged luminance and opacity | [`average`] | linear opacity |
//! | exact, Williams-Max-Stein (eq. 3.28), f64 | [`exact`] | linear attenuation |
//! | partial pre-integration (eq. 5.5, Psi table) | [`ppi`], [`psi`] | linear attenuation |
//! | linear luminance, average opacity (5.3.1) | [`opacity`] | linear opacity |
//! | linear luminance and opacity (5.3.2) | [`opacity`] | linear opacity |
//! | full pre-integration (Roettger/Engel/Schulze) | [`preintegrated`] | linear attenuation |
//! | Riemann sum (eq. 3.13) | [`ScalarIntegrator`] | the transfer function, sampled |
//! | f64 adaptive quadrature (eq. 2.2) | [`reference`](mod@reference) | either |
//!
//! Conventions: a segment runs from its back (far from the eye) to its
//! front; its light is what it emits towards the eye (premultiplied) and its
//! transmittance, per RGB channel. Attenuation `tau` is per unit length.
//!
//! The renderers call [`ScalarIntegrator::integrate`] with the scalar at
//! both ends of a cell segment; it cuts the segment at the transfer
//! function's knots (section 4.3), so that luminance and attenuation are
//! linear on every piece, and applies the chosen method to each piece.

pub mod average;
pub mod colorspace;
mod error;
pub mod exact;
pub mod fastmath;
pub mod grey;
pub mod kernels;
mod knots;
pub mod opacity;
mod paraview;
mod piecewise;
pub mod ppi;
pub mod preintegrated;
pub mod psi;
pub mod reference;
mod scalar;
mod segment;
pub mod special;
mod tf;

pub use error::IntegrateError;
pub use kernels::{KernelVisitor, RIEMANN_MAX_SAMPLES, SegmentKernel, Typed};
pub use knots::{KnotSample, Material, OpacityMode, Piece, TfKnots};
pub use preintegrated::PreintegrationTable;
pub use psi::{GammaSpacing, PsiAt, PsiTable};
pub use scalar::{IntegratorOptions, ScalarIntegrator};
pub use segment::{OpacityParams, SampledSegment, SegmentLight, SegmentParams, Weights};
pub use tetray_core::method::{Method, Model, UnknownMethod};
pub use tf::{ColorPoint, OpacityPoint, TfError, TransferFunction};
