//! Folded cells: hexahedra whose trilinear map inverts at a corner (the
//! three edges there are left-handed: a concave corner, as in two cells of
//! the Combustor). The reader's split avoids that corner's tetrahedron by
//! its choice of diagonals, but trilinear points near the corner fold the
//! refined cells there, whatever the diagonals. Inside such a cell (and on
//! its faces) refined points are placed piecewise-linearly on the cell's
//! own 5 tetrahedra instead, which are positively oriented: the refined
//! cells at the corner are then scaled copies of the split cell's, valid
//! at every refinement.

use rayon::prelude::*;

use crate::plot3d::{Plot3dGrid, plot3d_split_counts};

/// A cell along one axis and the coordinate in it, in [0, 1].
pub(crate) type AxisCell = (usize, f64);

/// The folded cells of a grid and the diagonal parity of its split.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FoldedCells {
    /// Cells per axis.
    cells: [usize; 3],
    /// One flag per hexahedron (i fastest).
    folded: Vec<bool>,
    /// The reader's diagonal parity for the unrefined grid.
    parity: usize,
}

impl FoldedCells {
    /// The folded cells of `grid`, or `None` when there are none (the
    /// common case, which then costs nothing more).
    pub fn find(grid: &Plot3dGrid) -> Option<FoldedCells> {
        let [ni, nj, nk] = grid.dims;
        let cells = [ni - 1, nj - 1, nk - 1];
        let point = |i: usize, j: usize, k: usize| {
            let p = i + ni * (j + nj * k);
            glam::DVec3::new(
                f64::from(grid.xyz[0][p]),
                f64::from(grid.xyz[1][p]),
                f64::from(grid.xyz[2][p]),
            )
        };
        let folded: Vec<bool> = (0..cells.iter().product())
            .into_par_iter()
            .map(|h| {
                let (i, j, k) = (
                    h % cells[0],
                    (h / cells[0]) % cells[1],
                    h / (cells[0] * cells[1]),
                );
                (0..8).any(|c| {
                    let (di, dj, dk) = (c & 1, (c >> 1) & 1, c >> 2);
                    let o = point(i + di, j + dj, k + dk);
                    let ei = point(i + 1 - di, j + dj, k + dk) - o;
                    let ej = point(i + di, j + 1 - dj, k + dk) - o;
                    let ek = point(i + di, j + dj, k + 1 - dk) - o;
                    // Each edge pointing backwards is a reflection.
                    let sign = if (di + dj + dk) % 2 == 0 { 1.0 } else { -1.0 };
                    // Strictly negative: a collapsed edge (Blunt Fin) gives
                    // 0 and is not folded.
                    sign * ei.dot(ej.cross(ek)) < 0.0
                })
            })
            .collect();
        if !folded.contains(&true) {
            return None;
        }
        Some(FoldedCells {
            cells,
            folded,
            parity: plot3d_split_counts(grid).diagonal_parity,
        })
    }

    /// Number of folded cells.
    pub fn count(&self) -> usize {
        self.folded.iter().filter(|&&f| f).count()
    }

    /// The piecewise-linear stencil (4 source points and weights) of a
    /// point in the closed cell of a folded hexahedron, given per axis the
    /// cells it lies in (two on a grid plane, one inside a cell); `None`
    /// when no such cell is folded. `index` maps `(i, j, k)` to a point.
    pub fn stencil(
        &self,
        axes: [&[AxisCell]; 3],
        index: impl Fn([usize; 3]) -> usize,
    ) -> Option<[(usize, f64); 4]> {
        for &(ck, z) in axes[2] {
            for &(cj, y) in axes[1] {
                for &(ci, x) in axes[0] {
                    let h = ci + self.cells[0] * (cj + self.cells[1] * ck);
                    if self.folded[h] {
                        let set = (ci + cj + ck + self.parity) % 2;
                        let local = tet_weights([x, y, z], set);
                        return Some(
                            local.map(|([a, b, c], w)| (index([ci + a, cj + b, ck + c]), w)),
                        );
                    }
                }
            }
        }
        None
    }
}

/// Barycentric weights of reference point `x` in the 5-tetrahedra split of
/// the unit cube (`crate::structured`): template `set` 0 has its central
/// tetrahedron on the even corners and cuts off the odd ones, set 1 the
/// reverse. The corner tetrahedron at corner `k` is where `|x - k|_1 <= 1`.
fn tet_weights(x: [f64; 3], set: usize) -> [([usize; 3], f64); 4] {
    let corners = |parity: usize| {
        (0..8)
            .map(|c| [c & 1, (c >> 1) & 1, c >> 2])
            .filter(move |k| (k[0] + k[1] + k[2]) % 2 == parity)
    };
    for k in corners(1 - set) {
        let d = [0, 1, 2].map(|a| (x[a] - k[a] as f64).abs());
        if d[0] + d[1] + d[2] <= 1.0 {
            let step = |a: usize| {
                let mut n = k;
                n[a] = 1 - n[a];
                (n, d[a])
            };
            return [(k, 1.0 - d[0] - d[1] - d[2]), step(0), step(1), step(2)];
        }
    }
    // The central tetrahedron; set 1 is set 0 reflected in x.
    let (mut a, y, z) = (x[0], x[1], x[2]);
    if set == 1 {
        a = 1.0 - a;
    }
    let reflect = |mut k: [usize; 3]| {
        if set == 1 {
            k[0] = 1 - k[0];
        }
        k
    };
    [
        (reflect([0, 0, 0]), 1.0 - 0.5 * (a + y + z)),
        (reflect([1, 1, 0]), 0.5 * (a + y - z)),
        (reflect([1, 0, 1]), 0.5 * (a - y + z)),
        (reflect([0, 1, 1]), 0.5 * (-a + y + z)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The weights reproduce the point and every corner's own tetrahedron.
    #[test]
    fn weights_interpolate_linearly_in_both_sets() {
        for set in 0..2 {
            for n in 0..125 {
                let x = [n % 5, (n / 5) % 5, n / 25].map(|c| c as f64 / 4.0);
                let w = tet_weights(x, set);
                let sum: f64 = w.iter().map(|(_, w)| w).sum();
                assert!((sum - 1.0).abs() < 1e-12, "{x:?}");
                for a in 0..3 {
                    let back: f64 = w.iter().map(|(k, w)| k[a] as f64 * w).sum();
                    assert!((back - x[a]).abs() < 1e-12, "{x:?} set {set}");
                }
                assert!(
                    w.iter().all(|(_, w)| *w >= -1e-12),
                    "{x:?} set {set}: {w:?}"
                );
            }
        }
    }
}
