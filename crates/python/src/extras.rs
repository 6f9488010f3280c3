//! `segment`, `psi` and `compare`: the CLI's commands of the same names,
//! returning Python values instead of printing JSON.

use glam::Vec3;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tetray_engine::Setup;
use tetray_integrate::{Method, Model, PsiTable, SegmentParams};

use crate::{guard, to_py, value_error};

/// The integration methods by name, in the CLI's order.
#[pyfunction]
pub fn methods() -> Vec<&'static str> {
    Method::ALL.iter().map(|m| m.name()).collect()
}

fn method(name: &str) -> PyResult<Method> {
    name.parse()
        .map_err(|e: tetray_integrate::UnknownMethod| value_error(e.to_string()))
}

fn rgb(key: &str, v: (f32, f32, f32), non_negative: bool) -> PyResult<Vec3> {
    let v = Vec3::new(v.0, v.1, v.2);
    if !v.is_finite() || (non_negative && v.min_element() < 0.0) {
        return Err(value_error(format!(
            "{key}: {v} must be finite{}",
            if non_negative { " and >= 0" } else { "" }
        )));
    }
    Ok(v)
}

/// One ray segment integrated by `integrator` (`tetray segment`): a dict
/// with colour, alpha, emitted, transmittance, method and model.
#[pyfunction]
#[pyo3(signature = (integrator, lb, lf, tau_b, tau_f, length, incoming=(0.0, 0.0, 0.0),
    unit_distance=1.0, psi_size=1024, riemann_step=None, preintegration_size=256))]
#[allow(clippy::too_many_arguments)]
pub fn segment<'py>(
    py: Python<'py>,
    integrator: &str,
    lb: (f32, f32, f32),
    lf: (f32, f32, f32),
    tau_b: (f32, f32, f32),
    tau_f: (f32, f32, f32),
    length: f32,
    incoming: (f32, f32, f32),
    unit_distance: f32,
    psi_size: usize,
    riemann_step: Option<f32>,
    preintegration_size: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let method = method(integrator)?;
    let params = SegmentParams {
        lum_back: rgb("lb", lb, true)?,
        lum_front: rgb("lf", lf, true)?,
        tau_back: rgb("tau_b", tau_b, true)?,
        tau_front: rgb("tau_f", tau_f, true)?,
        length,
    };
    let incoming = rgb("incoming", incoming, true)?;
    if !(length.is_finite() && length >= 0.0) {
        return Err(value_error(format!(
            "length {length} must be finite and >= 0"
        )));
    }
    if !(unit_distance.is_finite() && unit_distance > 0.0) {
        return Err(value_error(format!(
            "unit_distance {unit_distance} must be finite and > 0"
        )));
    }
    if let Some(step) = riemann_step.filter(|s| !(s.is_finite() && *s > 0.0)) {
        return Err(value_error(format!(
            "riemann_step {step} must be finite and > 0"
        )));
    }
    let options = tetray_engine::SegmentOptions {
        unit_distance,
        psi_size,
        riemann_step,
        preintegration_size,
    };
    let light = guard(|| tetray_engine::segment(method, &params, &options).map_err(to_py))?;
    let d = PyDict::new(py);
    d.set_item("method", method.name())?;
    d.set_item(
        "model",
        match method.model() {
            Model::LinearAttenuation => "linear attenuation",
            Model::LinearOpacity => "linear opacity",
        },
    )?;
    d.set_item("colour", light.over(incoming).to_array())?;
    d.set_item("alpha", light.alpha())?;
    d.set_item("emitted", light.emitted.to_array())?;
    d.set_item("transmittance", light.transmittance.to_array())?;
    Ok(d)
}

/// The Psi table at (gamma_b, gamma_f) against Psi in f64 (`tetray psi`).
#[pyfunction]
#[pyo3(signature = (gamma_b, gamma_f, size=1024))]
pub fn psi<'py>(
    py: Python<'py>,
    gamma_b: f32,
    gamma_f: f32,
    size: usize,
) -> PyResult<Bound<'py, PyDict>> {
    for (key, g) in [("gamma_b", gamma_b), ("gamma_f", gamma_f)] {
        if !(0.0..=1.0).contains(&g) {
            return Err(value_error(format!("{key} {g} is outside [0, 1]")));
        }
    }
    let table = guard(|| PsiTable::shared(size).map_err(|e| value_error(e.to_string())))?;
    let at = table.at_gamma(gamma_b, gamma_f);
    let d = PyDict::new(py);
    d.set_item("gamma_b", gamma_b)?;
    d.set_item("gamma_f", gamma_f)?;
    d.set_item("tau_b_d", at.tau_b_d)?;
    d.set_item("tau_f_d", at.tau_f_d)?;
    d.set_item("size", table.size())?;
    d.set_item("spacing", table.spacing().name())?;
    d.set_item("table_bilinear", at.bilinear)?;
    d.set_item("table_nearest", at.nearest)?;
    d.set_item("f64", at.exact)?;
    d.set_item("error_bilinear", at.error_bilinear())?;
    d.set_item("error_nearest", at.error_nearest())?;
    Ok(d)
}

/// One combination of `compare`: renderer, integrator (None: the scene's),
/// sort (project only).
pub type Spec = (String, Option<String>, Option<String>);

/// Renders the CPU f64 reference and each spec from the setup's camera
/// (median of `frames` timed frames, GPU renderers warmed up first), as
/// `tetray compare` does, through the same code, and compares them. The
/// setup's integrator is left as it was.
pub fn compare(
    setup: &mut Setup,
    specs: &[Spec],
    frames: u32,
    size: (u32, u32),
    log: &dyn Fn(String),
) -> PyResult<tetray_compare::Report> {
    if frames == 0 {
        return Err(value_error("frames must be at least 1"));
    }
    let specs = specs
        .iter()
        .map(|(renderer, integrator, sort)| {
            let text = [Some(renderer), integrator.as_ref(), sort.as_ref()]
                .into_iter()
                .flatten()
                .map(String::as_str)
                .collect::<Vec<_>>()
                .join(":");
            tetray_compare::parse_spec(&text).map_err(|e| value_error(format!("compare: {e}")))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let options = tetray_compare::RunOptions {
        size,
        frames,
        adaptive_tf: true,
    };
    tetray_compare::run(setup, &specs, options, log).map_err(|e| match e {
        tetray_compare::CompareError::Engine(e) => to_py(*e),
        other => value_error(tetray_engine::error_chain(&other)),
    })
}
