//! One ray segment integrated by any method, as `tetray segment` and the
//! Python package's `segment` do: luminance and attenuation given at its
//! back and front, the tables and steps sized for this one segment.

use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, SegmentLight, SegmentParams};

use crate::error::{Context, EngineError};

/// The sizes of the tables and steps; `None`: the defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentOptions {
    pub unit_distance: f32,
    pub psi_size: usize,
    /// `None`: the segment's length over 256.
    pub riemann_step: Option<f32>,
    pub preintegration_size: usize,
}

/// The light `method` gives `segment` (a zero length emits nothing).
pub fn segment(
    method: Method,
    segment: &SegmentParams,
    options: &SegmentOptions,
) -> Result<SegmentLight, EngineError> {
    let length_or_one = if segment.length > 0.0 {
        segment.length
    } else {
        1.0
    };
    let integrator_options = IntegratorOptions {
        unit_distance: options.unit_distance,
        psi_table_size: options.psi_size,
        riemann_step: options.riemann_step.unwrap_or(length_or_one / 256.0),
        preintegration_table_size: options.preintegration_size,
        preintegration_length: length_or_one,
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::for_segment(method, segment, &integrator_options)
        .with_context(|| format!("setting up the {method} integrator"))?;
    // The knots put the back at scalar 0 and the front at scalar 1.
    Ok(integrator.integrate(1.0, 0.0, segment.length))
}
