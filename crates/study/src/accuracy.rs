//! `accuracy`: the error of one segment's light, every method against the
//! f64 reference of its model, over the dissertation's sweeps (section
//! 6.2, figs. 6.5-6.11): `L_b = 1 - L_f` and `tau_b = 1 - tau_f` (for the
//! opacity model `alpha_b = 1 - alpha_f`, the opacity of one unit
//! distance), at segment lengths `D` = 0.001, 0.1, 1 and 100, no incoming
//! light, so the error is in units of the display's full intensity.
//!
//! Each method runs on the CPU (`ScalarIntegrator`, what the CPU ray
//! caster calls) and, where an adapter exists, through the GPU kernel's
//! `piece_light` ([`crate::gpu_segments`]), read back. The Riemann sum runs
//! on the CPU only (16 midpoint steps per segment): on the GPU it samples
//! the transfer-function buffer, which a per-segment kernel does not have.
//! Full pre-integration is left out: its table is built per transfer
//! function and holds this very segment at a node, so a sweep of single
//! segments measures only the quadrature it was built with.

use glam::Vec3A;
use serde::Serialize;
use tetray_gpu::GpuContext;
use tetray_integrate::reference::{attenuation_segment, opacity_segment};
use tetray_integrate::{
    IntegratorOptions, Material, Method, Model, PsiTable, ScalarIntegrator, TfKnots,
};

use crate::cells;
use crate::gpu_segments::{GpuSegment, SegmentKernel};
use crate::output::{Csv, OutputDir};
use crate::svg::Axis;
use crate::svg::heat::{ColourScale, HeatPanel, heat_figure};
use crate::svg::line::{LinePanel, Series, line_figure};
use crate::{Check, StudyError};

/// Sizes of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyOptions {
    /// Sweep points per parameter (the sweep is `steps` x `steps`).
    pub steps: usize,
    /// Segment lengths `D` (unit distances for the opacity model).
    pub lengths: Vec<f64>,
    /// Run the GPU half when an adapter exists.
    pub gpu: bool,
}

impl Default for AccuracyOptions {
    fn default() -> Self {
        AccuracyOptions {
            steps: 41,
            lengths: vec![0.001, 0.1, 1.0, 100.0],
            gpu: true,
        }
    }
}

/// Largest opacity the sweep uses (the methods clamp there too).
const ALPHA_MAX: f64 = tetray_integrate::opacity::ALPHA_MAX as f64;
/// Riemann steps per segment.
const RIEMANN_STEPS: f64 = 16.0;

/// Where a method ran.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Device {
    Cpu,
    Gpu,
}

impl Device {
    pub fn name(self) -> &'static str {
        match self {
            Device::Cpu => "cpu",
            Device::Gpu => "gpu",
        }
    }
}

/// The error of one method at one length on one device.
#[derive(Debug, Clone, Serialize)]
pub struct SweepError {
    pub model: &'static str,
    pub length: f64,
    pub device: Device,
    pub method: &'static str,
    /// Largest and mean |I - I_ref| of the emitted light.
    pub max_error: f64,
    pub mean_error: f64,
    /// (L_f, tau_f or alpha_f) of the largest error.
    pub max_at: (f64, f64),
    /// Largest |T - T_ref| of the transmittance.
    pub max_transmittance_error: f64,
}

/// What the study found.
#[derive(Debug, Clone, Serialize)]
pub struct AccuracySummary {
    pub steps: usize,
    /// The adapter of the GPU half, or why there was none.
    pub gpu_adapter: Option<String>,
    pub gpu_note: Option<String>,
    pub sweeps: Vec<SweepError>,
    pub checks: Vec<Check>,
}

/// The methods of a model, dissertation order.
fn methods(model: Model) -> &'static [Method] {
    match model {
        Model::LinearAttenuation => &[Method::Average, Method::Ppi, Method::Exact, Method::Riemann],
        Model::LinearOpacity => &[
            Method::AverageOpacity,
            Method::LinAvgOpacity,
            Method::LinOpacity,
        ],
    }
}

fn model_name(model: Model) -> &'static str {
    match model {
        Model::LinearAttenuation => "attenuation",
        Model::LinearOpacity => "opacity",
    }
}

/// One sweep point: front luminance and front quantity; the back ones are
/// `1 - x`, opacities clamped below 1.
#[derive(Debug, Clone, Copy)]
struct Point {
    lum_front: f64,
    q_front: f64,
    q_back: f64,
}

fn sweep(model: Model, steps: usize) -> Vec<Point> {
    let v = |i: usize| i as f64 / (steps - 1) as f64;
    let clamp = |q: f64| match model {
        Model::LinearAttenuation => q,
        Model::LinearOpacity => q.min(ALPHA_MAX),
    };
    (0..steps * steps)
        .map(|k| Point {
            lum_front: v(k % steps),
            q_front: clamp(v(k / steps)),
            q_back: clamp(1.0 - v(k / steps)),
        })
        .collect()
}

/// The f64 light of the point's segment.
fn reference(model: Model, p: Point, d: f64) -> (f64, f64) {
    let light = match model {
        Model::LinearAttenuation => {
            attenuation_segment(1.0 - p.lum_front, p.lum_front, p.q_back, p.q_front, d)
        }
        Model::LinearOpacity => {
            opacity_segment(1.0 - p.lum_front, p.lum_front, p.q_back, p.q_front, d)
        }
    };
    (light.emitted, light.transmittance)
}

/// The CPU integrator's light of the point's segment (unit distance 1).
fn cpu_light(method: Method, model: Model, p: Point, d: f64) -> Result<(f64, f64), StudyError> {
    let material = |lum: f64, q: f64| {
        let (tau, alpha) = match model {
            Model::LinearAttenuation => (q, 1.0 - (-q).exp()),
            Model::LinearOpacity => (-(-q).ln_1p(), q),
        };
        Material {
            lum: Vec3A::splat(lum as f32),
            tau: Vec3A::splat(tau as f32),
            alpha: Vec3A::splat(alpha as f32),
        }
    };
    let knots = TfKnots::from_materials(vec![
        (0.0, material(1.0 - p.lum_front, p.q_back)),
        (1.0, material(p.lum_front, p.q_front)),
    ]);
    let options = IntegratorOptions {
        riemann_step: (d / RIEMANN_STEPS) as f32,
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::from_knots(method, knots, (0.0, 1.0), &options)?;
    let light = integrator.integrate(1.0, 0.0, d as f32);
    Ok((f64::from(light.emitted.x), f64::from(light.transmittance.x)))
}

/// One evaluated sweep: the errors at every point.
struct Sweep {
    model: Model,
    length: f64,
    device: Device,
    method: Method,
    errors: Vec<f64>,
    transmittance_errors: Vec<f64>,
    lights: Vec<f64>,
}

/// Runs the study, writing its plots and tables into `out`.
pub fn run(
    options: &AccuracyOptions,
    out: &mut OutputDir,
    log: &dyn Fn(&str),
) -> Result<AccuracySummary, StudyError> {
    if options.steps < 2 || options.lengths.iter().any(|d| !(*d > 0.0 && d.is_finite())) {
        return Err(StudyError::Option(
            "accuracy: needs at least 2 steps and positive finite lengths".into(),
        ));
    }
    let (gpu, gpu_note) = if options.gpu {
        match GpuContext::new() {
            Ok(ctx) => {
                let kernel = SegmentKernel::new(&ctx, &*PsiTable::shared(1024)?)?;
                (Some((ctx, kernel)), None)
            }
            Err(e) => {
                let note = format!("no GPU half: {e}");
                log(&format!("accuracy: {note}"));
                (None, Some(note))
            }
        }
    } else {
        (None, Some("GPU half not requested".to_string()))
    };
    let mut sweeps = Vec::new();
    for model in [Model::LinearAttenuation, Model::LinearOpacity] {
        let points = sweep(model, options.steps);
        for &d in &options.lengths {
            let want: Vec<(f64, f64)> = points.iter().map(|&p| reference(model, p, d)).collect();
            let mut record = |device, method, lights: Vec<(f64, f64)>| {
                let (errors, transmittance_errors) = lights
                    .iter()
                    .zip(&want)
                    .map(|(got, want)| ((got.0 - want.0).abs(), (got.1 - want.1).abs()))
                    .unzip();
                sweeps.push(Sweep {
                    model,
                    length: d,
                    device,
                    method,
                    errors,
                    transmittance_errors,
                    lights: lights.iter().map(|l| l.0).collect(),
                });
            };
            for &method in methods(model) {
                let lights = points
                    .iter()
                    .map(|&p| cpu_light(method, model, p, d))
                    .collect::<Result<Vec<_>, _>>()?;
                record(Device::Cpu, method, lights);
                if let (Some((ctx, kernel)), Some(_)) = (&gpu, method.gpu_code()) {
                    if method == Method::Riemann {
                        continue;
                    }
                    let segments: Vec<GpuSegment> = points
                        .iter()
                        .map(|p| {
                            GpuSegment::new(
                                (1.0 - p.lum_front) as f32,
                                p.lum_front as f32,
                                p.q_back as f32,
                                p.q_front as f32,
                                d as f32,
                            )
                        })
                        .collect();
                    let lights = kernel.evaluate(ctx, method, 1.0, &segments)?;
                    record(
                        Device::Gpu,
                        method,
                        lights
                            .iter()
                            .map(|l| (f64::from(l[0]), f64::from(l[1])))
                            .collect(),
                    );
                }
            }
            log(&format!("accuracy: {} model, D = {d}", model_name(model)));
        }
    }
    let points_of = |model| sweep(model, options.steps);
    write_figures(&sweeps, options, out)?;
    write_tables(&sweeps, &points_of, out)?;
    let summaries: Vec<SweepError> = sweeps
        .iter()
        .map(|s| summarize(s, &points_of(s.model)))
        .collect();
    let checks = checks(&summaries);
    let summary = AccuracySummary {
        steps: options.steps,
        gpu_adapter: gpu.as_ref().map(|(ctx, _)| ctx.adapter_name()),
        gpu_note,
        sweeps: summaries,
        checks,
    };
    out.json("accuracy.json", &summary)?;
    Ok(summary)
}

fn summarize(s: &Sweep, points: &[Point]) -> SweepError {
    let (k, max_error) = s
        .errors
        .iter()
        .copied()
        .enumerate()
        .fold((0, 0.0), |a, (k, e)| if e > a.1 { (k, e) } else { a });
    SweepError {
        model: model_name(s.model),
        length: s.length,
        device: s.device,
        method: s.method.name(),
        max_error,
        mean_error: s.errors.iter().sum::<f64>() / s.errors.len() as f64,
        max_at: (points[k].lum_front, points[k].q_front),
        max_transmittance_error: s.transmittance_errors.iter().copied().fold(0.0, f64::max),
    }
}

/// One heat figure per model, length and device (panels: methods), and
/// the maximum error against the length.
fn write_figures(
    sweeps: &[Sweep],
    options: &AccuracyOptions,
    out: &mut OutputDir,
) -> Result<(), StudyError> {
    let n = options.steps;
    let scale = ColourScale::log_fit(sweeps.iter().flat_map(|s| s.errors.iter().copied()), 9);
    let mut by_length = Vec::new();
    for model in [Model::LinearAttenuation, Model::LinearOpacity] {
        let q = match model {
            Model::LinearAttenuation => "tau_f (tau_b = 1 - tau_f)",
            Model::LinearOpacity => "alpha_f (alpha_b = 1 - alpha_f)",
        };
        for &d in &options.lengths {
            for device in [Device::Cpu, Device::Gpu] {
                let panels: Vec<HeatPanel> = sweeps
                    .iter()
                    .filter(|s| s.model == model && s.length == d && s.device == device)
                    .map(|s| HeatPanel {
                        title: s.method.name().to_string(),
                        x_label: "L_f (L_b = 1 - L_f)".into(),
                        y_label: q.into(),
                        x_range: (0.0, 1.0),
                        y_range: (0.0, 1.0),
                        nx: n,
                        ny: n,
                        values: s.errors.clone(),
                    })
                    .collect();
                if panels.is_empty() {
                    continue;
                }
                let svg = heat_figure(
                    &format!(
                        "|I - I_ref|, linear luminance and {}, D = {d}, {}",
                        model_name(model),
                        device.name().to_uppercase()
                    ),
                    &panels,
                    panels.len(),
                    scale,
                    "absolute error of the intensity",
                )?;
                out.write(
                    &format!("accuracy_{}_d{d}_{}.svg", model_name(model), device.name()),
                    &svg,
                )?;
            }
        }
        let mut series = Vec::new();
        for (c, &method) in methods(model).iter().enumerate() {
            for device in [Device::Cpu, Device::Gpu] {
                let points: Vec<(f64, f64)> = sweeps
                    .iter()
                    .filter(|s| s.model == model && s.method == method && s.device == device)
                    .map(|s| (s.length, s.errors.iter().copied().fold(0.0, f64::max)))
                    .collect();
                if points.is_empty() {
                    continue;
                }
                let line = Series::new(format!("{method} ({})", device.name()), c, points);
                series.push(match device {
                    Device::Cpu => line.with_markers(),
                    Device::Gpu => line.dashed(),
                });
            }
        }
        by_length.push(LinePanel {
            title: format!("linear luminance and {}", model_name(model)),
            x: Axis::log("segment length D"),
            y: Axis::log("max |I - I_ref| over the sweep"),
            series,
        });
    }
    let svg = line_figure(
        "Worst per-segment error against segment length (figs. 6.5-6.11)",
        &by_length,
        2,
    );
    out.write("accuracy_by_length.svg", &svg)
}

fn write_tables(
    sweeps: &[Sweep],
    points_of: &dyn Fn(Model) -> Vec<Point>,
    out: &mut OutputDir,
) -> Result<(), StudyError> {
    let mut all = Csv::new(&[
        "model",
        "length",
        "device",
        "method",
        "lum_front",
        "q_front",
        "q_back",
        "intensity",
        "error",
        "transmittance_error",
    ]);
    let mut table = Csv::new(&[
        "model",
        "length",
        "device",
        "method",
        "max_error",
        "mean_error",
        "max_at_lum_front",
        "max_at_q_front",
        "max_transmittance_error",
    ]);
    for s in sweeps {
        let points = points_of(s.model);
        for (k, p) in points.iter().enumerate() {
            all.row(&cells![
                model_name(s.model),
                s.length,
                s.device.name(),
                s.method.name(),
                p.lum_front,
                p.q_front,
                p.q_back,
                s.lights[k],
                s.errors[k],
                s.transmittance_errors[k]
            ]);
        }
        let e = summarize(s, &points);
        table.row(&cells![
            e.model,
            e.length,
            e.device.name(),
            e.method,
            e.max_error,
            e.mean_error,
            e.max_at.0,
            e.max_at.1,
            e.max_transmittance_error
        ]);
    }
    out.csv("accuracy_points.csv", &all)?;
    out.csv("accuracy_summary.csv", &table)
}

/// The dissertation's findings, on our numbers: partial pre-integration
/// below averaging at every length on every device (section 6.2), the
/// exact method at f32 rounding on the CPU, the improved opacity
/// approximation below both others from D = 0.1 on (figs. 6.10, 6.11).
fn checks(sweeps: &[SweepError]) -> Vec<Check> {
    let find = |model: &str, d: f64, device: Device, method: Method| {
        sweeps
            .iter()
            .find(|s| {
                s.model == model && s.length == d && s.device == device && s.method == method.name()
            })
            .map(|s| s.max_error)
    };
    let mut checks = Vec::new();
    let lengths: Vec<f64> = {
        let mut v: Vec<f64> = sweeps.iter().map(|s| s.length).collect();
        v.dedup();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    for &d in &lengths {
        for device in [Device::Cpu, Device::Gpu] {
            let tag = format!("D = {d}, {}", device.name());
            if let (Some(ppi), Some(avg)) = (
                find("attenuation", d, device, Method::Ppi),
                find("attenuation", d, device, Method::Average),
            ) {
                checks.push(Check::new(
                    format!("{tag}: ppi below average"),
                    ppi < avg,
                    format!("{ppi:.3e} vs {avg:.3e}"),
                ));
            }
            let opacity = (
                find("opacity", d, device, Method::LinOpacity),
                find("opacity", d, device, Method::LinAvgOpacity),
                find("opacity", d, device, Method::AverageOpacity),
            );
            if let (Some(lin), Some(lin_avg), Some(avg)) = opacity
                && d >= 0.1
            {
                checks.push(Check::new(
                    format!("{tag}: lin-opacity below lin-avg-opacity and average-opacity"),
                    lin < lin_avg && lin < avg,
                    format!("{lin:.3e} vs {lin_avg:.3e}, {avg:.3e}"),
                ));
            }
        }
        if let Some(exact) = find("attenuation", d, Device::Cpu, Method::Exact) {
            checks.push(Check::new(
                format!("D = {d}, cpu: exact at f32 rounding"),
                exact < 1e-6,
                format!("{exact:.3e}"),
            ));
        }
    }
    checks
}
