//! EXR and PNG output read back with the image crate.

use std::path::PathBuf;

use glam::Vec3;
use tetray_core::{Image, ImageError};

fn temp_path(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("tetray-raycast-test");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn sample() -> Image {
    let rgba = vec![
        [0.25, 0.5, 0.0, 0.5],
        [0.0, 0.0, 0.0, 0.0],
        [1.5, -0.25, 0.125, 1.0],
        [0.1, 0.2, 0.3, 0.75],
        [0.0, 0.0, 0.0, 1.0],
        [0.5, 0.5, 0.5, 0.5],
    ];
    Image::from_pixels(3, 2, rgba).unwrap()
}

#[test]
fn exr_round_trips_float_rgba_exactly() {
    let image = sample();
    let path = temp_path("round.exr");
    image.write_exr(&path).unwrap();
    let back = image::open(&path).unwrap().into_rgba32f();
    assert_eq!((back.width(), back.height()), (3, 2));
    for (x, y, p) in back.enumerate_pixels() {
        // f32 channels are stored losslessly.
        assert_eq!(p.0, image.pixel(x, y).unwrap(), "pixel ({x}, {y})");
    }
}

#[test]
fn png_composites_over_the_background_and_clamps() {
    let image = sample();
    let path = temp_path("over.png");
    image.write_png(&path, Vec3::new(1.0, 1.0, 0.0)).unwrap();
    let back = image::open(&path).unwrap().into_rgb8();
    assert_eq!((back.width(), back.height()), (3, 2));
    // c + (1 - a) bg, clamped, rounded to 8 bits, no sRGB curve.
    assert_eq!(back.get_pixel(0, 0).0, [191, 255, 0]); // 0.75, 1.0, 0.0
    assert_eq!(back.get_pixel(1, 0).0, [255, 255, 0]); // background only
    assert_eq!(back.get_pixel(2, 0).0, [255, 0, 32]); // 1.5 and -0.25 clamp
    assert_eq!(back.get_pixel(0, 1).0, [89, 115, 77]); // 0.35, 0.45, 0.3
    assert_eq!(back.get_pixel(1, 1).0, [0, 0, 0]);
    assert_eq!(back.get_pixel(2, 1).0, [255, 255, 128]);
}

#[test]
fn write_errors_name_the_path() {
    let path = temp_path("missing-dir").join("nope").join("x.png");
    let err = sample().write_png(&path, Vec3::ZERO).unwrap_err();
    assert!(matches!(err, ImageError::Write { .. }));
    assert!(err.to_string().contains("x.png"), "{err}");
    assert!(matches!(
        Image::from_pixels(2, 2, vec![[0.0; 4]; 3]),
        Err(ImageError::SizeMismatch { .. })
    ));
}

#[test]
fn pixels_composite_over_the_background_as_8_bits() {
    let image =
        Image::from_pixels(2, 1, vec![[0.5, 0.0, 0.0, 0.5], [2.0, 0.0, 0.0, 1.0]]).expect("image");
    let rgb = image.to_rgb8(Vec3::new(0.0, 0.0, 1.0)).expect("rgb");
    assert_eq!(rgb.get_pixel(0, 0).0, [128, 0, 128]);
    assert_eq!(rgb.get_pixel(1, 0).0, [255, 0, 0]);
}
