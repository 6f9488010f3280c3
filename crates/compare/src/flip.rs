//! A FLIP-like perceptual difference (after Andersson et al., "FLIP: A
//! Difference Evaluator for Alternating Images", 2020), from the paper's
//! description, per pixel in [0, 1]:
//!
//! - colour: both images (composited over black, their values displayed
//!   as sRGB) go to the opponent space YCxCz, each channel is blurred by a
//!   contrast-sensitivity kernel (sums of Gaussians, in degrees of visual
//!   angle at `pixels_per_degree`), back to CIELAB with the Hunt
//!   adjustment (chroma scaled by 0.01 L), and the HyAB distance, raised to
//!   0.7, is compressed so the distance from green to blue is 1 (95% of
//!   the range for the first 40% of it);
//! - features: edges (first derivative of a Gaussian) and points (second
//!   derivative) of the achromatic channel, the larger difference of their
//!   magnitudes, square-rooted;
//! - the error is colour^(1 - feature): a difference on an edge counts more.
//!
//! Simplifications, against the paper: the kernels are truncated at three
//! widths; the feature filters use one width for both detectors.

use rayon::prelude::*;

use tetray_core::Image;

use crate::CompareError;
use crate::metrics::same_size;

/// FLIP's default viewing: a 0.7 m wide 4K display seen from 0.7 m.
pub const PIXELS_PER_DEGREE: f32 = 67.0;

const WHITE: [f32; 3] = [0.950_456, 1.0, 1.088_754];

/// The per-pixel FLIP-like error of `test` against `reference`.
pub fn flip(
    test: &Image,
    reference: &Image,
    pixels_per_degree: f32,
) -> Result<Vec<f32>, CompareError> {
    same_size(test, reference)?;
    let (w, h) = (test.width as usize, test.height as usize);
    let ycxcz = |image: &Image| -> [Vec<f32>; 3] {
        let pixels: Vec<[f32; 3]> = image
            .rgba
            .par_iter()
            .map(|p| to_ycxcz(displayed(p)))
            .collect();
        std::array::from_fn(|c| pixels.iter().map(|p| p[c]).collect())
    };
    let (t, r) = (ycxcz(test), ycxcz(reference));
    let kernels = csf_kernels(pixels_per_degree);
    let blur = |channels: &[Vec<f32>; 3]| -> [Vec<f32>; 3] {
        std::array::from_fn(|c| convolve(&channels[c], w, h, &kernels[c], &kernels[c]))
    };
    let (tb, rb) = (blur(&t), blur(&r));
    let max_distance = hyab(
        hunt(lab(linear_to_xyz([0.0, 1.0, 0.0]))),
        hunt(lab(linear_to_xyz([0.0, 0.0, 1.0]))),
    )
    .powf(0.7);
    let colour: Vec<f32> = (0..w * h)
        .into_par_iter()
        .map(|i| {
            let lab_of = |b: &[Vec<f32>; 3]| {
                let rgb = xyz_to_linear(from_ycxcz([b[0][i], b[1][i], b[2][i]]))
                    .map(|v| v.clamp(0.0, 1.0));
                hunt(lab(linear_to_xyz(rgb)))
            };
            compress(hyab(lab_of(&tb), lab_of(&rb)).powf(0.7), max_distance)
        })
        .collect();
    // Features on the achromatic channel, normalized to [0, 1].
    let sigma = 0.5 * 0.082 * pixels_per_degree;
    let (gauss, first, second) = feature_kernels(sigma);
    let grey = |ch: &Vec<f32>| ch.iter().map(|&y| (y + 16.0) / 116.0).collect::<Vec<f32>>();
    let features = |y: &Vec<f32>| {
        let ex = convolve(y, w, h, &first, &gauss);
        let ey = convolve(y, w, h, &gauss, &first);
        let px = convolve(y, w, h, &second, &gauss);
        let py = convolve(y, w, h, &gauss, &second);
        let edge: Vec<f32> = ex.iter().zip(&ey).map(|(a, b)| a.hypot(*b)).collect();
        let point: Vec<f32> = px.iter().zip(&py).map(|(a, b)| a.hypot(*b)).collect();
        (edge, point)
    };
    let (te, tp) = features(&grey(&t[0]));
    let (re, rp) = features(&grey(&r[0]));
    Ok((0..w * h)
        .map(|i| {
            let difference = (te[i] - re[i]).abs().max((tp[i] - rp[i]).abs());
            let feature = (difference / std::f32::consts::SQRT_2)
                .clamp(0.0, 1.0)
                .sqrt();
            colour[i].powf(1.0 - feature)
        })
        .collect())
}

/// The pixel as displayed over black: its value read as sRGB, linearized.
fn displayed(p: &[f32; 4]) -> [f32; 3] {
    std::array::from_fn(|c| {
        let v = p[c].clamp(0.0, 1.0);
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    })
}

fn linear_to_xyz(c: [f32; 3]) -> [f32; 3] {
    [
        0.412_391 * c[0] + 0.357_584 * c[1] + 0.180_481 * c[2],
        0.212_639 * c[0] + 0.715_169 * c[1] + 0.072_192 * c[2],
        0.019_331 * c[0] + 0.119_195 * c[1] + 0.950_532 * c[2],
    ]
}

fn xyz_to_linear(c: [f32; 3]) -> [f32; 3] {
    [
        3.240_97 * c[0] - 1.537_383 * c[1] - 0.498_611 * c[2],
        -0.969_244 * c[0] + 1.875_968 * c[1] + 0.041_555 * c[2],
        0.055_630 * c[0] - 0.203_977 * c[1] + 1.056_972 * c[2],
    ]
}

fn to_ycxcz(rgb: [f32; 3]) -> [f32; 3] {
    let [x, y, z] = linear_to_xyz(rgb);
    let (x, y, z) = (x / WHITE[0], y / WHITE[1], z / WHITE[2]);
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

fn from_ycxcz(c: [f32; 3]) -> [f32; 3] {
    let y = (c[0] + 16.0) / 116.0;
    let x = y + c[1] / 500.0;
    let z = y - c[2] / 200.0;
    [x * WHITE[0], y * WHITE[1], z * WHITE[2]]
}

fn lab(xyz: [f32; 3]) -> [f32; 3] {
    let f = |t: f32| {
        let delta = 6.0f32 / 29.0;
        if t > delta * delta * delta {
            t.cbrt()
        } else {
            t / (3.0 * delta * delta) + 4.0 / 29.0
        }
    };
    let [fx, fy, fz] = [
        f(xyz[0] / WHITE[0]),
        f(xyz[1] / WHITE[1]),
        f(xyz[2] / WHITE[2]),
    ];
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

fn hunt(lab: [f32; 3]) -> [f32; 3] {
    [lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]]
}

fn hyab(a: [f32; 3], b: [f32; 3]) -> f32 {
    (a[0] - b[0]).abs() + (a[1] - b[1]).hypot(a[2] - b[2])
}

/// FLIP's compression of the colour distance to [0, 1].
fn compress(distance: f32, max: f32) -> f32 {
    let (pc, pt) = (0.4, 0.95);
    if distance < pc * max {
        pt / (pc * max) * distance
    } else {
        (pt + (distance - pc * max) / (max - pc * max) * (1.0 - pt)).min(1.0)
    }
}

/// The contrast-sensitivity kernels of Y, Cx, Cz: a1 sqrt(pi / b1)
/// exp(-pi^2 x^2 / b1) + a2 (likewise), x in degrees, normalized.
fn csf_kernels(ppd: f32) -> [Vec<f32>; 3] {
    let params: [[f32; 4]; 3] = [
        [1.0, 0.0047, 0.0, 1e-5],
        [1.0, 0.0053, 0.0, 1e-5],
        [34.1, 0.04, 13.5, 0.025],
    ];
    params.map(|[a1, b1, a2, b2]| {
        let widest = b1.max(b2);
        let radius =
            (3.0 * (widest / (2.0 * std::f32::consts::PI.powi(2))).sqrt() * ppd).ceil() as i32;
        let pi = std::f32::consts::PI;
        let g = |x: f32, a: f32, b: f32| a * (pi / b).sqrt() * (-pi * pi * x * x / b).exp();
        normalized((-radius..=radius).map(|i| {
            let x = i as f32 / ppd;
            g(x, a1, b1) + g(x, a2, b2)
        }))
    })
}

/// A Gaussian and its first and second derivatives (each derivative
/// normalized so its positive weights sum to 1).
fn feature_kernels(sigma: f32) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
    let radius = (3.0 * sigma).ceil() as i32;
    let xs: Vec<f32> = (-radius..=radius).map(|i| i as f32).collect();
    let g: Vec<f32> = xs
        .iter()
        .map(|x| (-x * x / (2.0 * sigma * sigma)).exp())
        .collect();
    let first: Vec<f32> = xs.iter().zip(&g).map(|(x, g)| -x * g).collect();
    let second: Vec<f32> = xs
        .iter()
        .zip(&g)
        .map(|(x, g)| (x * x / (sigma * sigma) - 1.0) * g)
        .collect();
    let positive = |k: &[f32]| k.iter().filter(|&&v| v > 0.0).sum::<f32>();
    let (p1, p2) = (positive(&first), positive(&second));
    let mean2 = second.iter().sum::<f32>() / second.len() as f32;
    let second: Vec<f32> = second.iter().map(|v| (v - mean2) / p2).collect();
    (
        normalized(g.into_iter()),
        first.iter().map(|v| v / p1).collect(),
        second,
    )
}

fn normalized(values: impl Iterator<Item = f32>) -> Vec<f32> {
    let v: Vec<f32> = values.collect();
    let sum: f32 = v.iter().sum();
    v.iter().map(|x| x / sum).collect()
}

/// Separable convolution (`along_x`, then `along_y`), edges clamped.
fn convolve(data: &[f32], w: usize, h: usize, along_x: &[f32], along_y: &[f32]) -> Vec<f32> {
    let pass = |src: &[f32], kernel: &[f32], horizontal: bool| -> Vec<f32> {
        let r = (kernel.len() / 2) as isize;
        (0..w * h)
            .into_par_iter()
            .map(|i| {
                let (x, y) = ((i % w) as isize, (i / w) as isize);
                kernel
                    .iter()
                    .enumerate()
                    .map(|(k, weight)| {
                        let d = k as isize - r;
                        let (sx, sy) = if horizontal { (x + d, y) } else { (x, y + d) };
                        let (sx, sy) = (sx.clamp(0, w as isize - 1), sy.clamp(0, h as isize - 1));
                        weight * src[sy as usize * w + sx as usize]
                    })
                    .sum()
            })
            .collect()
    };
    pass(&pass(data, along_x, true), along_y, false)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(level: f32) -> Image {
        let pixels = (0..32 * 32)
            .map(|i| {
                let (x, y) = (i % 32, i / 32);
                let v = if (8..24).contains(&x) && (8..24).contains(&y) {
                    level
                } else {
                    0.1
                };
                [v, v * 0.5, v * 0.25, 1.0]
            })
            .collect();
        Image::from_pixels(32, 32, pixels).unwrap()
    }

    #[test]
    fn identical_images_have_no_error_and_larger_differences_more() {
        let reference = square(0.8);
        let same = flip(&reference, &reference, PIXELS_PER_DEGREE).unwrap();
        assert!(
            same.iter().all(|&e| e.abs() < 1e-5),
            "{:?}",
            same.iter().cloned().fold(0.0, f32::max)
        );
        let mean = |e: Vec<f32>| e.iter().sum::<f32>() / e.len() as f32;
        let small = mean(flip(&square(0.75), &reference, PIXELS_PER_DEGREE).unwrap());
        let large = mean(flip(&square(0.3), &reference, PIXELS_PER_DEGREE).unwrap());
        assert!(
            0.0 < small && small < large && large <= 1.0,
            "{small} {large}"
        );
        // Black against white is (nearly) the largest error there is.
        let white = Image::from_pixels(8, 8, vec![[1.0; 4]; 64]).unwrap();
        let black = Image::from_pixels(8, 8, vec![[0.0, 0.0, 0.0, 1.0]; 64]).unwrap();
        let e = flip(&black, &white, PIXELS_PER_DEGREE).unwrap();
        assert!(e.iter().all(|&v| v > 0.9), "{}", e[0]);
    }
}
