//! ParaView presets: how closely the linear pieces follow the colour-space
//! interpolation and the opacity curves they replace, and the colour-space
//! maths against published values.

use tetray_integrate::TransferFunction;
use tetray_integrate::colorspace::{self, ColorSpace};

/// The error budget of the piecewise-linear approximations (colour and
/// opacity units).
const BUDGET: f64 = 1e-3;
/// Samples per interval when measuring an approximation error.
const MEASURE_SAMPLES: usize = 4000;

fn read(text: &str) -> TransferFunction {
    TransferFunction::from_paraview_json(text, None, None).unwrap_or_else(|e| panic!("{e}"))
}

fn rgb_preset(space: &str, rgb_points: &str) -> String {
    format!(r#"{{"ColorSpace": "{space}", "RGBPoints": [{rgb_points}]}}"#)
}

fn opacity_preset(points: &str) -> String {
    format!(
        r#"{{"ColorSpace": "RGB", "RGBPoints": [0, 1, 1, 1, 1, 1, 1, 1], "Points": [{points}]}}"#
    )
}

/// The opacity shape vtkPiecewiseFunction documents, written out here from
/// its description to check the library's version against.
fn vtk_opacity(y0: f64, y1: f64, midpoint: f64, sharpness: f64, t: f64) -> f64 {
    let u = if t < midpoint {
        0.5 * t / midpoint
    } else {
        0.5 + 0.5 * (t - midpoint) / (1.0 - midpoint)
    };
    if sharpness < 0.01 {
        return y0 + (y1 - y0) * u;
    }
    if sharpness > 0.99 {
        return if u < 0.5 { y0 } else { y1 };
    }
    let p = 1.0 + 10.0 * sharpness;
    let s = if u < 0.5 {
        0.5 * (2.0 * u).powf(p)
    } else {
        1.0 - 0.5 * (2.0 * (1.0 - u)).powf(p)
    };
    let h00 = 2.0 * s.powi(3) - 3.0 * s * s + 1.0;
    let h01 = 1.0 - h00;
    let h10 = s.powi(3) - 2.0 * s * s + s;
    let h11 = s.powi(3) - s * s;
    let tangent = (1.0 - sharpness) * (y1 - y0);
    h00 * y0 + h01 * y1 + (h10 + h11) * tangent
}

/// Largest |tf colour - colour-space interpolation| over one interval.
fn color_error(
    tf: &TransferFunction,
    space: ColorSpace,
    (x0, c0): (f32, [f64; 3]),
    (x1, c1): (f32, [f64; 3]),
) -> f64 {
    (1..MEASURE_SAMPLES)
        .map(|k| {
            let t = k as f64 / MEASURE_SAMPLES as f64;
            let s = x0 + (x1 - x0) * t as f32;
            let t = f64::from((s - x0) / (x1 - x0));
            let want = colorspace::interpolate(space, c0, c1, t);
            let got = tf.color_at(s).to_array();
            (0..3)
                .map(|c| (f64::from(got[c]) - want[c]).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

#[test]
fn sharp_opacity_curves_stay_within_the_budget() {
    println!("midpoint sharpness pieces max_error");
    for &(midpoint, sharpness) in &[
        (0.5, 0.2),
        (0.5, 0.5),
        (0.3, 0.5),
        (0.8, 0.75),
        (0.5, 0.9),
        (0.1, 0.98),
    ] {
        let text = opacity_preset(&format!(
            "0, 0.05, {midpoint}, {sharpness}, 1, 0.95, 0.5, 0"
        ));
        let tf = read(&text);
        let error = (0..=MEASURE_SAMPLES)
            .map(|k| {
                let s = k as f32 / MEASURE_SAMPLES as f32;
                let want = vtk_opacity(0.05, 0.95, midpoint, sharpness, f64::from(s));
                (f64::from(tf.opacity_at(s)) - want).abs()
            })
            .fold(0.0, f64::max);
        let pieces = tf.opacity_points().len() - 1;
        println!("{midpoint:8} {sharpness:9} {pieces:6} {error:.2e}");
        assert!(
            error < BUDGET,
            "midpoint {midpoint}, sharpness {sharpness}: error {error}"
        );
        assert!(pieces <= 64, "{pieces} pieces");
    }
}

/// Colour pairs that exercise each rule: a diverging pair (white midpoint),
/// saturated to grey (hue spin), hues far apart, close colours.
const COLOR_PAIRS: &[([f64; 3], [f64; 3])] = &[
    ([0.230, 0.299, 0.754], [0.706, 0.016, 0.150]),
    ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
    ([0.9, 0.9, 0.9], [0.1, 0.6, 0.2]),
    ([1.0, 1.0, 0.0], [0.2, 0.2, 0.2]),
    ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
    ([0.8, 0.1, 0.6], [0.1, 0.8, 0.7]),
    ([0.5, 0.4, 0.3], [0.52, 0.41, 0.33]),
];

fn check_color_space(name: &str, space: ColorSpace) {
    println!("{name}: pieces and max error per pair");
    for &(c0, c1) in COLOR_PAIRS {
        let points = format!(
            "-2, {}, {}, {}, 3, {}, {}, {}",
            c0[0], c0[1], c0[2], c1[0], c1[1], c1[2]
        );
        let tf = read(&rgb_preset(name, &points));
        let error = color_error(&tf, space, (-2.0, c0), (3.0, c1));
        let pieces = tf.color_points().len() - 1;
        println!("  {c0:?} -> {c1:?}: {pieces} pieces, error {error:.2e}");
        assert!(error < BUDGET, "{name} {c0:?} -> {c1:?}: error {error}");
        assert!(pieces <= 128, "{name}: {pieces} pieces");
    }
}

#[test]
fn lab_interpolation_stays_within_the_budget() {
    check_color_space("Lab", ColorSpace::Lab);
    assert_eq!(
        read(&rgb_preset("CIELAB", "0, 1, 0, 0, 1, 0, 0, 1")),
        read(&rgb_preset("Lab", "0, 1, 0, 0, 1, 0, 0, 1"))
    );
}

#[test]
fn diverging_interpolation_stays_within_the_budget() {
    check_color_space("Diverging", ColorSpace::Diverging);
}

#[test]
fn hsv_interpolation_stays_within_the_budget() {
    check_color_space("HSV", ColorSpace::Hsv { wrap: false });
}

#[test]
fn wrapped_hsv_interpolation_stays_within_the_budget() {
    println!("HSVWrap:");
    for &(c0, c1) in COLOR_PAIRS {
        let text = format!(
            r#"{{"ColorSpace": "HSV", "HSVWrap": 1, "RGBPoints": [0, {}, {}, {}, 1, {}, {}, {}]}}"#,
            c0[0], c0[1], c0[2], c1[0], c1[1], c1[2]
        );
        let tf = read(&text);
        let error = color_error(&tf, ColorSpace::Hsv { wrap: true }, (0.0, c0), (1.0, c1));
        println!(
            "  {c0:?} -> {c1:?}: {} pieces, error {error:.2e}",
            tf.color_points().len() - 1
        );
        assert!(error < BUDGET, "{c0:?} -> {c1:?}: error {error}");
    }
}

/// A small deterministic generator for the randomised checks.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn random_colour_pairs_stay_within_the_budget_in_every_space() {
    let spaces = [
        ("Lab", ColorSpace::Lab, 0),
        ("Diverging", ColorSpace::Diverging, 0),
        ("HSV", ColorSpace::Hsv { wrap: false }, 0),
        ("HSV", ColorSpace::Hsv { wrap: true }, 1),
    ];
    let mut rng = Lcg(7);
    for (name, space, wrap) in spaces {
        let (mut worst, mut most_pieces) = (0.0f64, 0);
        for _ in 0..200 {
            let c0 = [rng.next(), rng.next(), rng.next()];
            let c1 = [rng.next(), rng.next(), rng.next()];
            let text = format!(
                r#"{{"ColorSpace": "{name}", "HSVWrap": {wrap}, "RGBPoints": [0, {}, {}, {}, 1, {}, {}, {}]}}"#,
                c0[0], c0[1], c0[2], c1[0], c1[1], c1[2]
            );
            let tf = read(&text);
            worst = worst.max(color_error(&tf, space, (0.0, c0), (1.0, c1)));
            most_pieces = most_pieces.max(tf.color_points().len() - 1);
        }
        println!(
            "{space:?}: 200 random pairs, max error {worst:.2e}, at most {most_pieces} pieces"
        );
        assert!(worst < BUDGET, "{space:?}: error {worst}");
    }
}

#[test]
fn random_opacity_shapes_stay_within_the_budget() {
    let mut rng = Lcg(11);
    let (mut worst, mut most_pieces) = (0.0f64, 0);
    for _ in 0..200 {
        let (y0, y1, midpoint, sharpness) = (rng.next(), rng.next(), rng.next(), rng.next());
        let tf = read(&opacity_preset(&format!(
            "0, {y0}, {midpoint}, {sharpness}, 1, {y1}, 0.5, 0"
        )));
        let error = (0..=MEASURE_SAMPLES)
            .map(|k| {
                let s = k as f32 / MEASURE_SAMPLES as f32;
                let want = vtk_opacity(y0, y1, midpoint, sharpness, f64::from(s));
                (f64::from(tf.opacity_at(s)) - want).abs()
            })
            .fold(0.0, f64::max);
        worst = worst.max(error);
        most_pieces = most_pieces.max(tf.opacity_points().len() - 1);
    }
    println!("200 random opacity intervals: max error {worst:.2e}, at most {most_pieces} pieces");
    assert!(worst < BUDGET, "error {worst}");
}

#[test]
fn diverging_matches_morelands_cool_to_warm_table() {
    // Moreland (2009) tabulates this map to three decimals; the ends given
    // here are rounded too, hence 3e-3.
    let tf = read(&rgb_preset(
        "Diverging",
        "0, 0.230, 0.299, 0.754, 1, 0.706, 0.016, 0.150",
    ));
    for (s, want) in [
        (0.25, [0.552, 0.690, 0.996]),
        (0.5, [0.865, 0.865, 0.865]),
        (0.75, [0.958, 0.604, 0.482]),
    ] {
        let got = tf.color_at(s);
        for c in 0..3 {
            assert!(
                (got[c] - want[c]).abs() < 0.003,
                "at {s}: {got} vs {want:?}"
            );
        }
    }
}

#[test]
fn lab_conversion_matches_published_values() {
    let lab = colorspace::srgb_to_lab([1.0, 0.0, 0.0]);
    for (got, want) in lab.iter().zip([53.24, 80.09, 67.20]) {
        assert!((got - want).abs() < 0.02, "{lab:?}");
    }
    let back = colorspace::lab_to_srgb(colorspace::srgb_to_lab([0.2, 0.5, 0.7]));
    for (got, want) in back.iter().zip([0.2, 0.5, 0.7]) {
        assert!((got - want).abs() < 1e-9, "{back:?}");
    }
}
