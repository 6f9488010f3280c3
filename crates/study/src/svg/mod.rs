//! A small SVG plotting module: line charts ([`line`](mod@line)) and heat maps
//! ([`heat`]), each figure one or more titled panels with labelled axes,
//! ticks and a legend or colour bar. SVG text is drawn by the viewer's
//! fonts, so nothing here needs a font file.

pub mod heat;
pub mod line;
pub mod table;

use std::fmt::Write as _;

/// How an axis maps data to position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    Linear,
    /// Decades; values at or below zero are left out.
    Log10,
}

/// One axis of a panel: its label, scale and (optional) fixed range; a
/// range left `None` is fitted to the data.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub label: String,
    pub scale: Scale,
    pub range: Option<(f64, f64)>,
}

impl Axis {
    pub fn linear(label: impl Into<String>) -> Axis {
        Axis {
            label: label.into(),
            scale: Scale::Linear,
            range: None,
        }
    }

    pub fn log(label: impl Into<String>) -> Axis {
        Axis {
            label: label.into(),
            scale: Scale::Log10,
            range: None,
        }
    }

    pub fn with_range(mut self, lo: f64, hi: f64) -> Axis {
        self.range = Some((lo, hi));
        self
    }
}

/// Colours of successive series (Okabe-Ito, readable by colour-blind
/// viewers), then repeated.
pub const PALETTE: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442",
];

/// An SVG document being written.
pub(crate) struct Svg {
    out: String,
}

impl Svg {
    pub(crate) fn new(width: f64, height: f64) -> Svg {
        let mut out = String::new();
        let _ = write!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" \
             viewBox=\"0 0 {width:.0} {height:.0}\" font-family=\"sans-serif\">\n\
             <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        );
        Svg { out }
    }

    pub(crate) fn raw(&mut self, text: &str) {
        self.out.push_str(text);
        self.out.push('\n');
    }

    pub(crate) fn line(&mut self, (x0, y0): (f64, f64), (x1, y1): (f64, f64), stroke: &str) {
        let _ = writeln!(
            self.out,
            "<line x1=\"{x0:.2}\" y1=\"{y0:.2}\" x2=\"{x1:.2}\" y2=\"{y1:.2}\" stroke=\"{stroke}\" stroke-width=\"1\"/>"
        );
    }

    pub(crate) fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, fill: &str, stroke: &str) {
        let _ = writeln!(
            self.out,
            "<rect x=\"{x:.2}\" y=\"{y:.2}\" width=\"{w:.2}\" height=\"{h:.2}\" fill=\"{fill}\" stroke=\"{stroke}\"/>"
        );
    }

    /// Text at `(x, y)`; `anchor` is start, middle or end; `rotate` in
    /// degrees about the anchor point.
    pub(crate) fn text(
        &mut self,
        (x, y): (f64, f64),
        size: f64,
        anchor: &str,
        rotate: f64,
        text: &str,
    ) {
        let transform = if rotate != 0.0 {
            format!(" transform=\"rotate({rotate:.0} {x:.2} {y:.2})\"")
        } else {
            String::new()
        };
        let _ = writeln!(
            self.out,
            "<text x=\"{x:.2}\" y=\"{y:.2}\" font-size=\"{size:.0}\" text-anchor=\"{anchor}\"{transform}>{}</text>",
            escape(text)
        );
    }

    pub(crate) fn finish(mut self) -> String {
        self.out.push_str("</svg>\n");
        self.out
    }
}

/// XML-escapes `text`.
pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A panel's plotting area in pixels and the data ranges it shows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
    pub x_range: (f64, f64),
    pub y_range: (f64, f64),
    pub x_scale: Scale,
    pub y_scale: Scale,
}

impl Frame {
    /// Pixel position of a data point (y grows downwards in SVG).
    pub(crate) fn map(&self, vx: f64, vy: f64) -> (f64, f64) {
        let fx = fraction(vx, self.x_range, self.x_scale);
        let fy = fraction(vy, self.y_range, self.y_scale);
        (self.x + fx * self.w, self.y + (1.0 - fy) * self.h)
    }
}

/// Position of `v` in `range` as a fraction (outside `[0, 1]` when outside).
fn fraction(v: f64, (lo, hi): (f64, f64), scale: Scale) -> f64 {
    match scale {
        Scale::Linear => (v - lo) / (hi - lo),
        Scale::Log10 => (v.log10() - lo.log10()) / (hi.log10() - lo.log10()),
    }
}

/// The range an axis shows for data spanning `data` (min, max): the fixed
/// range if given, else the data padded to round numbers (decades for log
/// axes). Empty or degenerate data gives a unit range.
pub fn fit_range(axis: &Axis, data: Option<(f64, f64)>) -> (f64, f64) {
    if let Some(range) = axis.range {
        return range;
    }
    match (axis.scale, data) {
        (Scale::Linear, Some((lo, hi))) if hi > lo => {
            let step = nice_step((hi - lo) / 5.0);
            ((lo / step).floor() * step, (hi / step).ceil() * step)
        }
        (Scale::Linear, Some((v, _))) => (v - 0.5 * v.abs().max(1.0), v + 0.5 * v.abs().max(1.0)),
        (Scale::Log10, Some((lo, hi))) if lo > 0.0 => {
            let lo = 10f64.powf(lo.log10().floor());
            let hi = 10f64.powf(hi.log10().ceil());
            if hi > lo { (lo, hi) } else { (lo, lo * 10.0) }
        }
        (Scale::Linear, None) => (0.0, 1.0),
        (Scale::Log10, _) => (1.0, 10.0),
    }
}

/// 1, 2 or 5 times a power of ten, at least `raw`.
fn nice_step(raw: f64) -> f64 {
    if raw.is_nan() || raw <= 0.0 || raw.is_infinite() {
        return 1.0;
    }
    let power = 10f64.powf(raw.log10().floor());
    let mantissa = raw / power;
    let nice = if mantissa <= 1.0 {
        1.0
    } else if mantissa <= 2.0 {
        2.0
    } else if mantissa <= 5.0 {
        5.0
    } else {
        10.0
    };
    nice * power
}

/// Tick positions and labels of an axis over `range`.
pub(crate) fn ticks((lo, hi): (f64, f64), scale: Scale) -> Vec<(f64, String)> {
    match scale {
        Scale::Linear => {
            let step = nice_step((hi - lo) / 5.0);
            let first = (lo / step - 1e-9).ceil() as i64;
            let last = (hi / step + 1e-9).floor() as i64;
            (first..=last)
                .map(|k| {
                    let v = k as f64 * step;
                    (v, format_tick(v, step))
                })
                .collect()
        }
        Scale::Log10 => {
            let first = (lo.log10() - 1e-9).ceil() as i32;
            let last = (hi.log10() + 1e-9).floor() as i32;
            // At most about eight labelled decades.
            let every = ((last - first) / 8 + 1).max(1);
            (first..=last)
                .filter(|e| (e - first) % every == 0)
                .map(|e| (10f64.powi(e), format_decade(e)))
                .collect()
        }
    }
}

fn format_decade(exponent: i32) -> String {
    match exponent {
        -2..=3 => format_number(10f64.powi(exponent)),
        _ => format!("1e{exponent}"),
    }
}

/// A tick value with as many decimals as its step needs.
fn format_tick(v: f64, step: f64) -> String {
    if v == 0.0 {
        return "0".to_string();
    }
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        return format!("{v:.1e}");
    }
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// A number for labels and legends: short, exact for round values.
pub fn format_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        let text = format!("{v:.2e}");
        return text.replace(".00e", "e").replace("0e", "e");
    }
    let text = format!("{v:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    text.to_string()
}

/// Draws the frame box, tick marks and labels and the axis labels.
pub(crate) fn draw_axes(svg: &mut Svg, frame: &Frame, x_label: &str, y_label: &str) {
    svg.rect(frame.x, frame.y, frame.w, frame.h, "none", "#333");
    let bottom = frame.y + frame.h;
    for (v, label) in ticks(frame.x_range, frame.x_scale) {
        let (px, _) = frame.map(v, frame.y_range.0);
        if px < frame.x - 0.5 || px > frame.x + frame.w + 0.5 {
            continue;
        }
        svg.line((px, bottom), (px, bottom + 4.0), "#333");
        svg.text((px, bottom + 16.0), 11.0, "middle", 0.0, &label);
    }
    for (v, label) in ticks(frame.y_range, frame.y_scale) {
        let (_, py) = frame.map(frame.x_range.0, v);
        if py < frame.y - 0.5 || py > bottom + 0.5 {
            continue;
        }
        svg.line((frame.x - 4.0, py), (frame.x, py), "#333");
        svg.text((frame.x - 6.0, py + 4.0), 11.0, "end", 0.0, &label);
    }
    svg.text(
        (frame.x + 0.5 * frame.w, bottom + 34.0),
        12.0,
        "middle",
        0.0,
        x_label,
    );
    svg.text(
        (frame.x - 52.0, frame.y + 0.5 * frame.h),
        12.0,
        "middle",
        -90.0,
        y_label,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        let t = ticks((0.0, 1.0), Scale::Linear);
        let labels: Vec<&str> = t.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        let t = ticks((1e-7, 1.0), Scale::Log10);
        assert_eq!(t.first().unwrap().1, "1e-7");
        assert_eq!(t.last().unwrap().1, "1");
        assert!(t.iter().all(|(v, _)| *v >= 1e-7 * 0.999 && *v <= 1.0));
    }

    #[test]
    fn ranges_fit_the_data() {
        assert_eq!(fit_range(&Axis::log("e"), Some((3e-6, 0.2))), (1e-6, 1.0));
        let (lo, hi) = fit_range(&Axis::linear("x"), Some((0.13, 0.87)));
        assert!(lo <= 0.13 && hi >= 0.87 && hi - lo <= 1.0);
        assert_eq!(
            fit_range(&Axis::linear("x").with_range(0.0, 2.0), None),
            (0.0, 2.0)
        );
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
        assert_eq!(format_number(0.001), "0.001");
        assert_eq!(format_number(1e-6), "1e-6");
        assert_eq!(format_number(2.5), "2.5");
    }
}
