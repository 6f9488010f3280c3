//! The light of one slab between two slices, and which slabs are empty.
//!
//! - Pre-integrated (Schulze et al., section 2.4): the scalar is linear
//!   across the slab from `s_f` on the front slice to `s_b` on the back one;
//!   the light is looked up (bilinearly) in the full pre-integration table
//!   of `tetray-integrate`, built once for the slab length `D0` (the grid
//!   spacing along the principal axis), and corrected for the slab length
//!   `D` of the view (section 2.2): `T' = T^(D/D0)`, `C' = C (1 - T') / (1 -
//!   T)`. For parallel projection `D` is one number per frame, so the whole
//!   table is corrected once per frame (Lacroute's correction table); for
//!   perspective every ray has its own `D` and the correction is per slab.
//! - Post-classified (the baseline): the scalar sampled on the front slice is
//!   classified and taken as constant over the slab, integrated exactly
//!   (`T = exp(-tau D)`, `C = c (1 - T)`: opacity and colour corrected).
//!
//! Empty slabs: a cell of a slice (its 2 x 2 points) gets a class, nonzero
//! when every value the bilinear interpolation can take in it is in one
//! run of exactly transparent classification: for pre-integration a run of
//! table nodes whose entries are all `T = 1, C = 0` (then every bilinear
//! lookup between them is too), for post-classification a scalar interval
//! of zero attenuation. A slab whose front and back cells share a nonzero
//! class (pre-integrated) or whose front cell has one (post-classified)
//! adds nothing, exactly, and is skipped.

use glam::Vec3A;
use tetray_integrate::{PreintegrationTable, SegmentLight, TfKnots};

/// How slabs are classified.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Classification {
    /// Full pre-integration over `(s_front, s_back)` (Schulze et al.'s method).
    #[default]
    PreIntegrated,
    /// The front sample, classified, constant over the slab (standard
    /// shear-warp; Schulze et al.'s baseline).
    PostClassified,
}

impl Classification {
    pub fn name(self) -> &'static str {
        match self {
            Classification::PreIntegrated => "pre-integrated",
            Classification::PostClassified => "post-classified",
        }
    }

    /// The classification an integration method asks of shear-warp: the
    /// Riemann sum post-classifies (Schulze et al.'s baseline: the front sample
    /// constant over each slab); every other method pre-integrates with the
    /// full table.
    pub fn for_method(method: tetray_integrate::Method) -> Classification {
        if method == tetray_integrate::Method::Riemann {
            Classification::PostClassified
        } else {
            Classification::PreIntegrated
        }
    }
}

/// Everything that depends on the transfer function only.
#[derive(Debug, Clone)]
pub(crate) struct Classifier {
    pub knots: TfKnots,
    pub table: Option<PreintegrationTable>,
    /// Post: scalar intervals of zero attenuation `(lo, hi, hi included)`.
    zero_scalars: Vec<(f32, f32, bool)>,
    /// Pre: runs of node intervals `n0..=n1` (node `n` to `n + 1`) whose
    /// table entries are all exactly clear.
    zero_nodes: Vec<(usize, usize)>,
}

impl Classifier {
    pub fn new(knots: TfKnots, table: Option<PreintegrationTable>) -> Classifier {
        let zero_scalars = zero_intervals(&knots);
        let zero_nodes = table.as_ref().map(clear_node_runs).unwrap_or_default();
        Classifier {
            knots,
            table,
            zero_scalars,
            zero_nodes,
        }
    }

    /// The class of a cell whose bilinear samples lie in `[lo, hi]`: 0 when
    /// it may be visible, else one more than the index of its empty run.
    pub fn class_of(&self, lo: f32, hi: f32) -> u16 {
        let found = match &self.table {
            Some(table) => {
                let (t_lo, t_hi) = table.scalar_range();
                let n = table.size();
                let scale = if t_hi > t_lo {
                    (n - 1) as f32 / (t_hi - t_lo)
                } else {
                    0.0
                };
                // One node of slack each side: f32 bilinear samples may fall
                // an ulp outside the cell's range.
                let node = |s: f32| ((s - t_lo) * scale).clamp(0.0, (n - 2) as f32) as usize;
                let (a, b) = (node(lo).saturating_sub(1), (node(hi) + 1).min(n - 2));
                self.zero_nodes
                    .iter()
                    .position(|&(n0, n1)| n0 <= a && b <= n1)
            }
            None => self
                .zero_scalars
                .iter()
                .position(|&(z0, z1, inc)| z0 <= lo && (hi < z1 || (inc && hi == z1))),
        };
        found.map_or(0, |r| (r + 1).min(u16::MAX as usize) as u16)
    }
}

/// The maximal scalar intervals where the attenuation is zero.
fn zero_intervals(knots: &TfKnots) -> Vec<(f32, f32, bool)> {
    let xs = knots.scalars();
    let ms = knots.materials();
    let zero = |k: usize| ms[k].tau.max_element() == 0.0;
    let mut runs: Vec<(f32, f32, bool)> = Vec::new();
    let mut open: Option<f32> = if zero(0) {
        Some(f32::NEG_INFINITY)
    } else {
        None
    };
    for k in 0..xs.len() {
        match (open, zero(k)) {
            (None, true) => open = Some(xs[k]),
            (Some(lo), false) => {
                let hi = xs[k - 1].max(lo);
                let inc = knots.at(hi).tau.max_element() == 0.0;
                runs.push((lo, hi, inc));
                open = None;
            }
            _ => {}
        }
    }
    if let Some(lo) = open {
        runs.push((lo, f32::INFINITY, true));
    }
    runs
}

/// Runs of node intervals whose four table entries are exactly clear.
fn clear_node_runs(table: &PreintegrationTable) -> Vec<(usize, usize)> {
    let n = table.size();
    let (emitted, transmittance) = table.entries();
    let clear = |a: usize, b: usize| {
        let i = a * n + b;
        transmittance[i] == Vec3A::ONE && emitted[i] == Vec3A::ZERO
    };
    let mut runs = Vec::new();
    let mut start = None;
    for m in 0..n - 1 {
        let ok = clear(m, m) && clear(m, m + 1) && clear(m + 1, m) && clear(m + 1, m + 1);
        match (start, ok) {
            (None, true) => start = Some(m),
            (Some(s), false) => {
                runs.push((s, m - 1));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        runs.push((s, n - 2));
    }
    // A run is trusted only if its whole block of entries is clear (it is
    // when the attenuation is zero across it, as the runs come from the
    // transfer function's zero intervals).
    runs.retain(|&(a, b)| (a..=b + 1).all(|i| (a..=b + 1).all(|j| clear(i, j))));
    runs
}

/// Slab light for one frame.
#[derive(Debug, Clone)]
pub(crate) enum SlabLight<'a> {
    /// Parallel projection: the table corrected for this frame's slab
    /// length, `[i_front * size + i_back]`.
    Corrected {
        size: usize,
        lo: f32,
        scale: f32,
        emitted: Vec<Vec3A>,
        transmittance: Vec<Vec3A>,
    },
    /// Perspective: the table, corrected per slab.
    PerSlab(&'a PreintegrationTable),
    Post(&'a TfKnots),
}

impl<'a> SlabLight<'a> {
    /// `length`: the slab length of a parallel projection (ignored for
    /// perspective, which passes it per slab).
    pub fn new(classifier: &'a Classifier, parallel_length: Option<f32>) -> SlabLight<'a> {
        match (&classifier.table, parallel_length) {
            (None, _) => SlabLight::Post(&classifier.knots),
            (Some(t), None) => SlabLight::PerSlab(t),
            (Some(t), Some(length)) => {
                let (lo, hi) = t.scalar_range();
                let n = t.size();
                let ratio = length / t.length();
                let (e, tr) = t.entries();
                let (emitted, transmittance) = e
                    .iter()
                    .zip(tr)
                    .map(|(&e, &t)| correct(e, t, ratio))
                    .unzip();
                SlabLight::Corrected {
                    size: n,
                    lo,
                    scale: if hi > lo {
                        (n - 1) as f32 / (hi - lo)
                    } else {
                        0.0
                    },
                    emitted,
                    transmittance,
                }
            }
        }
    }

    /// The light of a slab of `length` from `s_front` to `s_back`.
    #[inline]
    pub fn light(&self, s_front: f32, s_back: f32, length: f32) -> SegmentLight {
        match self {
            SlabLight::Corrected {
                size,
                lo,
                scale,
                emitted,
                transmittance,
            } => {
                let n = *size;
                let split = |s: f32| {
                    let x = ((s - lo) * scale).clamp(0.0, (n - 1) as f32);
                    let i = (x as usize).min(n - 2);
                    (i, x - i as f32)
                };
                let (i_f, t_f) = split(s_front);
                let (i_b, t_b) = split(s_back);
                let r0 = i_f * n + i_b;
                let r1 = r0 + n;
                let bilinear = |v: &[Vec3A]| {
                    let near = v[r0].lerp(v[r0 + 1], t_b);
                    let far = v[r1].lerp(v[r1 + 1], t_b);
                    near.lerp(far, t_f)
                };
                SegmentLight {
                    emitted: bilinear(emitted),
                    transmittance: bilinear(transmittance),
                }
            }
            SlabLight::PerSlab(table) => table.lookup(s_front, s_back, length),
            SlabLight::Post(knots) => {
                let m = knots.at(s_front);
                let t = if m.tau.x == m.tau.y && m.tau.y == m.tau.z {
                    Vec3A::splat((-m.tau.x * length).exp())
                } else {
                    Vec3A::new(
                        (-m.tau.x * length).exp(),
                        (-m.tau.y * length).exp(),
                        (-m.tau.z * length).exp(),
                    )
                };
                SegmentLight {
                    emitted: m.lum * (Vec3A::ONE - t),
                    transmittance: t,
                }
            }
        }
    }

    /// The light of the part `fraction` (0..=1) of a slab of `length`,
    /// from `s_front` to `s_back` (the scalars at the part's ends): where a
    /// ray crosses a side face of the grid between two slices.
    pub fn part(&self, s_front: f32, s_back: f32, length: f32, fraction: f32) -> SegmentLight {
        match self {
            SlabLight::Corrected { .. } => {
                let whole = self.light(s_front, s_back, length);
                let (emitted, transmittance) =
                    correct(whole.emitted, whole.transmittance, fraction);
                SegmentLight {
                    emitted,
                    transmittance,
                }
            }
            _ => self.light(s_front, s_back, length * fraction),
        }
    }
}

/// Schulze's correction for `ratio` times the table's length.
fn correct(emitted: Vec3A, transmittance: Vec3A, ratio: f32) -> (Vec3A, Vec3A) {
    let mut e = Vec3A::ZERO;
    let mut t = Vec3A::ONE;
    for c in 0..3 {
        let t0 = transmittance[c].clamp(0.0, 1.0);
        let t1 = t0.powf(ratio);
        t[c] = t1;
        let alpha = 1.0 - t0;
        e[c] = if alpha > 1e-6 {
            emitted[c] * (1.0 - t1) / alpha
        } else {
            emitted[c] * ratio
        };
    }
    (e, t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use tetray_integrate::{ColorPoint, OpacityMode, OpacityPoint, TransferFunction};

    fn knots() -> TfKnots {
        // Clear below 0.3, a ramp up to 0.5, clear again from 0.7 on
        // through a step down.
        let tf = TransferFunction::new(
            vec![ColorPoint {
                scalar: 0.0,
                rgb: Vec3::ONE,
            }],
            vec![
                OpacityPoint {
                    scalar: 0.3,
                    alpha: 0.0,
                },
                OpacityPoint {
                    scalar: 0.5,
                    alpha: 0.8,
                },
                OpacityPoint {
                    scalar: 0.7,
                    alpha: 0.8,
                },
                OpacityPoint {
                    scalar: 0.7,
                    alpha: 0.0,
                },
            ],
        )
        .unwrap();
        TfKnots::new(&tf, 1.0, OpacityMode::Exact)
    }

    #[test]
    fn post_classes_follow_zero_attenuation() {
        let c = Classifier::new(knots(), None);
        assert_ne!(c.class_of(-1.0, 0.3), 0);
        assert_eq!(c.class_of(0.2, 0.31), 0);
        assert_eq!(c.class_of(0.6, 0.65), 0);
        // At 0.7 the step is right-continuous: clear from 0.7 on.
        assert_ne!(c.class_of(0.7, 2.0), 0);
        assert_ne!(c.class_of(-1.0, 0.1), c.class_of(0.8, 0.9));
    }

    #[test]
    fn pre_classes_need_clear_table_entries() {
        let k = knots();
        let table = PreintegrationTable::build(&k, (0.0, 1.0), 101, 1.0).unwrap();
        let c = Classifier::new(k, Some(table));
        assert_ne!(c.class_of(0.0, 0.2), 0);
        assert_eq!(c.class_of(0.25, 0.35), 0);
        assert_ne!(c.class_of(0.75, 1.0), 0);
        assert_ne!(c.class_of(0.0, 0.2), c.class_of(0.75, 1.0));
        // Clear entries in a run are exactly clear after correction too.
        let light = SlabLight::new(&c, Some(1.7)).light(0.05, 0.21, 1.7);
        assert_eq!(light.transmittance, Vec3A::ONE);
        assert_eq!(light.emitted, Vec3A::ZERO);
    }
}
