//! Error maps as colour: a perceptually ordered dark-to-bright map
//! (black, purple, red, orange, yellow, white, after matplotlib's inferno)
//! and a labelled colour bar.

use image::{Rgb, RgbImage};

use crate::font::{LINE, draw_text, text_width};

const STOPS: [[f32; 3]; 6] = [
    [0.0, 0.0, 0.015],
    [0.26, 0.04, 0.41],
    [0.58, 0.15, 0.40],
    [0.87, 0.32, 0.23],
    [0.99, 0.65, 0.04],
    [0.99, 1.0, 0.64],
];

/// The colour of `t` in [0, 1] (clamped).
pub fn colour(t: f32) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (STOPS.len() - 1) as f32;
    let i = (x as usize).min(STOPS.len() - 2);
    let f = x - i as f32;
    std::array::from_fn(|c| {
        let v = STOPS[i][c] + (STOPS[i + 1][c] - STOPS[i][c]) * f;
        (v * 255.0).round() as u8
    })
}

/// `values` (row-major) mapped with 0 black and `max` and above white.
pub fn heat_map(values: &[f32], width: u32, height: u32, max: f32) -> RgbImage {
    let scale = if max > 0.0 { 1.0 / max } else { 0.0 };
    RgbImage::from_fn(width, height, |x, y| {
        Rgb(colour(values[(y * width + x) as usize] * scale))
    })
}

/// A vertical colour bar `height` pixels tall for values 0..`max`, ticks
/// labelled, `title` on top.
pub fn colour_bar(height: u32, max: f32, title: &str) -> RgbImage {
    let labels: Vec<String> = (0..=4)
        .map(|i| format_value(max * (4 - i) as f32 / 4.0))
        .collect();
    let label_width = labels.iter().map(|l| text_width(l, 1)).max().unwrap_or(0);
    let bar = 14;
    let width = (bar + 6 + label_width).max(text_width(title, 1)) + 4;
    let top = LINE + 4;
    let mut out = RgbImage::from_pixel(width, height + top + LINE, Rgb([255, 255, 255]));
    draw_text(&mut out, 0, 0, title, 1, [0, 0, 0]);
    for y in 0..height {
        let t = 1.0 - y as f32 / (height - 1).max(1) as f32;
        for x in 0..bar {
            out.put_pixel(x, top + y, Rgb(colour(t)));
        }
    }
    for (i, label) in labels.iter().enumerate() {
        let y = top + (height - 1) * i as u32 / 4;
        for x in bar..bar + 4 {
            out.put_pixel(x, y, Rgb([0, 0, 0]));
        }
        draw_text(&mut out, bar + 6, y.saturating_sub(3), label, 1, [0, 0, 0]);
    }
    out
}

/// A short number for a tick: 0, 0.25, 1.2E-3.
pub fn format_value(v: f32) -> String {
    if v == 0.0 {
        "0".to_string()
    } else if (0.01..1000.0).contains(&v.abs()) {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.1e}").to_uppercase()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_map_runs_dark_to_bright() {
        let luminance =
            |c: [u8; 3]| 0.3 * f32::from(c[0]) + 0.59 * f32::from(c[1]) + 0.11 * f32::from(c[2]);
        let steps: Vec<f32> = (0..=20)
            .map(|i| luminance(colour(i as f32 / 20.0)))
            .collect();
        assert!(steps.windows(2).all(|w| w[1] > w[0]), "{steps:?}");
        assert_eq!(colour(-1.0), colour(0.0));
        assert_eq!(colour(f32::NAN), colour(0.0));
        let map = heat_map(&[0.0, 0.5, 1.0, 2.0], 2, 2, 1.0);
        assert_eq!(map.get_pixel(1, 1).0, colour(1.0));
        assert_eq!(format_value(0.25), "0.25");
        assert_eq!(format_value(0.0012), "1.2E-3");
        assert!(colour_bar(64, 0.1, "abs error").height() > 64);
    }
}
