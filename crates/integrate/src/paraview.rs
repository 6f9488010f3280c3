//! ParaView colour-map presets (the JSON its preset manager imports and
//! exports) to and from [`TransferFunction`].
//!
//! A preset holds `"RGBPoints"` (x, r, g, b quadruples), optionally
//! `"Points"` (opacity: x, alpha, midpoint, sharpness) and a
//! `"ColorSpace"`. Everything downstream integrates piecewise-linear
//! functions exactly, so whatever is not linear between two points (colour
//! spaces other than RGB, opacity midpoints and sharpness) becomes linear
//! pieces here: exact where the shape is itself piecewise linear (steps, a
//! moved midpoint), otherwise within 5e-4 of the curve (see `pieces`).

use serde_json::{Map, Value};

use crate::colorspace::ColorSpace;
use crate::tf::{TfError, TransferFunction};

mod pieces;

use pieces::{ScalarMap, color_points, opacity_points};

/// Marker for the bare `NaN` / `Infinity` tokens some writers emit (Python's
/// `json`), so that they are reported by key and index instead of as a
/// syntax error.
const NON_FINITE_MARKER: &str = "\u{1}non-finite:";

/// Keys ParaView writes that carry no rendering meaning.
const METADATA_KEYS: &[&str] = &[
    "Name",
    "Creator",
    "License",
    "DefaultMap",
    "AllowDuplicateScalars",
    "ShowIndexedColorActiveValues",
    "HSVWrap",
];

/// Keys with a meaning this renderer does not reproduce, and why.
const IGNORED_KEYS: &[(&str, &str)] = &[
    ("NanColor", "tetray has no NaN colour"),
    ("NanOpacity", "tetray has no NaN colour"),
    (
        "AboveRangeColor",
        "beyond its last point the function stays constant",
    ),
    (
        "BelowRangeColor",
        "beyond its first point the function stays constant",
    ),
    (
        "UseAboveRangeColor",
        "beyond its last point the function stays constant",
    ),
    (
        "UseBelowRangeColor",
        "beyond its first point the function stays constant",
    ),
    ("UseLogScale", "the scalar is always mapped linearly"),
    ("Discretize", "the map is used continuously, not as a table"),
    (
        "NumberOfTableValues",
        "the map is used continuously, not as a table",
    ),
    (
        "Annotations",
        "categorical annotations do not apply to a continuous map",
    ),
    (
        "IndexedColors",
        "categorical colours do not apply to a continuous map",
    ),
    (
        "IndexedOpacities",
        "categorical opacities do not apply to a continuous map",
    ),
];

impl TransferFunction {
    /// Reads a ParaView colour-map preset; see
    /// [`TransferFunction::from_paraview_json_with_report`], whose warnings
    /// this drops.
    pub fn from_paraview_json(
        text: &str,
        name: Option<&str>,
        rescale: Option<(f32, f32)>,
    ) -> Result<TransferFunction, TfError> {
        Self::from_paraview_json_with_report(text, name, rescale).map(|(tf, _)| tf)
    }

    /// Reads a ParaView colour-map preset: one JSON object or an array of
    /// them, from which `name` picks one by its `"Name"` (`None`: the
    /// first). With `rescale = Some((lo, hi))` the range of `"RGBPoints"`
    /// is mapped onto `[lo, hi]` and the opacity points follow the same
    /// affine map, as when ParaView rescales both functions together; with
    /// `None` the preset's own scalars are kept.
    ///
    /// A preset without `"Points"` gets the rising opacity ramp of
    /// [`TransferFunction::default_for_range`] over the colour range
    /// (ParaView would keep whatever opacity it had; we have none). That,
    /// and every key that is ignored, is returned as a warning.
    pub fn from_paraview_json_with_report(
        text: &str,
        name: Option<&str>,
        rescale: Option<(f32, f32)>,
    ) -> Result<(TransferFunction, Vec<String>), TfError> {
        let root: Value = serde_json::from_str(&mark_non_finite(text))
            .map_err(|e| TfError::Preset(format!("the preset is not valid JSON: {e}")))?;
        let (label, preset) = select_preset(&root, name)?;
        let fail = |msg: String| TfError::Preset(format!("{label}: {msg}"));
        let mut warnings = Vec::new();
        check_keys(preset, &mut warnings);

        let hsv_wrap = match preset.get("HSVWrap") {
            None => false,
            Some(v) => flag(v).ok_or_else(|| fail(format!("\"HSVWrap\" is {}", describe(v))))?,
        };
        let space = match preset.get("ColorSpace") {
            None => {
                warnings.push("no \"ColorSpace\": interpolating in RGB".to_string());
                ColorSpace::Rgb
            }
            Some(Value::String(s)) if s.eq_ignore_ascii_case("Lab/CIEDE2000") => {
                return Err(fail(format!(
                    "colour space \"{s}\" is not supported; supported: {}",
                    ColorSpace::SUPPORTED
                )));
            }
            Some(Value::String(s)) => {
                ColorSpace::from_paraview_name(s, hsv_wrap).ok_or_else(|| {
                    fail(format!(
                        "unknown colour space \"{s}\"; supported: {}",
                        ColorSpace::SUPPORTED
                    ))
                })?
            }
            Some(v) => {
                return Err(fail(format!(
                    "\"ColorSpace\" is {}, not a string",
                    describe(v)
                )));
            }
        };

        let rgb_points = match preset.get("RGBPoints") {
            Some(v) => read_quads(v, "RGBPoints", ["x", "r", "g", "b"]).map_err(fail)?,
            None if preset.contains_key("IndexedColors") || preset.contains_key("Annotations") => {
                return Err(fail(
                    "a categorical preset (IndexedColors / Annotations without RGBPoints) cannot \
                     colour a continuous scalar"
                        .to_string(),
                ));
            }
            None => return Err(fail("no \"RGBPoints\" (x, r, g, b quadruples)".to_string())),
        };
        check_quads(&rgb_points, "RGBPoints", &mut warnings).map_err(fail)?;
        let opacity_quads = match preset.get("Points") {
            Some(v) => {
                let quads = read_quads(v, "Points", ["x", "alpha", "midpoint", "sharpness"])
                    .map_err(fail)?;
                check_quads(&quads, "Points", &mut warnings).map_err(fail)?;
                Some(quads)
            }
            None => None,
        };

        let map = ScalarMap::new(&rgb_points, rescale).map_err(|e| match e {
            TfError::Preset(msg) => fail(msg),
            other => other,
        })?;
        let color = color_points(&rgb_points, space, &map).map_err(fail)?;
        let opacity = match &opacity_quads {
            Some(quads) => opacity_points(quads, &map).map_err(fail)?,
            None => {
                let (lo, hi) = (color[0].scalar, color[color.len() - 1].scalar);
                warnings.push(format!(
                    "no \"Points\" (opacity): using the default rising opacity ramp over \
                     [{lo}, {hi}]"
                ));
                let default = TransferFunction::default_for_range(lo, hi);
                default.opacity_points().to_vec()
            }
        };
        let tf = TransferFunction::new(color, opacity)?;
        Ok((tf, warnings))
    }

    /// Writes this function as a ParaView preset (an array holding one
    /// object): RGB colour space, every opacity point with midpoint 0.5 and
    /// sharpness 0, so that it reads back exactly.
    pub fn to_paraview_json(&self, name: &str) -> String {
        let rgb: Vec<String> = self
            .color_points()
            .iter()
            .map(|p| {
                let [r, g, b] = p.rgb.to_array();
                [p.scalar, r, g, b].map(exact_number).join(", ")
            })
            .collect();
        let alpha: Vec<String> = self
            .opacity_points()
            .iter()
            .map(|p| {
                format!(
                    "{}, {}, 0.5, 0",
                    exact_number(p.scalar),
                    exact_number(p.alpha)
                )
            })
            .collect();
        let has_steps = self
            .color_points()
            .windows(2)
            .any(|w| w[0].scalar == w[1].scalar)
            || self
                .opacity_points()
                .windows(2)
                .any(|w| w[0].scalar == w[1].scalar);
        let mut out = String::from("[\n  {\n");
        let name = Value::String(name.to_string());
        out.push_str(&format!("    \"Name\": {name},\n"));
        out.push_str("    \"Creator\": \"tetray\",\n");
        out.push_str("    \"ColorSpace\": \"RGB\",\n");
        if has_steps {
            // Two points at one scalar make a step; ParaView merges them otherwise.
            out.push_str("    \"AllowDuplicateScalars\": 1,\n");
        }
        out.push_str(&format!(
            "    \"RGBPoints\": [\n      {}\n    ],\n",
            rgb.join(",\n      ")
        ));
        out.push_str(&format!(
            "    \"Points\": [\n      {}\n    ]\n",
            alpha.join(",\n      ")
        ));
        out.push_str("  }\n]\n");
        out
    }
}

/// The shortest decimal that reads back (through f64, as JSON readers do) as
/// exactly `v`.
fn exact_number(v: f32) -> String {
    let short = v.to_string();
    match short.parse::<f64>() {
        Ok(back) if back as f32 == v => short,
        _ => f64::from(v).to_string(),
    }
}

/// Replaces bare non-finite tokens outside strings by marker strings.
fn mark_non_finite(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let (mut i, mut in_string, mut escaped) = (0, false, false);
    while i < bytes.len() {
        let c = bytes[i];
        if in_string {
            in_string = escaped || c != b'"';
            escaped = !escaped && c == b'\\';
        } else if c == b'"' {
            in_string = true;
        } else if c.is_ascii_alphabetic()
            || (c == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_alphabetic))
        {
            let end = (i + 1..bytes.len())
                .find(|&j| !bytes[j].is_ascii_alphabetic())
                .unwrap_or(bytes.len());
            let word = &text[i..end];
            let lower = word.trim_start_matches('-').to_ascii_lowercase();
            if matches!(lower.as_str(), "nan" | "inf" | "infinity") {
                // A JSON escape: the string then starts with the marker.
                out.push_str(&format!("\"\\u0001non-finite:{word}\""));
            } else {
                out.push_str(word);
            }
            i = end;
            continue;
        } else if c.is_ascii_digit() || c == b'.' {
            // Skip a whole number so that its exponent letter is not a word.
            let end = (i + 1..bytes.len())
                .find(|&j| !(bytes[j].is_ascii_alphanumeric() || b".+-".contains(&bytes[j])))
                .unwrap_or(bytes.len());
            out.push_str(&text[i..end]);
            i = end;
            continue;
        }
        let width = text[i..].chars().next().map_or(1, char::len_utf8);
        out.push_str(&text[i..i + width]);
        i += width;
    }
    out
}

/// The preset to read and a label naming it in messages.
fn select_preset<'a>(
    root: &'a Value,
    name: Option<&str>,
) -> Result<(String, &'a Map<String, Value>), TfError> {
    let presets: Vec<&Value> = match root {
        Value::Array(items) => items.iter().collect(),
        Value::Object(_) => vec![root],
        other => {
            return Err(TfError::Preset(format!(
                "a preset file holds a JSON object or an array of them, not {}",
                describe(other)
            )));
        }
    };
    let mut named = Vec::with_capacity(presets.len());
    for (index, preset) in presets.iter().enumerate() {
        let Value::Object(object) = preset else {
            return Err(TfError::Preset(format!(
                "preset {index} is {}, not a JSON object",
                describe(preset)
            )));
        };
        named.push((object.get("Name").and_then(Value::as_str), object));
    }
    let label = |index: usize, preset_name: Option<&str>| match preset_name {
        Some(n) => format!("preset \"{n}\""),
        None => format!("preset {index}"),
    };
    match name {
        None => match named.first() {
            Some(&(n, object)) => Ok((label(0, n), object)),
            None => Err(TfError::Preset("the preset array is empty".to_string())),
        },
        Some(wanted) => match named.iter().position(|&(n, _)| n == Some(wanted)) {
            Some(index) => Ok((label(index, Some(wanted)), named[index].1)),
            None => {
                let available: Vec<String> = named
                    .iter()
                    .enumerate()
                    .map(|(index, &(n, _))| match n {
                        Some(n) => format!("\"{n}\""),
                        None => format!("#{index} (unnamed)"),
                    })
                    .collect();
                Err(TfError::Preset(format!(
                    "no preset named \"{wanted}\"; available: {}",
                    available.join(", ")
                )))
            }
        },
    }
}

/// Warns about keys that are ignored.
fn check_keys(preset: &Map<String, Value>, warnings: &mut Vec<String>) {
    let used = ["RGBPoints", "Points", "ColorSpace"];
    for key in preset.keys() {
        if used.contains(&key.as_str()) || METADATA_KEYS.contains(&key.as_str()) {
            continue;
        }
        match IGNORED_KEYS.iter().find(|(k, _)| k == key) {
            Some((_, why)) => warnings.push(format!("\"{key}\" is ignored: {why}")),
            None => warnings.push(format!("unknown key \"{key}\" is ignored")),
        }
    }
}

/// A JSON boolean or 0 / 1.
fn flag(v: &Value) -> Option<bool> {
    match v {
        Value::Bool(b) => Some(*b),
        Value::Number(n) => n.as_f64().map(|x| x != 0.0),
        _ => None,
    }
}

/// What a JSON value is, for messages.
fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".to_string(),
        Value::Bool(b) => format!("a boolean ({b})"),
        Value::Number(n) => format!("a number ({n})"),
        Value::String(s) => match s.strip_prefix(NON_FINITE_MARKER) {
            Some(token) => format!("{token} (not finite)"),
            None => format!("a string ({s:?})"),
        },
        Value::Array(_) => "an array".to_string(),
        Value::Object(_) => "an object".to_string(),
    }
}

/// A flat list of quadruples, every value a finite number.
fn read_quads(value: &Value, key: &str, fields: [&str; 4]) -> Result<Vec<[f64; 4]>, String> {
    let Value::Array(items) = value else {
        return Err(format!(
            "\"{key}\" is {}, not an array of numbers",
            describe(value)
        ));
    };
    if items.is_empty() {
        return Err(format!(
            "\"{key}\" is empty: it needs at least one point ({})",
            fields.join(", ")
        ));
    }
    if items.len() % 4 != 0 {
        return Err(format!(
            "\"{key}\" has {} values, not a multiple of 4 ({} per point): point {} at index {} is \
             incomplete",
            items.len(),
            fields.join(", "),
            items.len() / 4,
            items.len() / 4 * 4
        ));
    }
    let mut quads = Vec::with_capacity(items.len() / 4);
    for (point, chunk) in items.chunks(4).enumerate() {
        let mut quad = [0.0; 4];
        for (k, item) in chunk.iter().enumerate() {
            let at = format!(
                "\"{key}\"[{}] (point {point}, {})",
                4 * point + k,
                fields[k]
            );
            let v = item
                .as_f64()
                .ok_or_else(|| format!("{at} is {}, not a finite number", describe(item)))?;
            if !(v.is_finite() && (v as f32).is_finite()) {
                return Err(format!("{at} is {v}, not a finite single-precision number"));
            }
            quad[k] = v;
        }
        quads.push(quad);
    }
    Ok(quads)
}

/// Increasing x and values in range; warns about more than two points at
/// one x (only the first and last of them matter).
fn check_quads(quads: &[[f64; 4]], key: &str, warnings: &mut Vec<String>) -> Result<(), String> {
    for (point, q) in quads.iter().enumerate() {
        if point > 0 && q[0] < quads[point - 1][0] {
            return Err(format!(
                "\"{key}\"[{}] (point {point}, x = {}) is less than the previous point's x = {}: \
                 points must be in increasing x order",
                4 * point,
                q[0],
                quads[point - 1][0]
            ));
        }
        if point > 1 && q[0] == quads[point - 2][0] {
            warnings.push(format!(
                "\"{key}\": more than two points at x = {}; only the first and last are kept",
                q[0]
            ));
        }
        let (fields, in_range, range): ([&str; 3], fn(f64) -> bool, &str) = if key == "Points" {
            (
                ["alpha", "midpoint", "sharpness"],
                |v| (0.0..=1.0).contains(&v),
                "outside [0, 1]",
            )
        } else {
            (["r", "g", "b"], |v| v >= 0.0, "negative")
        };
        for (k, field) in fields.iter().enumerate() {
            let v = q[k + 1];
            if !in_range(v) {
                return Err(format!(
                    "\"{key}\"[{}] (point {point}, {field}) is {v}, {range}",
                    4 * point + k + 1
                ));
            }
        }
    }
    Ok(())
}
