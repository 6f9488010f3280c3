//! The conservative ray / box test used by every traversal of the BVH.
//!
//! The crossing itself is decided by the [`tetray_core::watertight`] predicate on
//! vertices projected into the ray frame; the box test only prunes, so it must
//! never cull a box holding a face the predicate would accept. Two things can
//! make an exact slab test do that: rounding (projection, frame, the slab
//! arithmetic itself) and exact grazing (an axis-aligned ray running along a
//! grid plane touches a box face exactly). Hence boxes are padded and every
//! comparison is inclusive.
//!
//! Padding bound. Let `S` be the largest coordinate magnitude of the boundary
//! plus that of the ray origin, and `eps = 2^-24`. When the predicate accepts
//! a face with distance `t`, the frame point `(0, 0, t)` lies on the face as
//! projected in f32 (its weights are exact-signed f64 edge functions, so `t`
//! is a true convex combination of the vertex distances). Each projected
//! coordinate is within about `8 eps S` of the exact one (difference, 3-term
//! dot product, a frame orthonormal to a few eps), and mapping `(0, 0, t)`
//! back to the world through the nearly orthonormal frame adds a few `eps S`
//! more: the world point `origin + t dir` is within ~`30 eps S` of a point of
//! the face, hence of the face's box (obvhs' split boxes cover their piece of
//! the face to within `eps S`). Computing the slab distances moves each slab
//! plane by at most a few `eps S` more. Padding by `PAD_REL * S` with
//! `PAD_REL = 2^-16 = 128 eps` covers all of this four times over, and costs
//! nothing measurable: cells are far larger than `1e-5` of the scene.

use glam::{Vec3, Vec4};

/// Relative box padding, see the module documentation.
pub(crate) const PAD_REL: f32 = 1.0 / 65536.0;

/// A ray prepared for slab tests against padded boxes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RaySlab {
    /// `origin + pad`: box minima are compared / subtracted against this,
    /// which is the same as lowering every minimum by `pad`.
    origin_plus_pad: [f32; 3],
    /// `origin - pad`, for the maxima.
    origin_minus_pad: [f32; 3],
    /// `1 / dir` per axis; unused where `parallel`.
    inv_dir: [f32; 3],
    /// Axes along which the ray does not move measurably: `1 / dir` is not
    /// finite (zero or subnormal component). A subnormal component moves the
    /// ray by under `1e-38 t`, far below the padding for any `t` at which a
    /// face can be crossed (`|t| <= 2 S`).
    parallel: [bool; 3],
    /// The same quantities in four lanes each, for
    /// [`RaySlab::entry_four`].
    four: Option<SlabFour>,
}

/// A ray that moves along every axis, prepared for one slab of four boxes
/// at once: per axis, the coordinate in every lane.
#[derive(Debug, Clone, Copy)]
struct SlabFour {
    origin_plus_pad: [Vec4; 3],
    origin_minus_pad: [Vec4; 3],
    inv_dir: [Vec4; 3],
}

impl RaySlab {
    /// `scene_abs_max`: the largest coordinate magnitude of any boundary point.
    #[inline(always)]
    pub(crate) fn new(origin: Vec3, dir: Vec3, scene_abs_max: f32) -> Self {
        let pad = PAD_REL * (scene_abs_max + origin.abs().max_element());
        let mut slab = RaySlab {
            origin_plus_pad: (origin + pad).to_array(),
            origin_minus_pad: (origin - pad).to_array(),
            inv_dir: [0.0; 3],
            parallel: [false; 3],
            four: None,
        };
        for axis in 0..3 {
            let inv = 1.0 / dir[axis];
            slab.parallel[axis] = !inv.is_finite();
            slab.inv_dir[axis] = if inv.is_finite() { inv } else { 0.0 };
        }
        if !slab.parallel.contains(&true) {
            slab.four = Some(SlabFour {
                origin_plus_pad: slab.origin_plus_pad.map(Vec4::splat),
                origin_minus_pad: slab.origin_minus_pad.map(Vec4::splat),
                inv_dir: slab.inv_dir.map(Vec4::splat),
            });
        }
        slab
    }

    /// [`RaySlab::entry`] for four boxes, given per axis as four lanes of
    /// minima and maxima: bit `i` of the mask is set where box `i` is
    /// entered within `[t_lo, t_hi]`, and lane `i` of the vector is then
    /// `entry`'s distance for it (the same number, `+0` and `-0` aside).
    /// One vector operation per axis and bound where the ray moves along
    /// all three axes; the per-axis test box by box otherwise.
    #[inline(always)]
    pub(crate) fn entry_four(
        &self,
        min: &[Vec4; 3],
        max: &[Vec4; 3],
        t_lo: f32,
        t_hi: f32,
    ) -> (u32, Vec4) {
        let Some(four) = &self.four else {
            let mut mask = 0;
            let mut near = [0.0; 4];
            for (lane, t) in near.iter_mut().enumerate() {
                let corner = |c: &[Vec4; 3]| [c[0][lane], c[1][lane], c[2][lane]];
                if let Some(entry) = self.entry(corner(min), corner(max), t_lo, t_hi) {
                    mask |= 1 << lane;
                    *t = entry;
                }
            }
            return (mask, Vec4::from_array(near));
        };
        let mut near = Vec4::splat(t_lo);
        let mut far = Vec4::splat(t_hi);
        for axis in 0..3 {
            let t0 = (min[axis] - four.origin_plus_pad[axis]) * four.inv_dir[axis];
            let t1 = (max[axis] - four.origin_minus_pad[axis]) * four.inv_dir[axis];
            // Finite lanes (see `entry`): the lane-wise minimum and maximum
            // pick what `entry`'s comparisons pick, in any order.
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        (near.cmple(far).bitmask(), near)
    }

    /// The distance at which the ray enters the padded box `[min, max]`, if
    /// its stretch inside overlaps `[t_lo, t_hi]`. Inclusive everywhere: a
    /// ray touching the padded box in one point still visits it.
    #[inline(always)]
    pub(crate) fn entry(&self, min: [f32; 3], max: [f32; 3], t_lo: f32, t_hi: f32) -> Option<f32> {
        let mut near = t_lo;
        let mut far = t_hi;
        for axis in 0..3 {
            if self.parallel[axis] {
                // Constant coordinate: inside the padded slab or never.
                if !(min[axis] <= self.origin_plus_pad[axis]
                    && self.origin_minus_pad[axis] <= max[axis])
                {
                    return None;
                }
            } else {
                let t0 = (min[axis] - self.origin_plus_pad[axis]) * self.inv_dir[axis];
                let t1 = (max[axis] - self.origin_minus_pad[axis]) * self.inv_dir[axis];
                // Plain comparisons (one instruction each, unlike f32::min /
                // max): t0 and t1 are finite (finite inverse, finite box and
                // origin), and a NaN query range fails every comparison.
                let (lo, hi) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
                near = if lo > near { lo } else { near };
                far = if hi < far { hi } else { far };
            }
        }
        if near <= far { Some(near) } else { None }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BOX_MIN: [f32; 3] = [0.0, 0.0, 0.0];
    const BOX_MAX: [f32; 3] = [1.0, 1.0, 1.0];

    #[test]
    fn grazing_axis_aligned_rays_visit_the_box() {
        // Rays running exactly along each face plane and each edge line of the
        // unit box, in both directions along each axis.
        for axis in 0..3 {
            for sign in [1.0f32, -1.0] {
                let mut dir = Vec3::ZERO;
                dir[axis] = sign;
                for a in [0.0f32, 1.0] {
                    for b in [0.0f32, 0.5, 1.0] {
                        let mut origin = Vec3::splat(0.0);
                        origin[axis] = -2.0 * sign + 0.5;
                        origin[(axis + 1) % 3] = a;
                        origin[(axis + 2) % 3] = b;
                        let slab = RaySlab::new(origin, dir, 1.0);
                        let entry = slab.entry(BOX_MIN, BOX_MAX, 0.0, f32::INFINITY);
                        assert!(entry.is_some(), "ray {origin} {dir} culled");
                    }
                }
            }
        }
    }

    #[test]
    fn flat_boxes_and_rays_starting_on_a_face_are_visited() {
        // A box of zero thickness in z (a face in a grid plane), hit head-on
        // and along its plane; a ray starting exactly on the box surface.
        let (min, max) = ([0.0, 0.0, 0.5], [1.0, 1.0, 0.5]);
        let head_on = RaySlab::new(Vec3::new(0.5, 0.5, -1.0), Vec3::Z, 1.0);
        assert!(head_on.entry(min, max, 0.0, f32::INFINITY).is_some());
        let in_plane = RaySlab::new(Vec3::new(-1.0, 0.0, 0.5), Vec3::X, 1.0);
        assert!(in_plane.entry(min, max, 0.0, f32::INFINITY).is_some());
        let on_face = RaySlab::new(Vec3::new(0.5, 0.5, 0.5), Vec3::Z, 1.0);
        assert_eq!(
            on_face.entry(min, max, 0.0, 0.0).map(|t| t <= 0.0),
            Some(true)
        );
    }

    /// The four-lane test gives the per-axis test's answer box by box.
    #[test]
    fn four_boxes_at_once_agree_with_the_per_axis_test() {
        let mut state = 0x2545_f491u32;
        let mut unit = || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32 * 2.0 - 1.0
        };
        let mut hits = 0;
        for i in 0..5_000 {
            let origin = Vec3::new(unit(), unit(), unit()) * 3.0;
            let mut dir = Vec3::new(unit(), unit(), unit()) * 1.2 - origin;
            if i % 10 == 0 {
                dir[i / 10 % 3] = 0.0;
            }
            let (mut min, mut max) = ([Vec4::ZERO; 3], [Vec4::ZERO; 3]);
            for lane in 0..4 {
                for axis in 0..3 {
                    let (a, b) = (unit(), unit());
                    min[axis][lane] = a.min(b);
                    max[axis][lane] = a.max(b);
                }
            }
            let t_lo = if i % 3 == 0 {
                f32::NEG_INFINITY
            } else {
                unit()
            };
            let t_hi = if i % 5 == 0 {
                f32::INFINITY
            } else {
                t_lo.max(-1.0) + 4.0 * unit().abs()
            };
            let slab = RaySlab::new(origin, dir, 1.0);
            let (mask, near) = slab.entry_four(&min, &max, t_lo, t_hi);
            for lane in 0..4 {
                let corner = |c: &[Vec4; 3]| [c[0][lane], c[1][lane], c[2][lane]];
                let want = slab.entry(corner(&min), corner(&max), t_lo, t_hi);
                let got = (mask >> lane & 1 == 1).then_some(near[lane]);
                assert_eq!(got, want, "{origin} {dir} lane {lane} [{t_lo}, {t_hi}]");
                hits += usize::from(want.is_some());
            }
        }
        assert!(hits > 1_000 && hits < 19_000, "{hits} boxes hit");
    }

    #[test]
    fn clear_misses_and_out_of_range_distances_are_culled() {
        let slab = RaySlab::new(Vec3::new(-1.0, 2.0, 0.5), Vec3::X, 1.0);
        assert_eq!(slab.entry(BOX_MIN, BOX_MAX, 0.0, f32::INFINITY), None);
        let slab = RaySlab::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 1.0);
        // The box spans t in [1, 2] (padded by 2^-15 here).
        assert_eq!(slab.entry(BOX_MIN, BOX_MAX, 0.0, 0.99), None);
        assert_eq!(slab.entry(BOX_MIN, BOX_MAX, 2.01, 5.0), None);
        assert!(slab.entry(BOX_MIN, BOX_MAX, 0.0, 1.0).is_some());
        assert!(slab.entry(BOX_MIN, BOX_MAX, 2.0, 5.0).is_some());
    }
}
