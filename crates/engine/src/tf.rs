//! The transfer function and the integrator of a frame, with the defaults
//! every front end shares: the default ramp over the field's range, a
//! uniform volume for a constant field, ParaView presets rescaled to the
//! range, the tables sized by the mesh's mean tetrahedron chord.

use std::time::Duration;

use glam::Vec3;
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityMode, OpacityPoint, ScalarIntegrator,
    TransferFunction,
};

use crate::error::{Context, EngineError, bail};
use crate::fields::SOLID;
use crate::options::{IntegratorChoice, Log, TfSource};

/// The transfer function of `source`: a ParaView preset (rescaled to the
/// field's range `(lo, hi)` unless asked not to), control points, a uniform
/// volume for a constant field (whose opacity lets 30% of the light through
/// the `bounds` diagonal), else the default ramp over the range.
pub fn transfer_function(
    source: &TfSource,
    field: &str,
    (lo, hi): (f32, f32),
    bounds: (Vec3, Vec3),
    unit_distance: f32,
    log: Log<'_>,
) -> Result<TransferFunction, EngineError> {
    match source {
        TfSource::ParaView {
            text,
            name,
            rescale,
            label,
        } => {
            let rescale = rescale.then_some((lo, hi));
            return TransferFunction::from_paraview_json(text, name.as_deref(), rescale)
                .context(label.clone());
        }
        TfSource::Points { color, opacity } => return from_points(color.clone(), opacity.clone()),
        TfSource::Normalized {
            color,
            opacity,
            range: Some(range),
        } => return normalized(color, opacity, *range),
        TfSource::Normalized { color, opacity, .. } if lo < hi => {
            return normalized(color, opacity, (lo, hi));
        }
        _ => {}
    }
    // A constant field (the Oxygen Post's density is 1 everywhere) would
    // get no opacity from the default ramp: an empty image.
    if lo == hi {
        let (lo_b, hi_b) = bounds;
        let unit_lengths = (hi_b - lo_b).length() / unit_distance;
        let alpha = solid_alpha(unit_lengths);
        if field != SOLID {
            (log.warn)(format!(
                "field {field:?} is constant ({lo}): rendering a uniform volume (ParaView's \
                 Solid Color) of opacity {alpha} per unit distance; pick another field \
                 (`tetray info` lists them)"
            ));
        }
        return Ok(solid_color(lo, alpha));
    }
    Ok(default_ramp((lo, hi)))
}

/// The transfer function of control points at the field's own values (an
/// editor's curve).
pub fn from_points(
    color: Vec<ColorPoint>,
    opacity: Vec<OpacityPoint>,
) -> Result<TransferFunction, EngineError> {
    TransferFunction::new(color, opacity).context("the transfer function")
}

/// The default ramp over `(lo, hi)`: cool to warm, opacity rising.
pub fn default_ramp((lo, hi): (f32, f32)) -> TransferFunction {
    TransferFunction::default_for_range(lo, hi)
}

/// A ParaView preset (`name`: which one when the JSON holds several),
/// rescaled to `rescale` when given, with the preset reader's warnings.
pub fn paraview_preset(
    text: &str,
    name: Option<&str>,
    rescale: Option<(f32, f32)>,
) -> Result<(TransferFunction, Vec<String>), EngineError> {
    TransferFunction::from_paraview_json_with_report(text, name, rescale)
        .map_err(|e| EngineError::Options(e.to_string()))
}

/// Points over [0, 1] mapped onto `[lo, hi]`; none at all: the default
/// ramp over `[lo, hi]`.
fn normalized(
    color: &[ColorPoint],
    opacity: &[OpacityPoint],
    (lo, hi): (f32, f32),
) -> Result<TransferFunction, EngineError> {
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        bail!("the colour range must be two finite numbers, low < high; got ({lo}, {hi})");
    }
    if color.is_empty() && opacity.is_empty() {
        return Ok(default_ramp((lo, hi)));
    }
    let at = |s: f32| lo + s * (hi - lo);
    let color = color
        .iter()
        .map(|p| ColorPoint {
            scalar: at(p.scalar),
            rgb: p.rgb,
        })
        .collect();
    let opacity = opacity
        .iter()
        .map(|p| OpacityPoint {
            scalar: at(p.scalar),
            alpha: p.alpha,
        })
        .collect();
    from_points(color, opacity)
}

/// Opacity per unit distance of a uniform volume: a ray along the bounds
/// diagonal (`unit_lengths` unit distances long) keeps 30% of the light
/// behind it, so the whole volume shows, translucent.
fn solid_alpha(unit_lengths: f32) -> f32 {
    let n = if unit_lengths.is_finite() && unit_lengths > 0.0 {
        unit_lengths
    } else {
        1.0
    };
    (1.0 - 0.3f32.powf(1.0 / n)).clamp(0.01, 1.0)
}

/// ParaView's "Solid Color": one colour and one opacity for every value.
fn solid_color(value: f32, alpha: f32) -> TransferFunction {
    let gray = Vec3::splat(0.865);
    let color = [value, value + 1.0].map(|scalar| ColorPoint { scalar, rgb: gray });
    let opacity = [value, value + 1.0].map(|scalar| OpacityPoint { scalar, alpha });
    TransferFunction::new(color.to_vec(), opacity.to_vec())
        .expect("a two-point uniform transfer function is valid")
}

/// The integrator's options; `chord` is the typical segment (a
/// tetrahedron's mean chord).
pub fn integrator_options(
    choice: &IntegratorChoice,
    unit_distance: f32,
    chord: f32,
    (lo, hi): (f32, f32),
) -> IntegratorOptions {
    IntegratorOptions {
        unit_distance,
        opacity_mode: choice.opacity_mode,
        psi_table_size: choice.psi_size,
        riemann_step: choice.riemann_step.unwrap_or(chord / 4.0),
        preintegration_table_size: choice.preintegration_size,
        // The table is exact at this length and corrected for others: the
        // typical segment, a tetrahedron's mean chord.
        preintegration_length: chord,
        scalar_range: Some((lo, hi)),
        split_at_knots: choice.knot_split,
        ..IntegratorOptions::default()
    }
}

/// The integrator of `method`, `tf` and `options`, and its setup time.
pub fn integrator(
    method: Method,
    tf: &TransferFunction,
    options: &IntegratorOptions,
) -> Result<(ScalarIntegrator, Duration), EngineError> {
    let integrator = ScalarIntegrator::new(method, tf, options)
        .with_context(|| format!("setting up the {method} integrator"))?;
    let time = integrator.setup_time();
    Ok((integrator, time))
}

/// One line: the integrator, its field and range, unit distance and
/// opacity mode.
pub fn describe_integrator(
    integrator: &ScalarIntegrator,
    options: &IntegratorOptions,
    field: &str,
    unit_distance_given: bool,
) -> String {
    let source = if unit_distance_given {
        "given"
    } else {
        "ParaView's default"
    };
    let (lo, hi) = options.scalar_range.unwrap_or((0.0, 0.0));
    format!(
        "integrator {}{}: {field} in [{lo}, {hi}], unit distance {} ({source}), opacity mode \
         {}, set up in {:.3} s",
        integrator.method(),
        table_note(integrator, options),
        options.unit_distance,
        opacity_mode_name(options.opacity_mode),
        integrator.setup_time().as_secs_f64()
    )
}

/// "exact" or "vtk".
pub fn opacity_mode_name(mode: OpacityMode) -> &'static str {
    match mode {
        OpacityMode::Exact => "exact",
        OpacityMode::Vtk => "vtk",
    }
}

fn table_note(integrator: &ScalarIntegrator, options: &IntegratorOptions) -> String {
    if let Some(psi) = integrator.psi_table() {
        format!(" (Psi table {0}x{0})", psi.size())
    } else if integrator.preintegration_table().is_some() {
        format!(
            " (table {0}x{0} at length {1})",
            options.preintegration_table_size, options.preintegration_length
        )
    } else if integrator.method() == Method::Riemann {
        format!(" (step {})", options.riemann_step)
    } else {
        String::new()
    }
}
