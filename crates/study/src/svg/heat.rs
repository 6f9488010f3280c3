//! Heat maps: one or more panels of a scalar over a 2-D grid sharing one
//! colour scale, with a colour bar. Each panel's raster is an embedded PNG
//! (a few kB) rather than one SVG rectangle per cell.

use base64::Engine as _;
use image::ImageEncoder as _;

use super::{Frame, Scale, Svg, draw_axes, format_number, ticks};

/// A grid of values over `x_range` x `y_range`: `values[j * nx + i]` is
/// the cell at column `i` (x) and row `j` (y, row 0 at `y_range.0`).
#[derive(Debug, Clone, PartialEq)]
pub struct HeatPanel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_range: (f64, f64),
    pub y_range: (f64, f64),
    pub nx: usize,
    pub ny: usize,
    pub values: Vec<f64>,
}

/// How values map to colours: linearly or by decade over `[lo, hi]`,
/// clamped at both ends. Values that cannot be shown (NaN, or at most 0 on
/// a log scale below `lo`) take the low colour; NaN is grey.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColourScale {
    pub scale: Scale,
    pub lo: f64,
    pub hi: f64,
}

impl ColourScale {
    /// A log scale over the decades spanning the positive values, at most
    /// `max_decades` below the largest.
    pub fn log_fit(values: impl Iterator<Item = f64>, max_decades: i32) -> ColourScale {
        let hi = values
            .filter(|v| v.is_finite() && *v > 0.0)
            .fold(0.0f64, f64::max);
        let hi_decade = if hi > 0.0 {
            hi.log10().ceil() as i32
        } else {
            0
        };
        ColourScale {
            scale: Scale::Log10,
            lo: 10f64.powi(hi_decade - max_decades),
            hi: 10f64.powi(hi_decade),
        }
    }

    /// Position of `v` on the bar, in `[0, 1]`.
    fn fraction(&self, v: f64) -> f64 {
        let f = match self.scale {
            Scale::Linear => (v - self.lo) / (self.hi - self.lo),
            Scale::Log10 if v > 0.0 => {
                (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
            }
            Scale::Log10 => 0.0,
        };
        f.clamp(0.0, 1.0)
    }

    fn colour(&self, v: f64) -> [u8; 3] {
        if v.is_nan() {
            return [160, 160, 160];
        }
        viridis(self.fraction(v))
    }
}

/// Anchors of the viridis colour map, evenly spaced over `[0, 1]`.
const VIRIDIS: [[f64; 3]; 9] = [
    [68.0, 1.0, 84.0],
    [71.0, 44.0, 122.0],
    [59.0, 81.0, 139.0],
    [44.0, 113.0, 142.0],
    [33.0, 144.0, 141.0],
    [39.0, 173.0, 129.0],
    [92.0, 200.0, 99.0],
    [170.0, 220.0, 50.0],
    [253.0, 231.0, 37.0],
];

/// The viridis colour at `t` in `[0, 1]` (piecewise linear between anchors).
pub fn viridis(t: f64) -> [u8; 3] {
    let x = t.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f64;
    let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    [0, 1, 2].map(|c| (a[c] + (b[c] - a[c]) * f).round() as u8)
}

/// Why a heat map could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum HeatError {
    #[error("heat map panel {title:?} has {values} values for a {nx} x {ny} grid")]
    GridSize {
        title: String,
        values: usize,
        nx: usize,
        ny: usize,
    },
    #[error("encoding the raster of heat map panel {title:?}: {source}")]
    Encode {
        title: String,
        source: image::ImageError,
    },
}

const PANEL: f64 = 300.0;
const CELL_W: f64 = PANEL + 110.0;
const CELL_H: f64 = PANEL + 100.0;
const BAR_W: f64 = 130.0;
const TITLE_H: f64 = 34.0;

/// The SVG of `panels` in `columns` sharing `colours`, whose bar is
/// labelled `colour_label`.
pub fn heat_figure(
    title: &str,
    panels: &[HeatPanel],
    columns: usize,
    colours: ColourScale,
    colour_label: &str,
) -> Result<String, HeatError> {
    let columns = columns.clamp(1, panels.len().max(1));
    let rows = panels.len().div_ceil(columns).max(1);
    let width = columns as f64 * CELL_W + BAR_W;
    let height = TITLE_H + rows as f64 * CELL_H;
    let mut svg = Svg::new(width, height);
    svg.text((0.5 * width, 22.0), 16.0, "middle", 0.0, title);
    for (k, panel) in panels.iter().enumerate() {
        let frame = Frame {
            x: (k % columns) as f64 * CELL_W + 80.0,
            y: TITLE_H + (k / columns) as f64 * CELL_H + 30.0,
            w: PANEL,
            h: PANEL,
            x_range: panel.x_range,
            y_range: panel.y_range,
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
        };
        let png = raster(panel, &colours)?;
        svg.raw(&format!(
            "<image x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" preserveAspectRatio=\"none\" \
             style=\"image-rendering:pixelated\" href=\"data:image/png;base64,{png}\"/>",
            frame.x, frame.y, frame.w, frame.h
        ));
        svg.text(
            (frame.x + 0.5 * frame.w, frame.y - 10.0),
            13.0,
            "middle",
            0.0,
            &panel.title,
        );
        draw_axes(&mut svg, &frame, &panel.x_label, &panel.y_label);
    }
    colour_bar(
        &mut svg,
        columns as f64 * CELL_W + 10.0,
        TITLE_H + 30.0,
        colours,
        colour_label,
    );
    Ok(svg.finish())
}

/// The panel's cells as a base64 PNG, top row first.
fn raster(panel: &HeatPanel, colours: &ColourScale) -> Result<String, HeatError> {
    let (nx, ny) = (panel.nx, panel.ny);
    if panel.values.len() != nx * ny || nx == 0 || ny == 0 {
        return Err(HeatError::GridSize {
            title: panel.title.clone(),
            values: panel.values.len(),
            nx,
            ny,
        });
    }
    let mut rgb = Vec::with_capacity(3 * nx * ny);
    for j in (0..ny).rev() {
        for i in 0..nx {
            rgb.extend(colours.colour(panel.values[j * nx + i]));
        }
    }
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(&rgb, nx as u32, ny as u32, image::ExtendedColorType::Rgb8)
        .map_err(|source| HeatError::Encode {
            title: panel.title.clone(),
            source,
        })?;
    Ok(base64::engine::general_purpose::STANDARD.encode(png))
}

fn colour_bar(svg: &mut Svg, x: f64, y: f64, colours: ColourScale, label: &str) {
    let (w, h) = (18.0, PANEL);
    let mut stops = String::new();
    for k in 0..=16 {
        let t = k as f64 / 16.0;
        let [r, g, b] = viridis(t);
        stops.push_str(&format!(
            "<stop offset=\"{t:.4}\" stop-color=\"rgb({r},{g},{b})\"/>"
        ));
    }
    svg.raw(&format!(
        "<linearGradient id=\"bar\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">{stops}</linearGradient>"
    ));
    svg.raw(&format!(
        "<rect x=\"{x:.2}\" y=\"{y:.2}\" width=\"{w}\" height=\"{h}\" fill=\"url(#bar)\" stroke=\"#333\"/>"
    ));
    for (v, text) in ticks((colours.lo, colours.hi), colours.scale) {
        let py = y + (1.0 - colours.fraction(v)) * h;
        svg.line((x + w, py), (x + w + 4.0, py), "#333");
        svg.text((x + w + 6.0, py + 4.0), 11.0, "start", 0.0, &text);
    }
    let note = match colours.scale {
        Scale::Log10 => format!(
            "{label} (log; below {} shown as {})",
            format_number(colours.lo),
            format_number(colours.lo)
        ),
        Scale::Linear => label.to_string(),
    };
    svg.text((x + w + 62.0, y + 0.5 * h), 12.0, "middle", -90.0, &note);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figure_embeds_rasters_and_a_bar() {
        let panel = HeatPanel {
            title: "t".into(),
            x_label: "gamma_b".into(),
            y_label: "gamma_f".into(),
            x_range: (0.0, 1.0),
            y_range: (0.0, 1.0),
            nx: 3,
            ny: 2,
            values: vec![1e-6, 1e-5, 1e-4, 1e-3, 0.0, f64::NAN],
        };
        let scale = ColourScale::log_fit(panel.values.iter().copied(), 4);
        assert_eq!((scale.lo, scale.hi), (1e-7, 1e-3));
        let svg = heat_figure("fig", &[panel.clone(), panel.clone()], 2, scale, "error").unwrap();
        assert_eq!(svg.matches("data:image/png;base64,").count(), 2);
        assert!(
            svg.contains("gamma_b") && svg.contains("gamma_f") && svg.contains("linearGradient")
        );
        let bad = HeatPanel { nx: 4, ..panel };
        assert!(heat_figure("fig", &[bad], 1, scale, "error").is_err());
    }

    #[test]
    fn colour_ends() {
        assert_eq!(viridis(0.0), [68, 1, 84]);
        assert_eq!(viridis(1.0), [253, 231, 37]);
        let s = ColourScale {
            scale: Scale::Linear,
            lo: 0.0,
            hi: 2.0,
        };
        assert_eq!(s.colour(5.0), viridis(1.0));
        assert_eq!(s.colour(f64::NAN), [160, 160, 160]);
    }
}
