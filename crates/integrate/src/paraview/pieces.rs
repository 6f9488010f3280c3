//! The linear pieces of a preset: colour intervals in their colour space,
//! opacity intervals with their midpoint and sharpness, each exact where
//! the shape is piecewise linear and otherwise within
//! [`LINEARIZE_TOLERANCE`] of it.

use glam::Vec3;

use crate::colorspace::{self, ColorSpace};
use crate::tf::{ColorPoint, OpacityPoint, TfError};

/// Largest deviation from the curve allowed at the check samples of a
/// linear piece: half the 1e-3 budget, so that the error between the
/// samples stays below 1e-3 too (the tests measure it).
const LINEARIZE_TOLERANCE: f64 = 5e-4;
/// Check samples inside each candidate piece.
const CHECK_SAMPLES: usize = 16;
/// Pieces per interval at most (a bound reached only at a jump).
const MAX_PIECES: usize = 4096;
/// Bisection steps locating the end of each piece.
const SEARCH_STEPS: u32 = 24;
/// VTK renders an opacity sharpness below this as linear and above
/// `1 - SHARPNESS_SNAP` as a step.
const SHARPNESS_SNAP: f64 = 0.01;

/// The affine map from preset scalars to transfer-function scalars.
pub(super) struct ScalarMap {
    offset: f64,
    scale: f64,
    target: f64,
}

impl ScalarMap {
    pub(super) fn new(
        rgb_points: &[[f64; 4]],
        rescale: Option<(f32, f32)>,
    ) -> Result<ScalarMap, TfError> {
        let Some((lo, hi)) = rescale else {
            return Ok(ScalarMap {
                offset: 0.0,
                scale: 1.0,
                target: 0.0,
            });
        };
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(TfError::BadRange { lo, hi });
        }
        let (first, last) = (rgb_points[0][0], rgb_points[rgb_points.len() - 1][0]);
        if last <= first {
            return Err(TfError::Preset(format!(
                "cannot rescale: \"RGBPoints\" span the single scalar {first}"
            )));
        }
        let scale = (f64::from(hi) - f64::from(lo)) / (last - first);
        Ok(ScalarMap {
            offset: first,
            scale,
            target: f64::from(lo),
        })
    }

    fn apply(&self, key: &str, point: usize, x: f64) -> Result<f32, String> {
        let mapped = (self.target + (x - self.offset) * self.scale) as f32;
        if mapped.is_finite() {
            Ok(mapped)
        } else {
            Err(format!(
                "\"{key}\"[{}] (point {point}, x = {x}) maps outside the f32 range",
                4 * point
            ))
        }
    }
}

/// Points of a piecewise-linear function of `N` channels in preset scalars,
/// with the preset point each came from (for messages).
struct Polyline<const N: usize> {
    points: Vec<(usize, f64, [f64; N])>,
}

impl<const N: usize> Polyline<N> {
    fn node(&mut self, point: usize, x: f64, v: [f64; N]) {
        self.points.push((point, x, v));
    }

    /// A point added between nodes; repeats of the previous point are dropped.
    fn generated(&mut self, point: usize, x: f64, v: [f64; N]) {
        if self
            .points
            .last()
            .is_some_and(|&(_, lx, lv)| lx == x && lv == v)
        {
            return;
        }
        self.points.push((point, x, v));
    }

    /// Adds the inner points of the linear pieces approximating `curve`
    /// between `start` and `end`, positions t in [0, 1] along the interval
    /// from `x0` to `x1` that starts at preset point `point`; the end points
    /// themselves are the caller's.
    fn curve(
        &mut self,
        point: usize,
        (x0, x1): (f64, f64),
        start: (f64, [f64; N]),
        end: (f64, [f64; N]),
        curve: &dyn Fn(f64) -> [f64; N],
    ) {
        if end.0 <= start.0 {
            return;
        }
        let mut inner = Vec::new();
        linearize(curve, start, end, &mut inner);
        for (t, v) in inner {
            self.generated(point, x0 + (x1 - x0) * t, v);
        }
    }
}

/// Interior points (t, value) of a piecewise-linear approximation of
/// `curve` between two of its points: greedily, each piece is the longest
/// chord from the previous point whose check samples lie within
/// [`LINEARIZE_TOLERANCE`] of the curve.
fn linearize<const N: usize>(
    curve: &dyn Fn(f64) -> [f64; N],
    (t0, v0): (f64, [f64; N]),
    (t1, v1): (f64, [f64; N]),
    out: &mut Vec<(f64, [f64; N])>,
) {
    let min_length = (t1 - t0) / MAX_PIECES as f64;
    let (mut start, mut v_start) = (t0, v0);
    while chord_error(curve, (start, v_start), (t1, v1)) > LINEARIZE_TOLERANCE {
        // Bisect for the end of the longest acceptable chord; the shortest
        // piece is accepted regardless, which only matters at a jump.
        let (mut good, mut bad) = (start + min_length, t1);
        for _ in 0..SEARCH_STEPS {
            let end = 0.5 * (good + bad);
            if chord_error(curve, (start, v_start), (end, curve(end))) <= LINEARIZE_TOLERANCE {
                good = end;
            } else {
                bad = end;
            }
        }
        let v_good = curve(good);
        out.push((good, v_good));
        (start, v_start) = (good, v_good);
    }
}

/// Largest deviation of the chord from `curve` at the check samples.
fn chord_error<const N: usize>(
    curve: &dyn Fn(f64) -> [f64; N],
    (t0, v0): (f64, [f64; N]),
    (t1, v1): (f64, [f64; N]),
) -> f64 {
    (1..CHECK_SAMPLES)
        .map(|k| {
            let w = k as f64 / CHECK_SAMPLES as f64;
            let v = curve(t0 + (t1 - t0) * w);
            (0..N)
                .map(|c| (v[c] - (v0[c] + (v1[c] - v0[c]) * w)).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// Colour points: RGB intervals as they are, steps as steps, other colour
/// spaces as linear pieces.
pub(super) fn color_points(
    quads: &[[f64; 4]],
    space: ColorSpace,
    map: &ScalarMap,
) -> Result<Vec<ColorPoint>, String> {
    let rgb = |q: &[f64; 4]| [q[1], q[2], q[3]];
    let mut line = Polyline::<3> { points: vec![] };
    line.node(0, quads[0][0], rgb(&quads[0]));
    for (i, pair) in quads.windows(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        if b[0] > a[0] {
            match space {
                ColorSpace::Rgb => {}
                ColorSpace::Step => line.generated(i, a[0], rgb(b)),
                _ => {
                    let f = |t: f64| colorspace::interpolate(space, rgb(a), rgb(b), t);
                    // The diverging map may turn at its white midpoint.
                    let vm = f(0.5);
                    line.curve(i, (a[0], b[0]), (0.0, rgb(a)), (0.5, vm), &f);
                    line.generated(i, 0.5 * (a[0] + b[0]), vm);
                    line.curve(i, (a[0], b[0]), (0.5, vm), (1.0, rgb(b)), &f);
                }
            }
        }
        line.node(i + 1, b[0], rgb(b));
    }
    let points = line
        .points
        .iter()
        .map(|&(point, x, v)| {
            Ok(ColorPoint {
                scalar: map.apply("RGBPoints", point, x)?,
                rgb: Vec3::from_array(v.map(|c| c as f32)),
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok(first_and_last_per_scalar(points, |p| p.scalar))
}

/// Opacity points, with each interval's midpoint and sharpness turned into
/// linear pieces.
pub(super) fn opacity_points(
    quads: &[[f64; 4]],
    map: &ScalarMap,
) -> Result<Vec<OpacityPoint>, String> {
    let mut line = Polyline::<1> { points: vec![] };
    line.node(0, quads[0][0], [quads[0][1]]);
    for (i, pair) in quads.windows(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        let (x, (y0, y1), midpoint, sharpness) = ((a[0], b[0]), (a[1], b[1]), a[2], a[3]);
        let x_mid = a[0] + (b[0] - a[0]) * midpoint;
        let mean = 0.5 * (y0 + y1);
        if b[0] > a[0] {
            if sharpness < SHARPNESS_SNAP {
                // Linear in the remapped position: a kink at the midpoint.
                if midpoint != 0.5 {
                    line.generated(i, x_mid, [mean]);
                }
            } else if sharpness > 1.0 - SHARPNESS_SNAP {
                line.generated(i, x_mid, [y0]);
                line.generated(i, x_mid, [y1]);
            } else {
                let f = |t: f64| [opacity_curve(y0, y1, midpoint, sharpness, t)];
                // Each side of the midpoint is smooth; at a midpoint of 0 or 1
                // the mean is reached by a step at that end.
                line.curve(i, x, (0.0, [y0]), (midpoint, [mean]), &f);
                line.generated(i, x_mid, [mean]);
                line.curve(i, x, (midpoint, [mean]), (1.0, [y1]), &f);
            }
        }
        line.node(i + 1, b[0], [y1]);
    }
    let points = line
        .points
        .iter()
        .map(|&(point, x, [alpha])| {
            Ok(OpacityPoint {
                scalar: map.apply("Points", point, x)?,
                alpha: alpha as f32,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok(first_and_last_per_scalar(points, |p| p.scalar))
}

/// vtkPiecewiseFunction's shape between two points at normalised position
/// `t`: the midpoint moves where the mean value is reached, and sharpness
/// blends from linear to a step through a Hermite curve whose end tangents
/// shrink by (1 - sharpness), evaluated at a position pushed away from the
/// middle towards the ends by a power 1 + 10 sharpness.
fn opacity_curve(y0: f64, y1: f64, midpoint: f64, sharpness: f64, t: f64) -> f64 {
    let u = if t < midpoint {
        0.5 * t / midpoint
    } else if midpoint < 1.0 {
        0.5 + 0.5 * (t - midpoint) / (1.0 - midpoint)
    } else {
        1.0
    };
    let power = 1.0 + 10.0 * sharpness;
    let s = if u < 0.5 {
        0.5 * (2.0 * u).powf(power)
    } else {
        1.0 - 0.5 * (2.0 * (1.0 - u)).powf(power)
    };
    let tangent = (1.0 - sharpness) * (y1 - y0);
    let (s2, s3) = (s * s, s * s * s);
    let value = (2.0 * s3 - 3.0 * s2 + 1.0) * y0
        + (3.0 * s2 - 2.0 * s3) * y1
        + (s3 - 2.0 * s2 + s) * tangent
        + (s3 - s2) * tangent;
    value.clamp(y0.min(y1), y0.max(y1))
}

/// Keeps the first and last of each run of points at one scalar: with
/// right-continuous steps the ones between never show.
fn first_and_last_per_scalar<T: Copy>(points: Vec<T>, scalar: impl Fn(&T) -> f32) -> Vec<T> {
    let mut out: Vec<T> = Vec::with_capacity(points.len());
    for p in points {
        let n = out.len();
        if n >= 2 && scalar(&out[n - 1]) == scalar(&p) && scalar(&out[n - 2]) == scalar(&p) {
            out[n - 1] = p;
        } else {
            out.push(p);
        }
    }
    out
}
