//! The transfer function as the integrators read it: one sorted list of
//! knots holding luminance, attenuation and opacity, linear between knots,
//! and the split of a segment at the knots it crosses (adaptive transfer
//! function sampling, dissertation section 4.3): within a piece everything
//! is linear, so the linear methods are exact on it.

use glam::{Vec3, Vec3A};

use crate::opacity::ALPHA_MAX;
use crate::segment::is_grey;
use crate::tf::TransferFunction;

/// How an opacity becomes an attenuation coefficient.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OpacityMode {
    /// `tau = -ln(1 - alpha) / u`: `alpha` is exactly the opacity of one
    /// unit distance `u` of material (eq. 5.12).
    #[default]
    Exact,
    /// `tau = alpha / u`, as VTK's unstructured-grid integrators do.
    Vtk,
}

/// Material properties at one scalar.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Material {
    /// Luminance (RGB).
    pub lum: Vec3A,
    /// Attenuation per world unit.
    pub tau: Vec3A,
    /// Opacity of one unit distance, at most [`ALPHA_MAX`].
    pub alpha: Vec3A,
}

impl Material {
    const ZERO: Material = Material {
        lum: Vec3A::ZERO,
        tau: Vec3A::ZERO,
        alpha: Vec3A::ZERO,
    };
}

/// A piece of a segment within one knot interval: its material at the
/// front and back ends and its length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub front: Material,
    pub back: Material,
    pub length: f32,
}

/// A scalar classified against the knots: its interval (right-continuous,
/// `-1` below the first knot) and its material, computed once per face a
/// ray crosses and shared by the two segments that meet there.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KnotSample {
    pub scalar: f32,
    pub interval: i32,
    pub material: Material,
}

/// Knots in nondecreasing scalar order (two at one scalar make a step).
#[derive(Debug, Clone, PartialEq)]
pub struct TfKnots {
    scalars: Vec<f32>,
    materials: Vec<Material>,
    /// Interval `k` (from -1 below the first knot to `n - 1` above the
    /// last) at index `k + 1`, in the form the inner loops evaluate.
    intervals: Vec<Interval>,
    /// Every knot's attenuation and opacity equal in all channels.
    grey: bool,
}

/// One knot interval as a linear function of the scalar:
/// `start + delta * clamp((s - x0) * inv_width, 0, 1)` (no division, no
/// branch; the outer intervals have `delta = 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Interval {
    x0: f32,
    inv_width: f32,
    start: Material,
    delta: Material,
}

impl TfKnots {
    /// Merges the colour and opacity points of `tf` into one knot list,
    /// converting opacity to attenuation with unit distance `u`.
    pub fn new(tf: &TransferFunction, unit_distance: f32, mode: OpacityMode) -> TfKnots {
        let mut xs: Vec<f32> = tf
            .color_points()
            .iter()
            .map(|p| p.scalar)
            .chain(tf.opacity_points().iter().map(|p| p.scalar))
            .collect();
        xs.sort_by(f32::total_cmp);
        xs.dedup();
        let mut scalars = Vec::with_capacity(xs.len() + 2);
        let mut materials = Vec::with_capacity(xs.len() + 2);
        for &x in &xs {
            let left = material(tf, x, Side::Left, unit_distance, mode);
            let right = material(tf, x, Side::Right, unit_distance, mode);
            scalars.push(x);
            materials.push(left);
            if right != left {
                scalars.push(x);
                materials.push(right);
            }
        }
        TfKnots::from_parts(scalars, materials)
    }

    fn from_parts(scalars: Vec<f32>, materials: Vec<Material>) -> TfKnots {
        let grey = materials.iter().all(|m| is_grey(m.tau) && is_grey(m.alpha));
        let n = scalars.len();
        let constant = |x0: f32, m: Material| Interval {
            x0,
            inv_width: 0.0,
            start: m,
            delta: Material::ZERO,
        };
        let mut intervals = vec![constant(scalars[0], materials[0])];
        for k in 0..n - 1 {
            let (x0, x1) = (scalars[k], scalars[k + 1]);
            let (m0, m1) = (materials[k], materials[k + 1]);
            intervals.push(Interval {
                x0,
                inv_width: if x1 > x0 { 1.0 / (x1 - x0) } else { 0.0 },
                start: m0,
                delta: Material {
                    lum: m1.lum - m0.lum,
                    tau: m1.tau - m0.tau,
                    alpha: m1.alpha - m0.alpha,
                },
            });
        }
        intervals.push(constant(scalars[n - 1], materials[n - 1]));
        TfKnots {
            scalars,
            materials,
            intervals,
            grey,
        }
    }

    /// Whether every knot's attenuation and opacity is the same in all
    /// channels (always so for a [`TransferFunction`], whose opacity is one
    /// number).
    pub fn is_grey(&self) -> bool {
        self.grey
    }

    /// Knots given directly (each scalar's material). Panics on an empty or
    /// unsorted list: callers build them from validated data.
    pub fn from_materials(knots: Vec<(f32, Material)>) -> TfKnots {
        assert!(!knots.is_empty(), "at least one knot");
        assert!(knots.windows(2).all(|w| w[0].0 <= w[1].0), "sorted knots");
        let (scalars, materials) = knots.into_iter().unzip();
        TfKnots::from_parts(scalars, materials)
    }

    pub fn scalars(&self) -> &[f32] {
        &self.scalars
    }

    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    pub fn len(&self) -> usize {
        self.scalars.len()
    }

    pub fn is_empty(&self) -> bool {
        self.scalars.is_empty()
    }

    /// Material at `s` (right-continuous at steps).
    pub fn at(&self, s: f32) -> Material {
        self.in_interval(self.interval_up(s), s)
    }

    /// `s` classified against the knots.
    #[inline(always)]
    pub fn sample(&self, s: f32) -> KnotSample {
        let k = self.interval_up(s);
        KnotSample {
            scalar: s,
            interval: k as i32,
            material: self.in_interval(k, s),
        }
    }

    /// [`TfKnots::sample`], trying `near`'s interval first: along a ray the
    /// scalar mostly stays within one interval.
    #[inline(always)]
    pub fn sample_near(&self, s: f32, near: &KnotSample) -> KnotSample {
        let k = near.interval as isize;
        let last = self.scalars.len() as isize - 1;
        let above_start = k < 0 || self.scalars[k as usize] <= s;
        let below_end = k >= last || s < self.scalars[(k + 1) as usize];
        if above_start && below_end {
            KnotSample {
                scalar: s,
                interval: near.interval,
                material: self.in_interval(k, s),
            }
        } else {
            self.sample(s)
        }
    }

    /// Like [`TfKnots::split`] for classified end points: one piece with the
    /// samples' own materials when both lie in one interval, otherwise the
    /// full split.
    #[inline]
    pub fn split_samples(
        &self,
        front: &KnotSample,
        back: &KnotSample,
        length: f32,
        mut piece: impl FnMut(&Piece),
    ) -> usize {
        if front.interval == back.interval {
            piece(&Piece {
                front: front.material,
                back: back.material,
                length,
            });
            1
        } else {
            self.split(front.scalar, back.scalar, length, piece)
        }
    }

    /// The interval `k` with `x_k <= s < x_(k+1)`: `-1` below the first
    /// knot, `n - 1` from the last one on.
    #[inline]
    fn interval_up(&self, s: f32) -> isize {
        self.scalars.partition_point(|&x| x <= s) as isize - 1
    }

    /// Material at `s` by the linear function of interval `k`.
    #[inline(always)]
    fn in_interval(&self, k: isize, s: f32) -> Material {
        let index = (k + 1).clamp(0, self.intervals.len() as isize - 1) as usize;
        let iv = &self.intervals[index];
        let t = ((s - iv.x0) * iv.inv_width).clamp(0.0, 1.0);
        Material {
            lum: iv.start.lum + iv.delta.lum * t,
            tau: iv.start.tau + iv.delta.tau * t,
            alpha: iv.start.alpha + iv.delta.alpha * t,
        }
    }

    /// Calls `piece` for each piece of a segment with scalar `s_front` at
    /// its front and `s_back` at its back, cut at every knot between them,
    /// front to back. Returns the number of pieces.
    #[inline]
    pub fn split(
        &self,
        s_front: f32,
        s_back: f32,
        length: f32,
        mut piece: impl FnMut(&Piece),
    ) -> usize {
        split_at_knots(
            &self.scalars,
            s_front,
            s_back,
            length,
            |k, s| self.in_interval(k, s),
            |s| self.at(s),
            |front, back, length| {
                piece(&Piece {
                    front,
                    back,
                    length,
                })
            },
        )
    }
}

/// The split of a segment at the knots `scalars`, for any representation
/// of the material: `eval(k, s)` is the material at `s` by interval `k`'s
/// linear function (`-1` below the first knot), `at(s)` the material at
/// `s`. Calls `piece(front, back, length)` front to back and returns the
/// number of pieces.
#[inline]
pub(crate) fn split_at_knots<M>(
    scalars: &[f32],
    s_front: f32,
    s_back: f32,
    length: f32,
    eval: impl Fn(isize, f32) -> M,
    at: impl Fn(f32) -> M,
    mut piece: impl FnMut(M, M, f32),
) -> usize
where
    M: Copy,
{
    let last = scalars.len() as isize - 1;
    let span = s_back - s_front;
    if span == 0.0 || !span.is_finite() {
        let m = at(s_front);
        piece(m, m, length);
        return 1;
    }
    let per_scalar = length / span.abs();
    let increasing = span > 0.0;
    // The interval holding s_front, entered in the direction of travel:
    // x_k <= s < x_(k+1) going up, x_k < s <= x_(k+1) going down.
    let mut k = if increasing {
        scalars.partition_point(|&x| x <= s_front) as isize - 1
    } else {
        scalars.partition_point(|&x| x < s_front) as isize - 1
    };
    let mut s = s_front;
    let mut count = 0;
    loop {
        // The end of interval k in the direction of travel.
        let (bound, next) = if increasing {
            if k < last {
                (scalars[(k + 1) as usize], k + 1)
            } else {
                (f32::INFINITY, k)
            }
        } else if k >= 0 {
            (scalars[k as usize], k - 1)
        } else {
            (f32::NEG_INFINITY, k)
        };
        let reached = if increasing {
            bound >= s_back
        } else {
            bound <= s_back
        };
        let s_end = if reached { s_back } else { bound };
        let piece_length = if reached && count == 0 {
            length
        } else {
            (s_end - s).abs() * per_scalar
        };
        if piece_length > 0.0 || reached {
            piece(eval(k, s), eval(k, s_end), piece_length);
            count += 1;
        }
        if reached {
            return count;
        }
        s = s_end;
        k = next;
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Side {
    Left,
    Right,
}

/// The material at knot scalar `x`, approached from one side.
fn material(tf: &TransferFunction, x: f32, side: Side, u: f32, mode: OpacityMode) -> Material {
    let color = one_sided(tf.color_points().iter().map(|p| (p.scalar, p.rgb)), x, side);
    let alpha_value = one_sided(
        tf.opacity_points()
            .iter()
            .map(|p| (p.scalar, Vec3::splat(p.alpha))),
        x,
        side,
    );
    let alpha = alpha_value.clamp(Vec3::ZERO, Vec3::splat(ALPHA_MAX));
    let tau = match mode {
        OpacityMode::Exact => Vec3::from_array(alpha.to_array().map(|a| -(-a).ln_1p())) / u,
        OpacityMode::Vtk => alpha / u,
    };
    Material {
        lum: color.into(),
        tau: tau.into(),
        alpha: alpha.into(),
    }
}

/// A piecewise-linear function of points `(scalar, value)` at `x`, taking
/// the left or the right limit at a step.
fn one_sided(points: impl Iterator<Item = (f32, Vec3)> + Clone, x: f32, side: Side) -> Vec3 {
    let pts: Vec<(f32, Vec3)> = points.collect();
    let n = pts.len();
    // Points strictly left of x and at or left of x.
    let below = pts.partition_point(|p| p.0 < x);
    let upto = pts.partition_point(|p| p.0 <= x);
    if upto > below {
        // x is a control point: the first (left) or last (right) at x.
        return if side == Side::Left {
            pts[below].1
        } else {
            pts[upto - 1].1
        };
    }
    if below == 0 {
        return pts[0].1;
    }
    if below == n {
        return pts[n - 1].1;
    }
    let (x0, v0) = pts[below - 1];
    let (x1, v1) = pts[below];
    v0.lerp(v1, (x - x0) / (x1 - x0))
}
