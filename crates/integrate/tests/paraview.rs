//! ParaView colour-map presets: reading every feature, every error case,
//! writing and round trips, the shipped presets. How closely the linear
//! pieces follow the curves they replace: `paraview_accuracy.rs`.

use glam::Vec3;
use tetray_integrate::{ColorPoint, OpacityPoint, TfError, TransferFunction};

fn read(text: &str) -> TransferFunction {
    TransferFunction::from_paraview_json(text, None, None).unwrap_or_else(|e| panic!("{e}"))
}

fn read_error(text: &str, name: Option<&str>) -> String {
    match TransferFunction::from_paraview_json(text, name, None) {
        Ok(tf) => panic!("expected an error, read {tf:?}"),
        Err(e) => e.to_string(),
    }
}

fn assert_mentions(message: &str, words: &[&str]) {
    for w in words {
        assert!(
            message.contains(w),
            "message {message:?} does not mention {w:?}"
        );
    }
}

fn rgb_preset(space: &str, rgb_points: &str) -> String {
    format!(
        r#"{{"Name": "t", "ColorSpace": "{space}", "RGBPoints": [{rgb_points}], "Points": [0, 0, 0.5, 0, 1, 1, 0.5, 0]}}"#
    )
}

fn opacity_preset(points: &str) -> String {
    format!(
        r#"{{"ColorSpace": "RGB", "RGBPoints": [0, 1, 1, 1, 1, 1, 1, 1], "Points": [{points}]}}"#
    )
}

#[test]
fn rgb_points_are_kept_as_one_piece_per_interval() {
    let tf = read(&rgb_preset("RGB", "-1, 0, 0, 1, 0, 1, 1, 1, 1, 1, 0, 0"));
    let scalars: Vec<f32> = tf.color_points().iter().map(|p| p.scalar).collect();
    assert_eq!(scalars, [-1.0, 0.0, 1.0]);
    assert_eq!(tf.color_at(-0.5), Vec3::new(0.5, 0.5, 1.0));
    assert_eq!(
        tf.opacity_points().len(),
        2,
        "midpoint 0.5, sharpness 0 is one linear piece"
    );
    assert_eq!(tf.opacity_at(0.25), 0.25);
}

#[test]
fn single_object_and_array_select_by_name() {
    let a = r#"{"Name": "A", "ColorSpace": "RGB", "RGBPoints": [0, 1, 0, 0, 1, 1, 0, 0], "Points": [0, 0.1, 0.5, 0]}"#;
    let b = r#"{"Name": "B", "ColorSpace": "RGB", "RGBPoints": [0, 0, 1, 0, 1, 0, 1, 0], "Points": [0, 0.2, 0.5, 0]}"#;
    let array = format!("[{a}, {b}]");
    let first = TransferFunction::from_paraview_json(&array, None, None).unwrap();
    assert_eq!(
        first.color_at(0.5),
        Vec3::X,
        "no name takes the first preset"
    );
    let second = TransferFunction::from_paraview_json(&array, Some("B"), None).unwrap();
    assert_eq!(second.color_at(0.5), Vec3::Y);
    assert_eq!(second.opacity_at(0.0), 0.2);
    let single = TransferFunction::from_paraview_json(a, Some("A"), None).unwrap();
    assert_eq!(single, first);
}

#[test]
fn missing_name_lists_the_available_ones() {
    let array = r#"[{"Name": "Cool", "RGBPoints": [0, 1, 1, 1]}, {"RGBPoints": [0, 1, 1, 1]}, {"Name": "Warm", "RGBPoints": [0, 1, 1, 1]}]"#;
    let message = read_error(array, Some("Jet"));
    assert_mentions(
        &message,
        &["\"Jet\"", "\"Cool\"", "\"Warm\"", "#1 (unnamed)"],
    );
    assert_mentions(&read_error("[]", None), &["empty"]);
}

#[test]
fn midpoint_without_sharpness_gives_two_pieces() {
    let tf = read(&opacity_preset("0, 0, 0.2, 0, 10, 1, 0.5, 0"));
    let points: Vec<(f32, f32)> = tf
        .opacity_points()
        .iter()
        .map(|p| (p.scalar, p.alpha))
        .collect();
    assert_eq!(points, [(0.0, 0.0), (2.0, 0.5), (10.0, 1.0)]);
    // Half the rise over the first fifth, the other half over the rest.
    assert_eq!(tf.opacity_at(1.0), 0.25);
    assert_eq!(tf.opacity_at(6.0), 0.75);
}

#[test]
fn sharpness_one_gives_an_exact_step() {
    let tf = read(&opacity_preset("0, 0.1, 0.25, 1, 4, 0.9, 0.5, 0"));
    let points: Vec<(f32, f32)> = tf
        .opacity_points()
        .iter()
        .map(|p| (p.scalar, p.alpha))
        .collect();
    assert_eq!(points, [(0.0, 0.1), (1.0, 0.1), (1.0, 0.9), (4.0, 0.9)]);
    assert_eq!(tf.opacity_at(0.999), 0.1);
    assert_eq!(tf.opacity_at(1.0), 0.9);
}

#[test]
fn sharpness_snaps_to_linear_and_step_as_vtk_does() {
    let linear = read(&opacity_preset("0, 0, 0.5, 0.005, 1, 1, 0.5, 0"));
    assert_eq!(linear.opacity_points().len(), 2);
    let step = read(&opacity_preset("0, 0, 0.5, 0.995, 1, 1, 0.5, 0"));
    assert_eq!(step.opacity_points().len(), 4);
}

#[test]
fn midpoint_at_the_ends_makes_a_step_there() {
    let tf = read(&opacity_preset("0, 0, 0, 0.5, 1, 1, 1, 0.5, 2, 0, 0.5, 0"));
    assert_eq!(
        tf.opacity_at(0.0),
        0.5,
        "midpoint 0: the mean is reached at once"
    );
    let before_end = tf.opacity_at(0.999_9);
    assert!(before_end > 0.99, "{before_end}");
    let tf = read(&opacity_preset("0, 0, 1, 0.5, 1, 1, 0.5, 0"));
    assert!(
        (tf.opacity_at(0.999_9) - 0.5).abs() < 1e-3,
        "midpoint 1: the mean until the end"
    );
    assert_eq!(tf.opacity_at(1.0), 1.0);
}

#[test]
fn hsv_wraps_only_when_asked() {
    // Red (hue 0) to magenta (hue 5/6): plain HSV runs through green and
    // blue, wrapped HSV takes the short way through the reds.
    let plain = read(&rgb_preset("HSV", "0, 1, 0, 0, 1, 1, 0, 1"));
    let middle = plain.color_at(0.5);
    assert!(
        middle.y > 0.9 && middle.x < 0.1,
        "plain HSV midpoint {middle}"
    );
    let text = r#"{"ColorSpace": "HSV", "HSVWrap": true, "RGBPoints": [0, 1, 0, 0, 1, 1, 0, 1]}"#;
    let middle = read(text).color_at(0.5);
    assert!(
        middle.x > 0.99 && middle.y < 0.01 && (middle.z - 0.5).abs() < 0.01,
        "wrapped midpoint {middle}"
    );
}

#[test]
fn step_color_space_takes_the_upper_points_colour() {
    let tf = read(&rgb_preset("Step", "0, 1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1"));
    assert_eq!(tf.color_at(-1.0), Vec3::X);
    assert_eq!(tf.color_at(0.5), Vec3::Y);
    assert_eq!(tf.color_at(1.5), Vec3::Z);
    assert_eq!(tf.color_at(5.0), Vec3::Z);
}

#[test]
fn unknown_color_space_lists_the_supported_ones() {
    let message = read_error(&rgb_preset("Viridis", "0, 1, 1, 1"), None);
    assert_mentions(
        &message,
        &["Viridis", "RGB", "HSV", "Lab", "Diverging", "Step"],
    );
    let message = read_error(&rgb_preset("Lab/CIEDE2000", "0, 1, 1, 1"), None);
    assert_mentions(&message, &["Lab/CIEDE2000", "not supported"]);
}

#[test]
fn missing_opacity_uses_the_default_ramp_and_says_so() {
    let text = r#"{"Name": "c", "ColorSpace": "RGB", "RGBPoints": [-1, 0, 0, 1, 1, 1, 0, 0]}"#;
    let (tf, warnings) =
        TransferFunction::from_paraview_json_with_report(text, None, Some((10.0, 20.0))).unwrap();
    let default = TransferFunction::default_for_range(10.0, 20.0);
    assert_eq!(tf.opacity_points(), default.opacity_points());
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("\"Points\"") && w.contains("default")),
        "{warnings:?}"
    );
}

#[test]
fn ignored_and_unknown_keys_are_reported() {
    let text = r#"{"Name": "n", "Creator": "me", "ColorSpace": "RGB", "NanColor": [1, 1, 0], "Frobnicate": 3,
        "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "Points": [0, 0, 0.5, 0, 1, 1, 0.5, 0]}"#;
    let (_, warnings) = TransferFunction::from_paraview_json_with_report(text, None, None).unwrap();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(warnings.iter().any(|w| w.contains("NanColor")));
    assert!(warnings.iter().any(|w| w.contains("Frobnicate")));
}

#[test]
fn categorical_presets_are_rejected() {
    let text =
        r#"{"Name": "KAAMS", "IndexedColors": [1, 1, 1, 1, 0, 0], "Annotations": ["0", "zero"]}"#;
    assert_mentions(&read_error(text, None), &["categorical", "KAAMS"]);
}

#[test]
fn rescale_maps_the_colour_range_and_moves_opacity_with_it() {
    let text = r#"{"ColorSpace": "RGB", "RGBPoints": [-1, 0, 0, 1, 1, 1, 0, 0], "Points": [-2, 0, 0.5, 0, 0, 0.5, 0.5, 0, 1, 1, 0.5, 0]}"#;
    let tf = TransferFunction::from_paraview_json(text, None, Some((100.0, 200.0))).unwrap();
    let colours: Vec<f32> = tf.color_points().iter().map(|p| p.scalar).collect();
    let opacities: Vec<f32> = tf.opacity_points().iter().map(|p| p.scalar).collect();
    assert_eq!(colours, [100.0, 200.0]);
    assert_eq!(
        opacities,
        [50.0, 150.0, 200.0],
        "opacity follows the colour range's map"
    );
    let unscaled = TransferFunction::from_paraview_json(text, None, None).unwrap();
    assert_eq!(unscaled.color_points()[0].scalar, -1.0);
    let bad = TransferFunction::from_paraview_json(text, None, Some((2.0, 1.0)));
    assert!(matches!(bad, Err(TfError::BadRange { .. })), "{bad:?}");
}

#[test]
fn written_presets_read_back_exactly() {
    let color = vec![
        ColorPoint {
            scalar: -0.1,
            rgb: Vec3::new(0.1, 1.0 / 3.0, 0.7),
        },
        ColorPoint {
            scalar: 0.3,
            rgb: Vec3::new(0.2, 0.2, 0.2),
        },
        ColorPoint {
            scalar: 0.3,
            rgb: Vec3::new(0.9, 1e-7, 2.5),
        },
        ColorPoint {
            scalar: 12345.678,
            rgb: Vec3::new(0.0, 0.5, 1.0),
        },
    ];
    let opacity = vec![
        OpacityPoint {
            scalar: -3.0e-5,
            alpha: 0.0,
        },
        OpacityPoint {
            scalar: 0.3,
            alpha: 0.123_456_79,
        },
        OpacityPoint {
            scalar: 0.3,
            alpha: 0.9,
        },
        OpacityPoint {
            scalar: 1.0e6,
            alpha: 1.0 / 7.0,
        },
    ];
    let tf = TransferFunction::new(color, opacity).unwrap();
    let text = tf.to_paraview_json("round \"trip\"");
    let (back, warnings) =
        TransferFunction::from_paraview_json_with_report(&text, Some("round \"trip\""), None)
            .unwrap();
    assert_eq!(back, tf, "{text}");
    assert!(warnings.is_empty(), "{warnings:?}");
    let default = TransferFunction::default_for_range(-4.5, 17.25);
    assert_eq!(read(&default.to_paraview_json("d")), default);
}

#[test]
fn malformed_presets_name_the_problem() {
    let full = rgb_preset("RGB", "0, 1, 0, 0, 1, 0, 0, 1");
    let cases: &[(String, &[&str])] = &[
        (
            full[..full.len() - 9].to_string(),
            &["not valid JSON", "EOF"],
        ),
        (
            rgb_preset("RGB", "0, 1, 0, 0, 1, 0, 0"),
            &["\"RGBPoints\"", "7 values", "multiple of 4", "point 1"],
        ),
        (
            rgb_preset("RGB", "0, 1, 0, NaN, 1, 0, 0, 1"),
            &["\"RGBPoints\"[3]", "NaN", "not finite"],
        ),
        (
            rgb_preset("RGB", "0, 1, 0, 0, -Infinity, 0, 0, 1"),
            &["\"RGBPoints\"[4]", "-Infinity"],
        ),
        (
            rgb_preset("RGB", "0, 1, \"0\", 0, 1, 0, 0, 1"),
            &["\"RGBPoints\"[2]", "point 0, g", "string"],
        ),
        (
            rgb_preset("RGB", "0, 1, 0, 0, 1e300, 0, 0, 1"),
            &["\"RGBPoints\"[4]", "single-precision"],
        ),
        (
            rgb_preset("RGB", "1, 1, 0, 0, 0, 0, 0, 1"),
            &["\"RGBPoints\"[4]", "increasing"],
        ),
        (
            rgb_preset("RGB", "0, 1, -0.5, 0"),
            &["\"RGBPoints\"[2]", "negative"],
        ),
        (rgb_preset("RGB", ""), &["\"RGBPoints\"", "empty"]),
        (
            opacity_preset("0, 0, 0.5, 0, 1, 1.5, 0.5, 0"),
            &["\"Points\"[5]", "point 1, alpha", "1.5", "[0, 1]"],
        ),
        (
            opacity_preset("0, 0, 1.5, 0, 1, 1, 0.5, 0"),
            &["\"Points\"[2]", "midpoint"],
        ),
        (
            opacity_preset("0, 0, 0.5, -1, 1, 1, 0.5, 0"),
            &["\"Points\"[3]", "sharpness"],
        ),
        (
            opacity_preset("1, 0, 0.5, 0, 0, 1, 0.5, 0"),
            &["\"Points\"[4]", "increasing"],
        ),
        (opacity_preset(""), &["\"Points\"", "empty"]),
        (
            r#"{"ColorSpace": "RGB", "RGBPoints": {"x": 1}}"#.to_string(),
            &["\"RGBPoints\"", "an object"],
        ),
        (r#"{"ColorSpace": "RGB"}"#.to_string(), &["RGBPoints"]),
        (
            r#"{"ColorSpace": 3, "RGBPoints": [0, 1, 1, 1]}"#.to_string(),
            &["ColorSpace", "not a string"],
        ),
        ("42".to_string(), &["JSON object", "a number"]),
        ("[1]".to_string(), &["preset 0", "not a JSON object"]),
    ];
    for (text, words) in cases {
        assert_mentions(&read_error(text, None), words);
    }
}

#[test]
fn garbage_never_panics() {
    let text = std::fs::read_to_string(asset("samples.json")).unwrap();
    for end in 0..text.len() {
        if text.is_char_boundary(end) {
            let _ = TransferFunction::from_paraview_json_with_report(
                &text[..end],
                Some("Banded Step"),
                Some((0.0, 1.0)),
            );
        }
    }
    for junk in [
        "",
        "null",
        "{",
        "\"NaN\"",
        "[[]]",
        "{\"RGBPoints\": [NaN]}",
        "-",
        "-inf",
        "nan",
        "\u{feff}{}",
        "{\"a\":\"\\\"NaN\"}",
    ] {
        assert!(
            TransferFunction::from_paraview_json(junk, None, None).is_err(),
            "{junk:?}"
        );
    }
}

fn asset(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/presets")
        .join(name)
}

#[test]
fn shipped_presets_parse() {
    let dir = asset("");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let root: serde_json::Value = serde_json::from_str(&text).unwrap();
        let names: Vec<Option<&str>> = match &root {
            serde_json::Value::Array(items) => items.iter().map(|p| p["Name"].as_str()).collect(),
            other => vec![other["Name"].as_str()],
        };
        for name in names {
            let (tf, warnings) =
                TransferFunction::from_paraview_json_with_report(&text, name, Some((0.0, 1.0)))
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            println!(
                "{} {name:?}: {} colour, {} opacity points, warnings {warnings:?}",
                path.display(),
                tf.color_points().len(),
                tf.opacity_points().len()
            );
            count += 1;
        }
    }
    assert!(count >= 4, "only {count} presets in {}", dir.display());
}
