//! From a visibility order to draws: one per tetrahedron, or with adaptive
//! transfer-function sampling (section 4.3) one per knot interval its
//! scalar range spans, each clipped to its interval per fragment, in
//! back-to-front order within the tetrahedron too.
//!
//! A draw is `[tet, clip]`: `clip = k + 1` clips to knot interval `k`
//! (`-1` below the first knot .. `n - 1` above the last), [`NO_CLIP`]
//! draws the whole cell with the transfer function sampled at its ends.

use rayon::prelude::*;

use crate::scene::ProjectScene;
use crate::view::View;

/// The clip code of a draw of the whole cell.
pub const NO_CLIP: u32 = u32::MAX;

/// The knot interval of `s` (right-continuous), as the kernels compute it:
/// the number of knots at or below `s`, minus one.
pub fn interval_of(knots: &[f32], s: f32) -> i32 {
    knots.partition_point(|&k| k <= s) as i32 - 1
}

/// Per tetrahedron, the knot intervals of its smallest and largest scalar:
/// its pieces under adaptive sampling. View independent; one per transfer
/// function.
#[derive(Debug, Clone, PartialEq)]
pub struct TetIntervals {
    pub knots: Vec<f32>,
    pub spans: Vec<[i32; 2]>,
    /// Pieces over all tetrahedra.
    pub pieces: usize,
}

impl TetIntervals {
    pub fn new(scene: &ProjectScene, knots: &[f32]) -> TetIntervals {
        let spans: Vec<[i32; 2]> = scene
            .scalar_ranges
            .par_iter()
            .map(|&[lo, hi]| [interval_of(knots, lo), interval_of(knots, hi)])
            .collect();
        let pieces = spans.iter().map(|s| (s[1] - s[0] + 1) as usize).sum();
        TetIntervals {
            knots: knots.to_vec(),
            spans,
            pieces,
        }
    }
}

/// The draws of `order` (back to front): whole cells, or, with
/// `intervals`, one clipped draw per piece.
pub fn expand(
    scene: &ProjectScene,
    intervals: Option<&TetIntervals>,
    order: &[u32],
    view: &View,
) -> Vec<[u32; 2]> {
    let Some(intervals) = intervals else {
        return order.par_iter().map(|&t| [t, NO_CLIP]).collect();
    };
    order
        .par_iter()
        .flat_map_iter(|&t| {
            let [lo, hi] = intervals.spans[t as usize];
            piece_order(scene, intervals, t, lo, hi, view).map(move |k| [t, (k + 1) as u32])
        })
        .collect()
}

/// The intervals `lo..=hi` of tetrahedron `t` back to front. Along any ray
/// from the eye the scalar runs monotonically away from its value at the
/// eye, `s_eye` (the cell's linear field extended): intervals above it are
/// farther the higher they are, those below it the lower, and the one
/// holding it is nearest. Orthographic views have the eye at infinity
/// against the view direction.
fn piece_order(
    scene: &ProjectScene,
    intervals: &TetIntervals,
    t: u32,
    lo: i32,
    hi: i32,
    view: &View,
) -> impl Iterator<Item = i32> + use<> {
    let g = scene.gradients[t as usize];
    let gradient = glam::Vec3::new(g[0], g[1], g[2]);
    let eye = if lo == hi {
        lo
    } else if view.orthographic {
        if gradient.dot(view.direction) > 0.0 {
            lo - 1
        } else {
            hi + 1
        }
    } else {
        let centroid = scene.centroids[t as usize];
        let s_eye = g[3] + gradient.dot(view.position - centroid);
        interval_of(&intervals.knots, s_eye).clamp(lo - 1, hi + 1)
    };
    // Above the eye's interval: high to low; below it: low to high; then
    // the eye's own.
    let above = ((eye + 1).max(lo)..=hi).rev();
    let below = lo..=(eye - 1).min(hi);
    let own = (lo..=hi).filter(move |&k| k == eye);
    above.chain(below).chain(own)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_are_right_continuous() {
        let knots = [0.0, 1.0, 1.0, 2.0];
        assert_eq!(interval_of(&knots, -0.5), -1);
        assert_eq!(interval_of(&knots, 0.0), 0);
        assert_eq!(interval_of(&knots, 0.99), 0);
        assert_eq!(interval_of(&knots, 1.0), 2);
        assert_eq!(interval_of(&knots, 2.0), 3);
        assert_eq!(interval_of(&knots, 5.0), 3);
    }
}
