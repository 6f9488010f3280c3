//! Renders against per-pixel closed forms: the expected image computed in
//! f64 from each pixel's own ray, the per-channel deviation, and on failure
//! actual / expected / difference EXRs under `target/test-output/<test>/`.

use std::path::{Path, PathBuf};

use glam::Vec3;
use tetray_core::watertight::RayFrame;
use tetray_core::{Camera, Image};

/// RGBA per pixel, row 0 at the top: premultiplied colour and
/// `alpha = 1 - mean(T)`, as the renderer stores them.
pub type Expected = Vec<[f64; 4]>;

/// `pixel(ray)` for the ray of every pixel of a `width x height` image.
pub fn expected_image(
    camera: &Camera,
    width: u32,
    height: u32,
    pixel: impl Fn(&RayFrame) -> [f64; 4],
) -> Expected {
    let rays = camera.pixel_rays(width, height).expect("camera");
    (0..height)
        .flat_map(|py| (0..width).map(move |px| (px, py)))
        .map(|(px, py)| pixel(&rays.ray(px, py)))
        .collect()
}

/// How far a render is from its closed form.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Deviation {
    /// Largest per-channel `|actual - expected|`.
    pub max: f64,
    /// The pixel where it occurs.
    pub worst: (u32, u32),
    /// Pixels with a channel off by more than the tolerance.
    pub over: usize,
}

/// Per-channel deviation of `actual` from `expected` (NaN counts as over).
pub fn deviation(actual: &Image, expected: &[[f64; 4]], tolerance: f64) -> Deviation {
    assert_eq!(actual.rgba.len(), expected.len(), "image sizes differ");
    let mut d = Deviation::default();
    for (i, (a, e)) in actual.rgba.iter().zip(expected).enumerate() {
        let error = (0..4)
            .map(|c| (f64::from(a[c]) - e[c]).abs())
            .fold(
                0.0f64,
                |m, x| if x.is_nan() { f64::INFINITY } else { m.max(x) },
            );
        if error > tolerance {
            d.over += 1;
        }
        if error > d.max {
            d.max = error;
            let w = actual.width as usize;
            d.worst = ((i % w) as u32, (i / w) as u32);
        }
    }
    d
}

/// Panics unless every channel of every pixel is within `tolerance` of the
/// closed form, after writing the three images of `case`; returns the
/// largest deviation.
pub fn assert_matches(
    test: &str,
    case: &str,
    actual: &Image,
    expected: &[[f64; 4]],
    tolerance: f64,
) -> f64 {
    let d = deviation(actual, expected, tolerance);
    if d.over > 0 {
        let folder = write_images(test, case, actual, expected);
        let (x, y) = d.worst;
        let i = y as usize * actual.width as usize + x as usize;
        panic!(
            "{test} / {case}: {} pixels off by more than {tolerance:e}; worst {:e} at ({x}, {y}): \
             actual {:?}, expected {:?}; images in {}",
            d.over,
            d.max,
            actual.rgba[i],
            expected[i],
            folder.display()
        );
    }
    d.max
}

/// Writes `<case>-actual.exr`, `-expected.exr` and `-difference.exr`
/// (absolute, per channel) and returns their folder.
pub fn write_images(test: &str, case: &str, actual: &Image, expected: &[[f64; 4]]) -> PathBuf {
    // The workspace's target folder: crates/raycast/../../target.
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).ancestors().nth(2);
    let folder = workspace
        .expect("the crate lies two folders below the workspace")
        .join("target/test-output")
        .join(test);
    std::fs::create_dir_all(&folder).expect("create the test output folder");
    let as_image = |rgba: Vec<[f32; 4]>| Image::from_pixels(actual.width, actual.height, rgba);
    let want = as_image(expected.iter().map(|p| p.map(|v| v as f32)).collect()).unwrap();
    let diff = actual
        .rgba
        .iter()
        .zip(expected)
        .map(|(a, e)| [0, 1, 2, 3].map(|c| (f64::from(a[c]) - e[c]).abs() as f32))
        .collect();
    let case = case.replace(|c: char| !c.is_ascii_alphanumeric() && c != '-', "_");
    for (name, image) in [
        ("actual", actual),
        ("expected", &want),
        ("difference", &as_image(diff).unwrap()),
    ] {
        image
            .write_exr(&folder.join(format!("{case}-{name}.exr")))
            .expect("write a test image");
    }
    eprintln!("{test} / {case}: images written to {}", folder.display());
    folder
}

/// Perspective and orthographic views of the bounds from several angles,
/// framed as VTK's ResetCamera does, each with a name for file names.
pub fn views(lo: Vec3, hi: Vec3, angles: &[(f32, f32)]) -> Vec<(String, Camera)> {
    let mut cameras = Vec::new();
    for &(azimuth, elevation) in angles {
        for ortho in [false, true] {
            let mut c = Camera::reset_to_bounds(lo, hi).unwrap();
            c.azimuth(azimuth).unwrap();
            c.elevation(elevation).unwrap();
            c.orthogonalize_view_up().unwrap();
            if ortho {
                c.parallel_scale = Some(0.5 * (hi - lo).length() * 1.1);
            }
            let kind = if ortho { "ortho" } else { "persp" };
            cameras.push((format!("{kind}-az{azimuth}-el{elevation}"), c));
        }
    }
    cameras
}

/// Largest deviation per method, printed at the end of a test (run with
/// `--nocapture` to see the measured errors).
#[derive(Default)]
pub struct Worst(Vec<(String, f64)>);

impl Worst {
    pub fn record(&mut self, name: &str, error: f64) {
        match self.0.iter_mut().find(|(n, _)| n == name) {
            Some((_, e)) => *e = e.max(error),
            None => self.0.push((name.to_string(), error)),
        }
    }

    pub fn print(&self, test: &str) {
        for (name, error) in &self.0 {
            eprintln!("{test}: {name}: max error {error:.2e}");
        }
    }
}
