//! Colour-space interpolation between two control colours of a colour map,
//! with the colour spaces ParaView offers (vtkColorTransferFunction): RGB,
//! HSV, CIELAB, Moreland's diverging Msh space and steps.
//!
//! Colours are sRGB components, nominally in [0, 1]. The maths follows the
//! published definitions: sRGB (IEC 61966-2-1) to XYZ with the D65 white,
//! CIELAB (CIE 15), and Msh with the diverging rules of K. Moreland,
//! "Diverging Color Maps for Scientific Visualization" (ISVC 2009).

use glam::{DMat3, DVec3};
use std::f64::consts::PI;

/// How a colour map interpolates between two control colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorSpace {
    /// Linear in sRGB components.
    Rgb,
    /// Linear in hue, saturation and value. Hue runs over [0, 1] and is not
    /// wrapped (ParaView's "HSV"); with `wrap` it takes the shorter way round
    /// the hue circle (ParaView's `HSVWrap`).
    Hsv { wrap: bool },
    /// Linear in CIELAB (D65 white).
    Lab,
    /// Moreland's diverging interpolation in Msh (polar CIELAB).
    Diverging,
    /// Constant on each interval with the colour of its upper point, as VTK's
    /// step colour space renders it.
    Step,
}

impl ColorSpace {
    /// The names [`ColorSpace::from_paraview_name`] accepts, for messages.
    pub const SUPPORTED: &'static str = "RGB, HSV, Lab (or CIELAB), Diverging, Step";

    /// Parses a ParaView `"ColorSpace"` value (case-insensitive). `hsv_wrap`
    /// is the preset's `"HSVWrap"` flag; the legacy name `Wrapped` means HSV
    /// with wrapping.
    pub fn from_paraview_name(name: &str, hsv_wrap: bool) -> Option<ColorSpace> {
        match name.to_ascii_lowercase().as_str() {
            "rgb" => Some(ColorSpace::Rgb),
            "hsv" => Some(ColorSpace::Hsv { wrap: hsv_wrap }),
            "wrapped" => Some(ColorSpace::Hsv { wrap: true }),
            "lab" | "cielab" => Some(ColorSpace::Lab),
            "diverging" => Some(ColorSpace::Diverging),
            "step" => Some(ColorSpace::Step),
            _ => None,
        }
    }
}

/// The colour at `t` in [0, 1] between control colours `c0` (t = 0) and
/// `c1` (t = 1). Lab and diverging results are clamped to [0, 1] (colours
/// outside the sRGB gamut), as VTK does.
pub fn interpolate(space: ColorSpace, c0: [f64; 3], c1: [f64; 3], t: f64) -> [f64; 3] {
    match space {
        ColorSpace::Rgb => lerp3(c0, c1, t),
        ColorSpace::Step => {
            if t > 0.0 {
                c1
            } else {
                c0
            }
        }
        ColorSpace::Hsv { wrap } => interpolate_hsv(c0, c1, t, wrap),
        ColorSpace::Lab => {
            let lab = lerp3(srgb_to_lab(c0), srgb_to_lab(c1), t);
            clamp_unit(lab_to_srgb(lab))
        }
        ColorSpace::Diverging => interpolate_diverging(c0, c1, t),
    }
}

fn lerp3(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

fn clamp_unit(c: [f64; 3]) -> [f64; 3] {
    c.map(|v| v.clamp(0.0, 1.0))
}

/// Hue, saturation and value, each in [0, 1] (hue 0 for greys).
pub fn rgb_to_hsv(rgb: [f64; 3]) -> [f64; 3] {
    let [r, g, b] = rgb;
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let delta = max - min;
    let saturation = if max > 0.0 { delta / max } else { 0.0 };
    let sextant = if delta <= 0.0 {
        0.0
    } else if max == r {
        (g - b) / delta
    } else if max == g {
        2.0 + (b - r) / delta
    } else {
        4.0 + (r - g) / delta
    };
    [(sextant / 6.0).rem_euclid(1.0), saturation, max]
}

pub fn hsv_to_rgb(hsv: [f64; 3]) -> [f64; 3] {
    let [h, s, v] = hsv;
    let sextant = h.rem_euclid(1.0) * 6.0;
    // Each primary is a trapezoid over the hue circle.
    let channel = |centre: f64| {
        let distance = (sextant - centre).rem_euclid(6.0);
        let distance = distance.min(6.0 - distance);
        let weight = (2.0 - distance).clamp(0.0, 1.0);
        v * (1.0 - s + s * weight)
    };
    [channel(0.0), channel(2.0), channel(4.0)]
}

fn interpolate_hsv(c0: [f64; 3], c1: [f64; 3], t: f64, wrap: bool) -> [f64; 3] {
    let mut a = rgb_to_hsv(c0);
    let mut b = rgb_to_hsv(c1);
    if wrap && (a[0] - b[0]).abs() > 0.5 {
        if a[0] < b[0] {
            a[0] += 1.0;
        } else {
            b[0] += 1.0;
        }
    }
    let hsv = lerp3(a, b, t);
    hsv_to_rgb([hsv[0].rem_euclid(1.0), hsv[1], hsv[2]])
}

/// sRGB primaries to CIE XYZ, D65 white (rows X, Y, Z).
fn rgb_to_xyz_matrix() -> DMat3 {
    DMat3::from_cols_array(&[
        0.4124564, 0.2126729, 0.0193339, // red column
        0.3575761, 0.7151522, 0.1191920, // green column
        0.1804375, 0.0721750, 0.9503041, // blue column
    ])
}

/// The D65 white point in XYZ (the sums of the matrix rows).
const WHITE_D65: [f64; 3] = [0.95047, 1.0, 1.08883];

fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_to_srgb(c: f64) -> f64 {
    if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// CIELAB's cube root, with the linear toe below (6/29)^3.
fn lab_f(t: f64) -> f64 {
    const DELTA: f64 = 6.0 / 29.0;
    if t > DELTA * DELTA * DELTA {
        t.cbrt()
    } else {
        t / (3.0 * DELTA * DELTA) + 4.0 / 29.0
    }
}

fn lab_f_inverse(f: f64) -> f64 {
    const DELTA: f64 = 6.0 / 29.0;
    if f > DELTA {
        f * f * f
    } else {
        3.0 * DELTA * DELTA * (f - 4.0 / 29.0)
    }
}

/// sRGB in [0, 1] to CIELAB (L in [0, 100]).
pub fn srgb_to_lab(rgb: [f64; 3]) -> [f64; 3] {
    let linear = DVec3::from_array(rgb.map(srgb_to_linear));
    let xyz = rgb_to_xyz_matrix() * linear;
    let [fx, fy, fz] = [0, 1, 2].map(|k| lab_f(xyz[k] / WHITE_D65[k]));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// CIELAB to sRGB, not clamped (out-of-gamut colours leave [0, 1]).
pub fn lab_to_srgb(lab: [f64; 3]) -> [f64; 3] {
    let [l, a, b] = lab;
    let fy = (l + 16.0) / 116.0;
    let f = [fy + a / 500.0, fy, fy - b / 200.0];
    let xyz = DVec3::from_array([0, 1, 2].map(|k| lab_f_inverse(f[k]) * WHITE_D65[k]));
    let linear = rgb_to_xyz_matrix().inverse() * xyz;
    linear.to_array().map(linear_to_srgb)
}

/// CIELAB to Msh: magnitude, saturation (angle from the L axis), hue.
pub fn lab_to_msh(lab: [f64; 3]) -> [f64; 3] {
    let [l, a, b] = lab;
    let m = (l * l + a * a + b * b).sqrt();
    let s = if m > 0.001 {
        (l / m).clamp(-1.0, 1.0).acos()
    } else {
        0.0
    };
    let h = if s > 0.001 { b.atan2(a) } else { 0.0 };
    [m, s, h]
}

pub fn msh_to_lab(msh: [f64; 3]) -> [f64; 3] {
    let [m, s, h] = msh;
    [m * s.cos(), m * s.sin() * h.cos(), m * s.sin() * h.sin()]
}

/// Saturation below which a colour counts as unsaturated (Moreland).
const UNSATURATED: f64 = 0.05;

/// Moreland's diverging interpolation: linear in Msh, through a white
/// midpoint when both ends are saturated and their hues differ by more than
/// 60 degrees, and with the hue of an unsaturated end spun towards the
/// saturated one so that the map does not turn through unrelated hues.
fn interpolate_diverging(c0: [f64; 3], c1: [f64; 3], t: f64) -> [f64; 3] {
    let mut a = lab_to_msh(srgb_to_lab(c0));
    let mut b = lab_to_msh(srgb_to_lab(c1));
    let mut t = t;
    if a[1] > UNSATURATED && b[1] > UNSATURATED && hue_distance(a[2], b[2]) > PI / 3.0 {
        let white = [a[0].max(b[0]).max(88.0), 0.0, 0.0];
        if t < 0.5 {
            b = white;
            t *= 2.0;
        } else {
            a = white;
            t = 2.0 * t - 1.0;
        }
    }
    if a[1] < UNSATURATED && b[1] > UNSATURATED {
        a[2] = spun_hue(b, a[0]);
    } else if b[1] < UNSATURATED && a[1] > UNSATURATED {
        b[2] = spun_hue(a, b[0]);
    }
    clamp_unit(lab_to_srgb(msh_to_lab(lerp3(a, b, t))))
}

/// Angle between two hues in radians, in [0, pi].
fn hue_distance(h0: f64, h1: f64) -> f64 {
    let d = (h0 - h1).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

/// The hue to give an unsaturated colour of magnitude `m_unsaturated` that
/// is interpolated with the saturated `saturated` (Moreland's hue spin).
fn spun_hue(saturated: [f64; 3], m_unsaturated: f64) -> f64 {
    let [m, s, h] = saturated;
    if m >= m_unsaturated {
        return h;
    }
    let spin = s * (m_unsaturated * m_unsaturated - m * m).sqrt() / (m * s.sin());
    if h > -PI / 3.0 { h + spin } else { h - spin }
}
