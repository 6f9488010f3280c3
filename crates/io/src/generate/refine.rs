//! Refinement of a PLOT3D grid: every hexahedron cut into `ri x rj x rk`
//! smaller ones, the grid's points and solution values at the new points
//! by trilinear interpolation of the hexahedron's corners.
//!
//! One level of doubling (factors 2, 2, 2) splits each hexahedron into 8;
//! `L` levels are the factors `2^L`. Trilinear interpolation of a trilinear
//! interpolant is the same trilinear function, so factors `2^L` computed at
//! once equal `L` successive doublings up to f32 rounding, and are computed
//! in one pass from the original values (one rounding, not `L`). Other
//! factors (3, or 4 along one axis and 3 along the others) hit a requested
//! tetrahedron count more closely. Every original point is kept exactly
//! (weight 1), and the result is deterministic: the same source and factors
//! give the same bytes. The one exception to trilinear interpolation is a
//! cell whose trilinear map inverts at a corner (two cells of the
//! Combustor): it is refined on its own tetrahedra (see `folded.rs`).

use glam::Vec3;

use super::GenerateError;
use super::folded::{AxisCell, FoldedCells};
use crate::plot3d::{Plot3dGrid, Plot3dSource};

/// A refined grid computed on the fly from its source: nothing is stored
/// but the source, so it can be written at any size.
#[derive(Debug, Clone)]
pub struct Refinement<'a> {
    source: &'a Plot3dGrid,
    factors: [usize; 3],
    dims: [usize; 3],
    /// Cells refined on their tetrahedra instead (see `folded.rs`).
    folded: Option<FoldedCells>,
}

/// The at most two source points (along one axis) a refined point is
/// interpolated from: `index[0]` alone, or `index[0]` and `index[1]` at
/// parameter `t` in (0, 1).
#[derive(Debug, Clone, Copy)]
struct AxisStencil {
    index: [usize; 2],
    t: f64,
    len: usize,
}

impl AxisStencil {
    /// `v(0) + t (v(1) - v(0))`: exactly `v(0)` when both ends are equal,
    /// whatever `t`.
    fn lerp(&self, v: impl Fn(usize) -> f64) -> f64 {
        let a = v(0);
        if self.len == 1 {
            a
        } else {
            a + self.t * (v(1) - a)
        }
    }

    /// `(source index, weight)` of each end.
    fn weights(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        // t is 0 for a single end.
        let w = [1.0 - self.t, self.t];
        (0..self.len).map(move |e| (self.index[e], w[e]))
    }
}

/// How a refined point is computed: trilinearly, or on a folded cell's
/// tetrahedra (4 source points and weights).
#[derive(Debug, Clone, Copy)]
enum PointStencil {
    Trilinear([AxisStencil; 3]),
    Linear([(usize, f64); 4]),
}

/// Refined point `i` along an axis of `n` source points cut `r` times: on
/// source point `c` where `i = c r`, else between `c` and `c + 1` at
/// `t = (i - c r) / r`.
fn axis_stencil(i: usize, n: usize, r: usize) -> AxisStencil {
    let c = (i / r).min(n - 2);
    let offset = i - c * r;
    if offset == 0 || offset == r {
        let at = if offset == 0 { c } else { c + 1 };
        return AxisStencil {
            index: [at, at],
            t: 0.0,
            len: 1,
        };
    }
    AxisStencil {
        index: [c, c + 1],
        t: offset as f64 / r as f64,
        len: 2,
    }
}

impl<'a> Refinement<'a> {
    /// `source` with every hexahedron cut `factors[a]` times along axis `a`.
    ///
    /// # Errors
    /// [`GenerateError::ZeroFactor`]; [`GenerateError::TooLarge`] when the
    /// refined grid has more points than 32-bit indices (and the PLOT3D
    /// header) can hold.
    pub fn new(source: &'a Plot3dGrid, factors: [usize; 3]) -> Result<Self, GenerateError> {
        if factors.contains(&0) {
            return Err(GenerateError::ZeroFactor { factors });
        }
        let too_large = |what: String, max: usize| GenerateError::TooLarge {
            dims: source.dims,
            factors,
            what,
            max,
        };
        let mut dims = [0; 3];
        for a in 0..3 {
            dims[a] = (source.dims[a] - 1)
                .checked_mul(factors[a])
                .map(|d| d + 1)
                .filter(|&d| d <= i32::MAX as usize)
                .ok_or_else(|| too_large(format!("axis {a} too long"), i32::MAX as usize))?;
        }
        let points = dims.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d));
        let max = u32::MAX as usize;
        match points {
            Some(p) if p <= max => Ok(Refinement {
                source,
                factors,
                dims,
                folded: FoldedCells::find(source),
            }),
            _ => Err(too_large(
                format!(
                    "{dims:?} = {} points",
                    dims.map(|d| d as u128).iter().product::<u128>()
                ),
                max,
            )),
        }
    }

    /// `level` doublings: factors `2^level` along every axis (hexahedra
    /// times `8^level`).
    ///
    /// # Errors
    /// As [`Refinement::new`].
    pub fn levels(source: &'a Plot3dGrid, level: u32) -> Result<Self, GenerateError> {
        // Too large a level fails in `new`, naming the axis.
        let factor = 1usize.checked_shl(level).unwrap_or(usize::MAX);
        Refinement::new(source, [factor; 3])
    }

    pub fn factors(&self) -> [usize; 3] {
        self.factors
    }

    pub fn source(&self) -> &'a Plot3dGrid {
        self.source
    }

    /// Cells of the source whose trilinear map inverts at a corner, refined
    /// piecewise-linearly on their own tetrahedra (see `folded.rs`).
    pub fn folded_cells(&self) -> usize {
        self.folded.as_ref().map_or(0, FoldedCells::count)
    }

    /// How refined point `p` is computed from the source.
    fn stencil(&self, p: usize) -> PointStencil {
        let axes = self.axis_stencils(p);
        match self.folded_stencil(&axes) {
            Some(linear) => PointStencil::Linear(linear),
            None => PointStencil::Trilinear(axes),
        }
    }

    /// The stencils of refined point `p` along i, j, k.
    fn axis_stencils(&self, p: usize) -> [AxisStencil; 3] {
        let [ni, nj, _] = self.dims;
        let (i, j, k) = (p % ni, (p / ni) % nj, p / (ni * nj));
        let [si, sj, sk] = self.source.dims;
        let [ri, rj, rk] = self.factors;
        [
            axis_stencil(i, si, ri),
            axis_stencil(j, sj, rj),
            axis_stencil(k, sk, rk),
        ]
    }

    /// Trilinear interpolation of `values` at the stencil, one axis at a
    /// time in f64 and rounded once to f32. Source points that coincide
    /// along a grid line (a collapsed edge, a wrapped seam) hold equal
    /// values, and [`AxisStencil::lerp`] of equal values is exact, so the
    /// refined points between or beside them coincide bit for bit too: the
    /// reader finds the same collapsed cells and duplicate points. Points
    /// in a folded cell are interpolated on its tetrahedra instead.
    fn interpolate(&self, s: &PointStencil, values: &[f32]) -> f32 {
        let [a, b, c] = match s {
            PointStencil::Trilinear(axes) => axes,
            PointStencil::Linear(linear) => {
                let sum: f64 = linear.iter().map(|&(p, w)| w * f64::from(values[p])).sum();
                return sum as f32;
            }
        };
        let [si, sj, _] = self.source.dims;
        let at = |x: usize, y: usize, z: usize| {
            f64::from(values[a.index[x] + si * (b.index[y] + sj * c.index[z])])
        };
        c.lerp(|z| b.lerp(|y| a.lerp(|x| at(x, y, z)))) as f32
    }

    /// The piecewise-linear stencil of a point inside or on a face of a
    /// folded cell. Points on edges and corners are left to the trilinear
    /// rule, which is linear there too.
    fn folded_stencil(&self, s: &[AxisStencil; 3]) -> Option<[(usize, f64); 4]> {
        let folded = self.folded.as_ref()?;
        if s.iter().filter(|a| a.len == 2).count() < 2 {
            return None;
        }
        let [si, sj, sk] = self.source.dims;
        // Along each axis: inside one cell, or on a grid plane between two.
        let cells = |a: &AxisStencil, n: usize| -> ([AxisCell; 2], usize) {
            let m = a.index[0];
            match (a.len, m) {
                (2, _) => ([(m, a.t), (0, 0.0)], 1),
                (_, 0) => ([(0, 0.0), (0, 0.0)], 1),
                (_, m) if m == n - 1 => ([(m - 1, 1.0), (0, 0.0)], 1),
                (_, m) => ([(m - 1, 1.0), (m, 0.0)], 2),
            }
        };
        let (ci, cj, ck) = (cells(&s[0], si), cells(&s[1], sj), cells(&s[2], sk));
        folded.stencil(
            [&ci.0[..ci.1], &cj.0[..cj.1], &ck.0[..ck.1]],
            |[i, j, k]| i + si * (j + sj * k),
        )
    }
}

impl Plot3dSource for Refinement<'_> {
    fn dims(&self) -> [usize; 3] {
        self.dims
    }

    fn coordinate(&self, axis: usize, p: usize) -> f32 {
        self.interpolate(&self.stencil(p), &self.source.xyz[axis])
    }

    fn has_iblank(&self) -> bool {
        self.source.iblank.is_some()
    }

    /// Conservative: 0 when any source point the value would be
    /// interpolated from is blanked, so every hexahedron cut from a blanked
    /// one keeps a blanked corner and none cut from a kept one gets one;
    /// otherwise the flag of the nearest of those points.
    fn iblank(&self, p: usize) -> i32 {
        let Some(iblank) = &self.source.iblank else {
            return 1;
        };
        let [a, b, c] = self.axis_stencils(p);
        let [si, sj, _] = self.source.dims;
        // (flag, weight) of the source points; the first of the heaviest
        // wins ties (the lowest index).
        let mut best = (1, f64::NEG_INFINITY);
        for (z, wz) in c.weights() {
            for (y, wy) in b.weights() {
                for (x, wx) in a.weights() {
                    let flag = iblank[x + si * (y + sj * z)];
                    if flag == 0 {
                        return 0;
                    }
                    if wx * wy * wz > best.1 {
                        best = (flag, wx * wy * wz);
                    }
                }
            }
        }
        best.0
    }

    fn conditions(&self) -> Option<[f32; 4]> {
        self.source.solution.as_ref().map(|s| s.conditions)
    }

    fn solution(&self, q: usize, p: usize) -> f32 {
        let Some(solution) = &self.source.solution else {
            return 0.0;
        };
        self.interpolate(&self.stencil(p), &solution.q[q])
    }

    /// One stencil for the three coordinates.
    fn point(&self, p: usize) -> Vec3 {
        let s = self.stencil(p);
        let [x, y, z] = &self.source.xyz;
        Vec3::new(
            self.interpolate(&s, x),
            self.interpolate(&s, y),
            self.interpolate(&s, z),
        )
    }
}

/// `source` refined by `factors`, held in memory (to refine it again, or
/// to test it).
///
/// # Errors
/// As [`Refinement::new`].
pub fn refine(source: &Plot3dGrid, factors: [usize; 3]) -> Result<Plot3dGrid, GenerateError> {
    Ok(Plot3dGrid::from_source(&Refinement::new(source, factors)?))
}
