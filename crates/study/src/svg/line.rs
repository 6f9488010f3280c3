//! Line charts: one or more panels, each with its series, axes and legend.

use std::fmt::Write as _;

use super::{Axis, Frame, PALETTE, Scale, Svg, draw_axes, fit_range};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stroke {
    Solid,
    Dashed,
}

/// One line: its legend label, points, colour (index into the palette) and
/// stroke; `markers` draws a dot at every point.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub colour: usize,
    pub stroke: Stroke,
    pub markers: bool,
}

impl Series {
    pub fn new(label: impl Into<String>, colour: usize, points: Vec<(f64, f64)>) -> Series {
        Series {
            label: label.into(),
            points,
            colour,
            stroke: Stroke::Solid,
            markers: false,
        }
    }

    pub fn dashed(mut self) -> Series {
        self.stroke = Stroke::Dashed;
        self
    }

    pub fn with_markers(mut self) -> Series {
        self.markers = true;
        self
    }
}

/// One chart of a figure.
#[derive(Debug, Clone, PartialEq)]
pub struct LinePanel {
    pub title: String,
    pub x: Axis,
    pub y: Axis,
    pub series: Vec<Series>,
}

const PANEL_W: f64 = 470.0;
const PANEL_H: f64 = 330.0;
const LEGEND_W: f64 = 170.0;
const MARGIN_LEFT: f64 = 70.0;
const MARGIN_TOP: f64 = 30.0;
const MARGIN_BOTTOM: f64 = 50.0;
const TITLE_H: f64 = 34.0;

/// The SVG of a figure titled `title` with `panels` laid out in `columns`.
pub fn line_figure(title: &str, panels: &[LinePanel], columns: usize) -> String {
    let columns = columns.clamp(1, panels.len().max(1));
    let rows = panels.len().div_ceil(columns).max(1);
    let cell_w = PANEL_W + LEGEND_W;
    let width = columns as f64 * cell_w;
    let height = TITLE_H + rows as f64 * PANEL_H;
    let mut svg = Svg::new(width, height);
    svg.text((0.5 * width, 22.0), 16.0, "middle", 0.0, title);
    for (i, panel) in panels.iter().enumerate() {
        let x0 = (i % columns) as f64 * cell_w;
        let y0 = TITLE_H + (i / columns) as f64 * PANEL_H;
        draw_panel(&mut svg, panel, x0, y0);
    }
    svg.finish()
}

/// Whether a point can be drawn on the panel's scales.
fn drawable(panel: &LinePanel, (x, y): (f64, f64)) -> bool {
    let ok = |v: f64, scale: Scale| v.is_finite() && (scale == Scale::Linear || v > 0.0);
    ok(x, panel.x.scale) && ok(y, panel.y.scale)
}

fn data_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

fn draw_panel(svg: &mut Svg, panel: &LinePanel, x0: f64, y0: f64) {
    let points = || {
        panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|&p| drawable(panel, p))
    };
    let frame = Frame {
        x: x0 + MARGIN_LEFT,
        y: y0 + MARGIN_TOP,
        w: PANEL_W - MARGIN_LEFT - 20.0,
        h: PANEL_H - MARGIN_TOP - MARGIN_BOTTOM,
        x_range: fit_range(&panel.x, data_range(points().map(|p| p.0))),
        y_range: fit_range(&panel.y, data_range(points().map(|p| p.1))),
        x_scale: panel.x.scale,
        y_scale: panel.y.scale,
    };
    svg.text(
        (frame.x + 0.5 * frame.w, y0 + 18.0),
        13.0,
        "middle",
        0.0,
        &panel.title,
    );
    // Clip the lines to the frame.
    let clip = format!("clip{:.0}x{:.0}", x0, y0);
    svg.raw(&format!(
        "<clipPath id=\"{clip}\"><rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\"/></clipPath>",
        frame.x, frame.y, frame.w, frame.h
    ));
    for series in &panel.series {
        let colour = PALETTE[series.colour % PALETTE.len()];
        let mut path = String::new();
        let mut pen_down = false;
        for &p in &series.points {
            if !drawable(panel, p) {
                pen_down = false;
                continue;
            }
            let (px, py) = frame.map(p.0, p.1);
            let _ = write!(path, "{}{px:.1},{py:.1} ", if pen_down { "L" } else { "M" });
            pen_down = true;
        }
        let dash = match series.stroke {
            Stroke::Solid => "",
            Stroke::Dashed => " stroke-dasharray=\"6,4\"",
        };
        svg.raw(&format!(
            "<path d=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.6\"{dash} clip-path=\"url(#{clip})\"/>",
            path.trim_end()
        ));
        if series.markers {
            for &p in series.points.iter().filter(|&&p| drawable(panel, p)) {
                let (px, py) = frame.map(p.0, p.1);
                svg.raw(&format!(
                    "<circle cx=\"{px:.2}\" cy=\"{py:.2}\" r=\"2.6\" fill=\"{colour}\" clip-path=\"url(#{clip})\"/>"
                ));
            }
        }
    }
    draw_axes(svg, &frame, &panel.x.label, &panel.y.label);
    draw_legend(svg, panel, frame.x + frame.w + 14.0, frame.y);
}

fn draw_legend(svg: &mut Svg, panel: &LinePanel, x: f64, y: f64) {
    for (i, series) in panel.series.iter().enumerate() {
        if series.label.is_empty() {
            continue;
        }
        let colour = PALETTE[series.colour % PALETTE.len()];
        let ly = y + 8.0 + 17.0 * i as f64;
        let dash = match series.stroke {
            Stroke::Solid => "",
            Stroke::Dashed => " stroke-dasharray=\"6,4\"",
        };
        svg.raw(&format!(
            "<line x1=\"{x:.2}\" y1=\"{ly:.2}\" x2=\"{:.2}\" y2=\"{ly:.2}\" stroke=\"{colour}\" stroke-width=\"2\"{dash}/>",
            x + 22.0
        ));
        svg.text((x + 27.0, ly + 4.0), 11.0, "start", 0.0, &series.label);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figure_has_titles_labels_and_paths() {
        let panel = LinePanel {
            title: "panel <one>".into(),
            x: Axis::linear("x label"),
            y: Axis::log("y label"),
            series: vec![
                Series::new("a", 0, vec![(0.0, 1e-3), (1.0, 1e-1)]),
                Series::new("b", 1, vec![(0.0, 0.0), (1.0, 1e-2)])
                    .dashed()
                    .with_markers(),
            ],
        };
        let svg = line_figure("figure", &[panel.clone(), panel], 2);
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
        for text in [
            "figure",
            "panel &lt;one&gt;",
            "x label",
            "y label",
            ">a<",
            ">b<",
        ] {
            assert!(svg.contains(text), "{text}");
        }
        // The point at y = 0 cannot be drawn on a log axis: one move, one line.
        assert_eq!(svg.matches("<path").count(), 4);
        assert!(svg.contains("stroke-dasharray"));
    }
}
