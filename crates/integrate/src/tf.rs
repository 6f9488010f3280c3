//! Transfer functions: piecewise-linear luminance (RGB) and opacity over the
//! scalar, constant beyond their end points (as in ParaView / VTK).

use glam::Vec3;

/// A luminance control point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColorPoint {
    pub scalar: f32,
    pub rgb: Vec3,
}

/// An opacity control point: `alpha` is the opacity of one unit distance
/// of material with this scalar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpacityPoint {
    pub scalar: f32,
    pub alpha: f32,
}

/// Why a transfer function is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TfError {
    #[error("the transfer function has no colour points")]
    NoColorPoints,
    #[error("the transfer function has no opacity points")]
    NoOpacityPoints,
    #[error("{what} point {index} has a non-finite value (scalar {scalar})")]
    NonFinite {
        what: &'static str,
        index: usize,
        scalar: f32,
    },
    #[error(
        "{what} points are not in increasing scalar order at point {index} ({previous} then {scalar})"
    )]
    Unsorted {
        what: &'static str,
        index: usize,
        previous: f32,
        scalar: f32,
    },
    #[error("{what} point {index}: more than two points at scalar {scalar} (two make a step)")]
    TooManyAtScalar {
        what: &'static str,
        index: usize,
        scalar: f32,
    },
    #[error("opacity point {index} has opacity {alpha}, outside [0, 1]")]
    OpacityRange { index: usize, alpha: f32 },
    #[error("colour point {index} has a negative luminance {rgb:?}")]
    NegativeColor { index: usize, rgb: [f32; 3] },
    #[error("cannot rescale to the range [{lo}, {hi}]: it must be finite with lo <= hi")]
    BadRange { lo: f32, hi: f32 },
    #[error("{0}")]
    Preset(String),
}

/// Piecewise-linear luminance and opacity over the scalar. Two points at the
/// same scalar make a step; beyond the first and last point the function is
/// constant.
#[derive(Debug, Clone, PartialEq)]
pub struct TransferFunction {
    color: Vec<ColorPoint>,
    opacity: Vec<OpacityPoint>,
}

impl TransferFunction {
    /// Validates and builds a transfer function.
    pub fn new(color: Vec<ColorPoint>, opacity: Vec<OpacityPoint>) -> Result<Self, TfError> {
        if color.is_empty() {
            return Err(TfError::NoColorPoints);
        }
        if opacity.is_empty() {
            return Err(TfError::NoOpacityPoints);
        }
        for (index, p) in color.iter().enumerate() {
            if !p.scalar.is_finite() || !p.rgb.is_finite() {
                return Err(TfError::NonFinite {
                    what: "colour",
                    index,
                    scalar: p.scalar,
                });
            }
            if p.rgb.min_element() < 0.0 {
                return Err(TfError::NegativeColor {
                    index,
                    rgb: p.rgb.to_array(),
                });
            }
        }
        for (index, p) in opacity.iter().enumerate() {
            if !p.scalar.is_finite() || !p.alpha.is_finite() {
                return Err(TfError::NonFinite {
                    what: "opacity",
                    index,
                    scalar: p.scalar,
                });
            }
            if !(0.0..=1.0).contains(&p.alpha) {
                return Err(TfError::OpacityRange {
                    index,
                    alpha: p.alpha,
                });
            }
        }
        check_order(
            "colour",
            &color.iter().map(|p| p.scalar).collect::<Vec<_>>(),
        )?;
        check_order(
            "opacity",
            &opacity.iter().map(|p| p.scalar).collect::<Vec<_>>(),
        )?;
        Ok(TransferFunction { color, opacity })
    }

    pub fn color_points(&self) -> &[ColorPoint] {
        &self.color
    }

    pub fn opacity_points(&self) -> &[OpacityPoint] {
        &self.opacity
    }

    /// Luminance at `s` (right-continuous at steps).
    pub fn color_at(&self, s: f32) -> Vec3 {
        let (i, t) = locate(self.color.len(), |k| self.color[k].scalar, s);
        match t {
            None => self.color[i].rgb,
            Some(t) => self.color[i].rgb.lerp(self.color[i + 1].rgb, t),
        }
    }

    /// Opacity at `s` (right-continuous at steps).
    pub fn opacity_at(&self, s: f32) -> f32 {
        let (i, t) = locate(self.opacity.len(), |k| self.opacity[k].scalar, s);
        match t {
            None => self.opacity[i].alpha,
            Some(t) => {
                self.opacity[i].alpha + (self.opacity[i + 1].alpha - self.opacity[i].alpha) * t
            }
        }
    }

    /// Smallest and largest control-point scalar of both functions.
    pub fn scalar_range(&self) -> (f32, f32) {
        let scalars = self
            .color
            .iter()
            .map(|p| p.scalar)
            .chain(self.opacity.iter().map(|p| p.scalar));
        scalars.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s), hi.max(s))
        })
    }

    /// The same function stretched linearly so that its scalar range
    /// becomes `[lo, hi]` (ParaView's "rescale to data range"). A function
    /// defined at a single scalar is moved to `lo`.
    pub fn rescaled(&self, lo: f32, hi: f32) -> Result<TransferFunction, TfError> {
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(TfError::BadRange { lo, hi });
        }
        let (old_lo, old_hi) = self.scalar_range();
        let map = |s: f32| {
            if old_hi > old_lo {
                let t =
                    (f64::from(s) - f64::from(old_lo)) / (f64::from(old_hi) - f64::from(old_lo));
                (f64::from(lo) + t * (f64::from(hi) - f64::from(lo))) as f32
            } else {
                lo
            }
        };
        let color = self
            .color
            .iter()
            .map(|p| ColorPoint {
                scalar: map(p.scalar),
                rgb: p.rgb,
            })
            .collect();
        let opacity = self
            .opacity
            .iter()
            .map(|p| OpacityPoint {
                scalar: map(p.scalar),
                alpha: p.alpha,
            })
            .collect();
        TransferFunction::new(color, opacity)
    }

    /// The default transfer function over `[lo, hi]`, what ParaView shows
    /// a new volume with: a blue-white-red diverging ramp (sampled from
    /// Moreland's cool-to-warm map) and an opacity rising linearly from 0
    /// at `lo` to 1 at `hi`.
    pub fn default_for_range(lo: f32, hi: f32) -> TransferFunction {
        let (lo, hi) = if lo.is_finite() && hi.is_finite() && lo < hi {
            (lo, hi)
        } else if lo.is_finite() {
            (lo, lo + 1.0)
        } else {
            (0.0, 1.0)
        };
        let at = |t: f32| lo + (hi - lo) * t;
        let ramp = [
            (0.0, [0.230, 0.299, 0.754]),
            (0.25, [0.552, 0.690, 0.996]),
            (0.5, [0.865, 0.865, 0.865]),
            (0.75, [0.958, 0.604, 0.482]),
            (1.0, [0.706, 0.016, 0.150]),
        ];
        let color = ramp
            .iter()
            .map(|&(t, rgb)| ColorPoint {
                scalar: at(t),
                rgb: Vec3::from_array(rgb),
            })
            .collect();
        let opacity = [(0.0, 0.0), (1.0, 1.0)]
            .iter()
            .map(|&(t, alpha)| OpacityPoint {
                scalar: at(t),
                alpha,
            })
            .collect();
        TransferFunction::new(color, opacity).expect("the default transfer function is valid")
    }
}

/// Nondecreasing scalars with at most two at any one value.
fn check_order(what: &'static str, xs: &[f32]) -> Result<(), TfError> {
    for index in 1..xs.len() {
        let (previous, scalar) = (xs[index - 1], xs[index]);
        if scalar < previous {
            return Err(TfError::Unsorted {
                what,
                index,
                previous,
                scalar,
            });
        }
        if index >= 2 && xs[index - 2] == scalar {
            return Err(TfError::TooManyAtScalar {
                what,
                index,
                scalar,
            });
        }
    }
    Ok(())
}

/// The interval of the `n` point scalars `x(k)` holding `s`
/// (right-continuous): `(i, None)` when the value is point `i`'s (outside
/// the range), `(i, Some(t))` to interpolate between points `i` and `i + 1`.
fn locate(n: usize, x: impl Fn(usize) -> f32, s: f32) -> (usize, Option<f32>) {
    // Binary search for the first point above s.
    let (mut lo, mut hi) = (0, n);
    while lo < hi {
        let mid = (lo + hi) / 2;
        if x(mid) <= s {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    if lo == 0 {
        return (0, None);
    }
    if lo == n {
        return (n - 1, None);
    }
    let i = lo - 1;
    (i, Some((s - x(i)) / (x(i + 1) - x(i))))
}
