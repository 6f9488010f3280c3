//! A folded hexahedron split around a point added inside it.
//!
//! A hexahedron deformed until its faces fold (the crushed cells of a
//! crash simulation) may have no split over its own corners whose
//! tetrahedra all have one orientation. Its face diagonals are fixed by
//! its neighbours (the splitter's smallest-index rule), so its boundary is
//! twelve fixed triangles; when some point sees all twelve from inside
//! (the cell is star-shaped around it), the cones from that point over the
//! triangles fill the cell exactly and conform with the neighbours. The
//! point is searched among the cell's own parametric points, so that its
//! place and its fields are the cell's trilinear interpolation.

use glam::DVec3;

use super::split::{HEX_FACES, HEX_REF, quad_triangles};

/// Parametric candidates per axis: 8^3 points at the centres of a regular
/// 8 x 8 x 8 subdivision of the reference cube.
const CANDIDATES_PER_AXIS: usize = 8;

/// A split of a hexahedron around an added point.
#[derive(Debug, Clone, PartialEq)]
pub struct CentredSplit {
    /// The added point as weights of the hexahedron's corners (trilinear,
    /// summing to 1), by global point id.
    pub weights: Vec<(u32, f64)>,
    /// The twelve boundary triangles (global ids) that, with the added
    /// point as the first vertex, give tetrahedra of one orientation.
    pub faces: Vec<[u32; 3]>,
}

/// The split of the hexahedron `ids` (VTK order, global point ids into
/// `xyz`, three coordinates per point) around the parametric point whose
/// twelve cone tetrahedra all have one orientation with the largest
/// smallest volume, or `None` when no candidate has (the cell is not
/// star-shaped around any of them).
pub fn hexahedron_centred(ids: &[u32], xyz: &[f64]) -> Option<CentredSplit> {
    let corner = |i: usize| {
        let p = 3 * ids[i] as usize;
        DVec3::new(xyz[p], xyz[p + 1], xyz[p + 2])
    };
    let corners: [DVec3; 8] = std::array::from_fn(corner);
    let faces: Vec<[usize; 3]> = HEX_FACES
        .iter()
        .flat_map(|&q| quad_triangles(ids, q))
        .collect();
    let mut best: Option<(f64, [f64; 8])> = None;
    let n = CANDIDATES_PER_AXIS;
    let at = |k: usize| (k as f64 + 0.5) / n as f64;
    for (i, j, k) in (0..n).flat_map(|i| (0..n).flat_map(move |j| (0..n).map(move |k| (i, j, k)))) {
        let w = trilinear_weights(at(i), at(j), at(k));
        let c = corners.iter().zip(w).map(|(&p, w)| p * w).sum::<DVec3>();
        // Six times the cone volumes; one orientation means all of one sign.
        let volumes = faces.iter().map(|t| {
            let [a, b, d] = t.map(|v| corners[v] - c);
            a.dot(b.cross(d))
        });
        let (lo, hi) = volumes.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        let margin = if lo > 0.0 {
            lo
        } else if hi < 0.0 {
            -hi
        } else {
            continue;
        };
        if best.is_none_or(|(m, _)| margin > m) {
            best = Some((margin, w));
        }
    }
    let (_, w) = best?;
    Some(CentredSplit {
        weights: ids.iter().zip(w).map(|(&id, w)| (id, w)).collect(),
        faces: faces.iter().map(|t| t.map(|v| ids[v])).collect(),
    })
}

/// The trilinear weights of the VTK hexahedron's corners at parametric
/// point (r, s, t): per corner of the reference cell, the product over the
/// axes of the coordinate where the corner is at 1, its complement at 0.
fn trilinear_weights(r: f64, s: f64, t: f64) -> [f64; 8] {
    let x = [r, s, t];
    HEX_REF.map(|corner| {
        (0..3)
            .map(|a| if corner[a] == 1.0 { x[a] } else { 1.0 - x[a] })
            .product()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube, in VTK order.
    const CUBE: [[f64; 3]; 8] = HEX_REF;

    fn volume6(c: DVec3, t: [u32; 3], xyz: &[f64]) -> f64 {
        let p = |i: u32| {
            let i = 3 * i as usize;
            DVec3::new(xyz[i], xyz[i + 1], xyz[i + 2]) - c
        };
        p(t[0]).dot(p(t[1]).cross(p(t[2])))
    }

    fn centre(split: &CentredSplit, xyz: &[f64]) -> DVec3 {
        split
            .weights
            .iter()
            .map(|&(id, w)| {
                let i = 3 * id as usize;
                DVec3::new(xyz[i], xyz[i + 1], xyz[i + 2]) * w
            })
            .sum()
    }

    /// A cube whose corner 1 is pushed inwards past the plane of its three
    /// neighbours: the corner's own tetrahedron inverts under every split
    /// over the corners, but the cell is still star-shaped around points
    /// near the opposite corner.
    fn dented() -> Vec<f64> {
        let mut points = CUBE;
        points[1] = [0.3, 0.3, 0.3];
        points.iter().flatten().copied().collect()
    }

    #[test]
    fn trilinear_weights_pick_each_corner_at_its_reference_point() {
        for (i, [r, s, t]) in HEX_REF.into_iter().enumerate() {
            let w = trilinear_weights(r, s, t);
            let one_hot: [f64; 8] = std::array::from_fn(|j| f64::from(u8::from(i == j)));
            assert_eq!(w, one_hot, "corner {i}");
        }
        // The centre weighs every corner alike.
        assert_eq!(trilinear_weights(0.5, 0.5, 0.5), [0.125; 8]);
    }

    #[test]
    fn a_cube_splits_into_twelve_cones_of_its_volume() {
        let xyz: Vec<f64> = CUBE.iter().flatten().copied().collect();
        let ids: Vec<u32> = (0..8).collect();
        let split = hexahedron_centred(&ids, &xyz).expect("a cube is star-shaped");
        assert_eq!(split.faces.len(), 12);
        let w: f64 = split.weights.iter().map(|w| w.1).sum();
        assert!((w - 1.0).abs() < 1e-12);
        let c = centre(&split, &xyz);
        let total: f64 = split.faces.iter().map(|&t| volume6(c, t, &xyz)).sum();
        // Six times the unit cube's volume, one sign throughout.
        assert!((total.abs() - 6.0).abs() < 1e-12, "{total}");
        let signs = split.faces.iter().map(|&t| volume6(c, t, &xyz).signum());
        assert!(
            signs
                .clone()
                .all(|s| s == signs.clone().next().unwrap_or(0.0))
        );
    }

    #[test]
    fn a_dented_cell_splits_around_a_point_that_sees_every_face() {
        let xyz = dented();
        let ids: Vec<u32> = (0..8).collect();
        let split = hexahedron_centred(&ids, &xyz).expect("star-shaped");
        let c = centre(&split, &xyz);
        let v: Vec<f64> = split.faces.iter().map(|&t| volume6(c, t, &xyz)).collect();
        assert!(
            v.iter().all(|&v| v > 0.0) || v.iter().all(|&v| v < 0.0),
            "{v:?}"
        );
        // The cones fill the cell: their volumes sum to the volume its
        // boundary encloses (the divergence theorem: the cones from the
        // origin over the same oriented triangles).
        let expected: f64 = split
            .faces
            .iter()
            .map(|&t| volume6(DVec3::ZERO, t, &xyz))
            .sum();
        let total: f64 = v.iter().sum();
        assert!((total - expected).abs() < 1e-12, "{total} vs {expected}");
    }

    #[test]
    fn a_cell_folded_through_itself_has_no_centre() {
        // The top face pushed through the bottom: every parametric point
        // sees some face from behind.
        let mut points = CUBE;
        for p in &mut points[4..] {
            p[2] = -0.5;
        }
        points[6] = [1.0, 1.0, 1.0];
        let xyz: Vec<f64> = points.iter().flatten().copied().collect();
        let ids: Vec<u32> = (0..8).collect();
        assert_eq!(hexahedron_centred(&ids, &xyz), None);
    }
}
