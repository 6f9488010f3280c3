//! `tetray segment`: one ray segment with linear luminance and attenuation,
//! integrated by any method, as JSON (for studying the methods).

use clap::Args;
use glam::Vec3;
use serde::Serialize;
use tetray_integrate::{Method, Model, SegmentParams};

use super::parse::{parse_method, parse_non_negative, parse_positive, parse_rgb};

/// A method, or all of them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodChoice {
    All,
    One(Method),
}

fn parse_method_choice(text: &str) -> Result<MethodChoice, String> {
    if text.trim().eq_ignore_ascii_case("all") {
        Ok(MethodChoice::All)
    } else {
        parse_method(text).map(MethodChoice::One)
    }
}

/// `tetray segment`.
#[derive(Debug, Clone, Args)]
pub struct SegmentArgs {
    /// Method name (see `tetray render --help`), or "all": every method
    /// with its error against its model's f64 reference.
    #[arg(long, value_name = "NAME", default_value = "all", value_parser = parse_method_choice)]
    pub integrator: MethodChoice,
    /// Luminance at the back end (far from the eye), r,g,b or one value.
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, allow_hyphen_values = true)]
    pub lb: Vec3,
    /// Luminance at the front end (near the eye).
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, allow_hyphen_values = true)]
    pub lf: Vec3,
    /// Attenuation per unit length at the back end, x or r,g,b.
    #[arg(long, value_name = "X|R,G,B", value_parser = parse_rgb, allow_hyphen_values = true)]
    pub tau_b: Vec3,
    /// Attenuation per unit length at the front end.
    #[arg(long, value_name = "X|R,G,B", value_parser = parse_rgb, allow_hyphen_values = true)]
    pub tau_f: Vec3,
    /// Segment length D.
    #[arg(long, value_name = "D", value_parser = parse_non_negative, allow_hyphen_values = true)]
    pub length: f32,
    /// Light entering the back of the segment.
    #[arg(long, value_name = "R,G,B", default_value = "0,0,0", value_parser = parse_rgb, allow_hyphen_values = true)]
    pub incoming: Vec3,
    /// Unit distance u of the opacity methods: their opacity is
    /// 1 - exp(-tau u), the opacity of u of material.
    #[arg(long, value_name = "U", default_value_t = 1.0, value_parser = parse_positive, allow_hyphen_values = true)]
    pub unit_distance: f32,
    /// Psi table nodes per axis (ppi).
    #[arg(long, value_name = "N", default_value_t = tetray_core::defaults::PSI_TABLE_SIZE)]
    pub psi_size: usize,
    /// Riemann-sum step. Default: D / 256.
    #[arg(long, value_name = "STEP", value_parser = parse_positive, allow_hyphen_values = true)]
    pub riemann_step: Option<f32>,
    /// Full pre-integration table nodes per axis (built for length D).
    #[arg(long, value_name = "N", default_value_t = tetray_core::defaults::PREINTEGRATION_TABLE_SIZE)]
    pub preintegration_size: usize,
}

/// One method's answer.
#[derive(Debug, Serialize)]
struct SegmentJson {
    method: &'static str,
    model: &'static str,
    /// incoming * transmittance + emitted.
    colour: [f32; 3],
    /// 1 - mean(transmittance).
    alpha: f32,
    emitted: [f32; 3],
    transmittance: [f32; 3],
    /// With `all`: the f64 reference of this method's model, and the
    /// largest absolute difference from it over colour and alpha.
    #[serde(skip_serializing_if = "Option::is_none")]
    reference: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    abs_error: Option<f32>,
}

#[derive(Debug, Serialize)]
struct AllJson {
    inputs: Inputs,
    methods: Vec<SegmentJson>,
}

#[derive(Debug, Serialize)]
struct Inputs {
    lb: [f32; 3],
    lf: [f32; 3],
    tau_b: [f32; 3],
    tau_f: [f32; 3],
    length: f32,
    incoming: [f32; 3],
    unit_distance: f32,
}

pub fn run(args: &SegmentArgs) -> anyhow::Result<()> {
    let text = match args.integrator {
        MethodChoice::One(method) => serde_json::to_string_pretty(&evaluate(args, method)?)?,
        MethodChoice::All => {
            let mut methods = Vec::with_capacity(Method::ALL.len());
            for method in Method::ALL {
                let mut json = evaluate(args, method)?;
                let reference = evaluate(args, method.reference())?;
                let colour_error = (0..3)
                    .map(|c| (json.colour[c] - reference.colour[c]).abs())
                    .fold(0.0f32, f32::max);
                json.abs_error = Some(colour_error.max((json.alpha - reference.alpha).abs()));
                json.reference = Some(method.reference().name());
                methods.push(json);
            }
            let inputs = Inputs {
                lb: args.lb.to_array(),
                lf: args.lf.to_array(),
                tau_b: args.tau_b.to_array(),
                tau_f: args.tau_f.to_array(),
                length: args.length,
                incoming: args.incoming.to_array(),
                unit_distance: args.unit_distance,
            };
            serde_json::to_string_pretty(&AllJson { inputs, methods })?
        }
    };
    println!("{text}");
    Ok(())
}

fn evaluate(args: &SegmentArgs, method: Method) -> anyhow::Result<SegmentJson> {
    let params = SegmentParams {
        lum_back: args.lb,
        lum_front: args.lf,
        tau_back: args.tau_b,
        tau_front: args.tau_f,
        length: args.length,
    };
    let options = tetray_engine::SegmentOptions {
        unit_distance: args.unit_distance,
        psi_size: args.psi_size,
        riemann_step: args.riemann_step,
        preintegration_size: args.preintegration_size,
    };
    let light = tetray_engine::segment(method, &params, &options)?;
    Ok(SegmentJson {
        method: method.name(),
        model: match method.model() {
            Model::LinearAttenuation => "linear attenuation",
            Model::LinearOpacity => "linear opacity",
        },
        colour: light.over(args.incoming).to_array(),
        alpha: light.alpha(),
        emitted: light.emitted.to_array(),
        transmittance: light.transmittance.to_array(),
        reference: None,
        abs_error: None,
    })
}
