//! The compact form of grey knots for the inner loops: when every knot's
//! attenuation and opacity is one number (always so for a transfer
//! function, whose opacity is scalar), a material is one `Vec4`, the
//! luminance in `xyz` and the one quantity the method needs in `w`
//! (attenuation per world unit, or opacity of a unit distance). A scalar is
//! then classified with a single 4-lane multiply-add.

use glam::{Vec3A, Vec4};

use crate::fastmath::clamp_f32;
use crate::knots::{TfKnots, split_at_knots};

/// Which quantity a grey material carries in `w`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    /// Attenuation per world unit (the linear-attenuation methods).
    Tau,
    /// Opacity of one unit distance (the linear-opacity methods).
    Alpha,
}

/// One knot interval: `start + delta * clamp((s - x0) * inv_width, 0, 1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct GreyInterval {
    start: Vec4,
    delta: Vec4,
    x0: f32,
    inv_width: f32,
}

/// Grey knots: the scalars of [`TfKnots`] and their intervals in 4 lanes.
#[derive(Debug, Clone, PartialEq)]
pub struct GreyKnots {
    scalars: Vec<f32>,
    /// Interval `k` (from -1 to `n - 1`) at index `k + 1`.
    intervals: Vec<GreyInterval>,
}

/// A scalar classified against grey knots.
#[derive(Debug, Clone, Copy, Default)]
pub struct GreySample {
    /// Luminance in `xyz`, the lane quantity in `w`.
    pub material: Vec4,
    /// The scalar, its knot interval's entry in `GreyKnots::intervals`
    /// (the interval plus one, as bits), and the interval's scalar range
    /// `[lo, hi)` (`-inf` before the first knot, `+inf` after the last),
    /// so that the next sample is checked against it without reading the
    /// knots. One vector, so that a sample moves as two vector loads and
    /// stores (the walk copies one per step).
    key: Vec4,
}

impl GreySample {
    #[inline(always)]
    pub fn lum(&self) -> Vec3A {
        Vec3A::from_vec4(self.material)
    }

    #[inline(always)]
    pub fn scalar(&self) -> f32 {
        self.key.x
    }

    /// The knot interval: `-1` before the first knot, `k` from knot `k` on.
    #[inline(always)]
    pub fn interval(&self) -> i32 {
        self.entry() as i32 - 1
    }

    /// The interval's entry in `GreyKnots::intervals`.
    #[inline(always)]
    fn entry(&self) -> usize {
        self.key.y.to_bits() as usize
    }

    #[inline(always)]
    fn lo(&self) -> f32 {
        self.key.z
    }

    #[inline(always)]
    fn hi(&self) -> f32 {
        self.key.w
    }
}

impl PartialEq for GreySample {
    fn eq(&self, other: &Self) -> bool {
        self.material == other.material
            && self.scalar() == other.scalar()
            && self.interval() == other.interval()
            && self.lo() == other.lo()
            && self.hi() == other.hi()
    }
}

impl GreyKnots {
    /// The compact form of `knots`, or `None` when they are not grey.
    pub fn new(knots: &TfKnots, lane: Lane) -> Option<GreyKnots> {
        if !knots.is_grey() {
            return None;
        }
        let pack = |k: usize| {
            let m = knots.materials()[k];
            let w = match lane {
                Lane::Tau => m.tau.x,
                Lane::Alpha => m.alpha.x,
            };
            m.lum.extend(w)
        };
        let scalars = knots.scalars().to_vec();
        let n = scalars.len();
        let constant = |k: usize| GreyInterval {
            start: pack(k),
            delta: Vec4::ZERO,
            x0: scalars[k],
            inv_width: 0.0,
        };
        let mut intervals = vec![constant(0)];
        for k in 0..n - 1 {
            let (x0, x1) = (scalars[k], scalars[k + 1]);
            intervals.push(GreyInterval {
                start: pack(k),
                delta: pack(k + 1) - pack(k),
                x0,
                inv_width: if x1 > x0 { 1.0 / (x1 - x0) } else { 0.0 },
            });
        }
        intervals.push(constant(n - 1));
        Some(GreyKnots { scalars, intervals })
    }

    /// Material at `s` by the linear function of interval `k`, which is
    /// one of a sample's (from -1 to `n - 1`, the `n + 1` entries of
    /// `intervals`; a default sample's -1 too): the index needs no clamp.
    #[inline(always)]
    fn in_interval(&self, k: isize, s: f32) -> Vec4 {
        self.in_entry((k + 1) as usize, s)
    }

    /// [`GreyKnots::in_interval`] by the interval's entry (`k + 1`), which
    /// a sample holds: no index arithmetic in the walk's classification.
    #[inline(always)]
    fn in_entry(&self, entry: usize, s: f32) -> Vec4 {
        let iv = &self.intervals[entry];
        let t = clamp_f32((s - iv.x0) * iv.inv_width, 0.0, 1.0);
        iv.start + iv.delta * t
    }

    /// `s` classified (right-continuous at steps).
    #[inline(always)]
    pub fn sample(&self, s: f32) -> GreySample {
        let k = self.scalars.partition_point(|&x| x <= s) as isize - 1;
        let lo = if k < 0 {
            f32::NEG_INFINITY
        } else {
            self.scalars[k as usize]
        };
        let hi = self
            .scalars
            .get((k + 1) as usize)
            .copied()
            .unwrap_or(f32::INFINITY);
        GreySample {
            material: self.in_interval(k, s),
            key: Vec4::new(s, f32::from_bits((k + 1) as u32), lo, hi),
        }
    }

    /// [`GreyKnots::sample`], trying `near`'s interval first: the same
    /// sample. (A NaN, or `+inf` in the last interval, fails the range
    /// test and is classified from scratch, to the same interval.)
    #[inline(always)]
    pub fn sample_near(&self, s: f32, near: &GreySample) -> GreySample {
        if near.lo() <= s && s < near.hi() {
            GreySample {
                material: self.in_entry(near.entry(), s),
                key: near.key.with_x(s),
            }
        } else {
            self.sample(s)
        }
    }

    /// Calls `piece(front, back, length)` for the pieces of a segment cut
    /// at the knots, front to back (as [`TfKnots::split`]).
    #[inline]
    pub fn split(
        &self,
        front: &GreySample,
        back: &GreySample,
        length: f32,
        piece: impl FnMut(Vec4, Vec4, f32),
    ) -> usize {
        split_at_knots(
            &self.scalars,
            front.scalar(),
            back.scalar(),
            length,
            |k, s| self.in_interval(k, s),
            |s| self.sample(s).material,
            piece,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knots::Material;

    /// Classifying near any earlier sample gives the sample classified
    /// from scratch, to the bit, for scalars in, between, at and beyond
    /// the knots (a step among them), infinities and NaN.
    #[test]
    fn sample_near_is_sample() {
        let grey = |v: f32| Vec3A::splat(v);
        let knots = TfKnots::from_materials(
            [(0.0, 0.1), (0.5, 0.9), (0.5, 0.3), (1.25, 2.0), (2.0, 0.0)]
                .into_iter()
                .map(|(x, v)| {
                    let m = Material {
                        lum: Vec3A::new(v, 1.0 - v, 0.5),
                        tau: grey(v),
                        alpha: grey(v * 0.5),
                    };
                    (x, m)
                })
                .collect(),
        );
        let grey_knots = GreyKnots::new(&knots, Lane::Tau).expect("grey knots");
        let mut values: Vec<f32> = (-20..=60).map(|i| i as f32 * 0.05).collect();
        values.extend([
            0.0,
            0.5,
            1.25,
            2.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ]);
        for &from in &values {
            let near = grey_knots.sample(from);
            for &s in &values {
                let (a, b) = (grey_knots.sample_near(s, &near), grey_knots.sample(s));
                assert_eq!(a.interval(), b.interval(), "{s} near {from}");
                assert_eq!(
                    a.material.to_array().map(f32::to_bits),
                    b.material.to_array().map(f32::to_bits),
                    "{s} near {from}"
                );
            }
        }
    }
}
