//! Full pre-integration (Roettger, Kraus and Ertl; Engel et al.; the
//! dissertation's section 3.2.5): the light of a segment of one fixed length
//! `D0` for every pair (s_front, s_back) of a scalar grid, computed for one
//! transfer function, looked up bilinearly and corrected for other lengths
//! with the opacity and colour correction of Schulze et al. (2003):
//! `T' = T^(D / D0)` and `C' = C (1 - T') / (1 - T)`.

use std::time::{Duration, Instant};

use glam::Vec3A;
use rayon::prelude::*;

use crate::IntegrateError;
use crate::exact::exact_weights;
use crate::knots::{Piece, TfKnots};
use crate::segment::{SegmentLight, light_from_weights};

pub const PREINTEGRATION_MIN: usize = 2;
pub const PREINTEGRATION_MAX: usize = 4096;

/// The pre-integrated light of segments of length `length` between every
/// pair of `size` scalars evenly spread over `[lo, hi]`.
#[derive(Debug, Clone, PartialEq)]
pub struct PreintegrationTable {
    size: usize,
    lo: f32,
    hi: f32,
    length: f32,
    /// `[i_front * size + i_back]`.
    emitted: Vec<Vec3A>,
    transmittance: Vec<Vec3A>,
    build_time: Duration,
}

impl PreintegrationTable {
    /// Integrates every entry exactly (eq. 3.28, cut at the knots).
    pub fn build(
        knots: &TfKnots,
        (lo, hi): (f32, f32),
        size: usize,
        length: f32,
    ) -> Result<PreintegrationTable, IntegrateError> {
        let start = Instant::now();
        if !(PREINTEGRATION_MIN..=PREINTEGRATION_MAX).contains(&size) {
            return Err(IntegrateError::PreintegrationTableSize {
                size,
                min: PREINTEGRATION_MIN,
                max: PREINTEGRATION_MAX,
            });
        }
        if !(length.is_finite() && length > 0.0) {
            return Err(IntegrateError::PreintegrationLength(length));
        }
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(IntegrateError::ScalarRange { lo, hi });
        }
        let scalar = |i: usize| lo + (hi - lo) * (i as f32 / (size - 1) as f32);
        let entries: Vec<SegmentLight> = (0..size * size)
            .into_par_iter()
            .map(|index| {
                let (front, back) = (scalar(index / size), scalar(index % size));
                let mut light = SegmentLight::CLEAR;
                knots.split(front, back, length, |p: &Piece| {
                    let d = p.length;
                    light = light.then(light_from_weights(
                        p.back.lum,
                        p.front.lum,
                        p.back.tau * d,
                        p.front.tau * d,
                        exact_weights,
                    ));
                });
                light
            })
            .collect();
        Ok(PreintegrationTable {
            size,
            lo,
            hi,
            length,
            emitted: entries.iter().map(|l| l.emitted).collect(),
            transmittance: entries.iter().map(|l| l.transmittance).collect(),
            build_time: start.elapsed(),
        })
    }

    pub fn size(&self) -> usize {
        self.size
    }

    /// The scalar range of the table; scalars outside it are clamped.
    pub fn scalar_range(&self) -> (f32, f32) {
        (self.lo, self.hi)
    }

    /// The segment length `D0` the table holds.
    pub fn length(&self) -> f32 {
        self.length
    }

    /// The entries at the table's length, `[i_front * size + i_back]`:
    /// emitted light and transmittance.
    pub fn entries(&self) -> (&[Vec3A], &[Vec3A]) {
        (&self.emitted, &self.transmittance)
    }

    /// How long [`PreintegrationTable::build`] took.
    pub fn build_time(&self) -> Duration {
        self.build_time
    }

    /// The light of a segment of `length` from `s_front` to `s_back`.
    pub fn lookup(&self, s_front: f32, s_back: f32, length: f32) -> SegmentLight {
        let n = self.size;
        let scale = if self.hi > self.lo {
            (n - 1) as f32 / (self.hi - self.lo)
        } else {
            0.0
        };
        let split = |s: f32| {
            let x = ((s - self.lo) * scale).clamp(0.0, (n - 1) as f32);
            let i = (x as usize).min(n - 2);
            (i, x - i as f32)
        };
        let (i_f, t_f) = split(s_front);
        let (i_b, t_b) = split(s_back);
        let bilinear = |v: &[Vec3A]| {
            let r0 = i_f * n + i_b;
            let r1 = r0 + n;
            let near = v[r0].lerp(v[r0 + 1], t_b);
            let far = v[r1].lerp(v[r1 + 1], t_b);
            near.lerp(far, t_f)
        };
        let emitted = bilinear(&self.emitted);
        let transmittance = bilinear(&self.transmittance);
        correct_length(emitted, transmittance, length / self.length)
    }
}

/// Schulze's correction of a table entry for a segment `ratio` times the
/// table's length: opacity by `T^ratio`, colour by the change of opacity.
fn correct_length(emitted: Vec3A, transmittance: Vec3A, ratio: f32) -> SegmentLight {
    if ratio == 1.0 {
        return SegmentLight {
            emitted,
            transmittance,
        };
    }
    let mut out = SegmentLight::CLEAR;
    for c in 0..3 {
        let t = transmittance[c].clamp(0.0, 1.0);
        let t_new = t.powf(ratio);
        let alpha = 1.0 - t;
        out.transmittance[c] = t_new;
        out.emitted[c] = if alpha > 1e-6 {
            emitted[c] * (1.0 - t_new) / alpha
        } else {
            emitted[c] * ratio
        };
    }
    out
}
