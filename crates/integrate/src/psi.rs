//! Psi, the partial pre-integration term (dissertation eq. 5.4, 5.8, 5.10):
//! for a segment with linear attenuation, `a = tau_b D` at the back and
//! `b = tau_f D` at the front,
//!
//! `Psi(a, b) = int_0^1 exp(-(b x + (a - b) x^2 / 2)) dx`
//!
//! (`x` is the fraction of the segment between a point and the front end:
//! Psi is the mean transmittance from the segment to the eye). This module
//! computes Psi in f64 by quadrature and stores it in the table that the
//! ray casters look up with `gamma = tau D / (1 + tau D)` (section 5.2.3).

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use tetray_wide::Wide;

use rayon::prelude::*;

use crate::IntegrateError;
use crate::special::gauss_legendre_panel;

/// Exponent drop (in e-folds) covered by one 16-point Gauss-Legendre panel:
/// `exp(-4 t)` on `[0, 1]` is integrated to 1e-16 by that rule.
const EFOLDS_PER_PANEL: f64 = 4.0;
/// Beyond this many e-folds the rest of the integrand is below 1e-26.
const EFOLDS_CUTOFF: f64 = 60.0;

/// Psi in f64 for `a = tau_b D >= 0` and `b = tau_f D >= 0` (either may be
/// infinite), to about 1e-15 absolute.
///
/// The exponent `E(x) = -(b x + c x^2)`, `c = (a - b) / 2`, decreases
/// monotonically on `[0, 1]` (`E'(x) = -(b (1 - x) + a x)`), so the interval
/// is cut where `E` crosses each multiple of `EFOLDS_PER_PANEL` and each
/// piece gets a Gauss-Legendre panel: accurate however steep the integrand.
pub fn psi(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() || a < 0.0 || b < 0.0 {
        return f64::NAN;
    }
    if a.is_infinite() || b.is_infinite() {
        return 0.0;
    }
    if a == 0.0 && b == 0.0 {
        // A transparent segment: exactly 1 (the rule's weights sum to 2 only
        // to rounding).
        return 1.0;
    }
    let c = 0.5 * (a - b);
    let total = 0.5 * (a + b);
    let integrand = |x: f64| (-(b * x + c * x * x)).exp();
    let mut sum = 0.0;
    let mut x0 = 0.0;
    let mut level = EFOLDS_PER_PANEL;
    loop {
        if level >= total {
            sum += gauss_legendre_panel(x0, 1.0, integrand);
            break;
        }
        if level > EFOLDS_CUTOFF {
            break;
        }
        // b x + c x^2 = level, in the form without cancellation.
        let x1 = (2.0 * level / (b + (b * b + 4.0 * c * level).max(0.0).sqrt())).min(1.0);
        sum += gauss_legendre_panel(x0, x1, integrand);
        x0 = x1;
        level += EFOLDS_PER_PANEL;
    }
    sum
}

/// How the table's nodes are placed along each gamma axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum GammaSpacing {
    /// Nodes uniform in gamma, `gamma_i = i / (N - 1)`: the dissertation's
    /// table. Near `gamma_b = 1` Psi behaves like `sqrt(1 - gamma_b)`, whose
    /// unbounded curvature limits bilinear lookup to about 1e-2 there.
    Uniform,
    /// Nodes uniform in `u = 1 - sqrt(1 - gamma) = 1 - 1/sqrt(1 + tau D)`,
    /// i.e. `gamma_i = 1 - (1 - i / (N - 1))^2`: Psi is smooth in `u` up to
    /// both opaque edges (bilinear error 1.0e-6 at 1024^2 over a dense grid).
    /// Only where both ends are extremely opaque does Psi vary faster than
    /// any separable grid resolves: with `w = 1 - u`, it changes over
    /// `w_b ~ w_f^2`, below one cell once `tau_f D > (N - 1)` and
    /// `tau_b D > (N - 1)^2`; there the error is at most about 2e-4, on
    /// a Psi below 1e-3.
    #[default]
    Quadratic,
}

impl GammaSpacing {
    /// The table coordinate in `[0, 1]` of `tau D >= 0` (infinity maps to 1).
    #[inline(always)]
    pub fn coord_of_tau_d(self, tau_d: f32) -> f32 {
        match self {
            GammaSpacing::Uniform => 1.0 - 1.0 / (1.0 + tau_d),
            GammaSpacing::Quadratic => 1.0 - (1.0 + tau_d).sqrt().recip(),
        }
    }

    /// The table coordinate in `[0, 1]` of `gamma` in `[0, 1]`.
    #[inline]
    pub fn coord_of_gamma(self, gamma: f32) -> f32 {
        match self {
            GammaSpacing::Uniform => gamma,
            GammaSpacing::Quadratic => 1.0 - (1.0 - gamma).max(0.0).sqrt(),
        }
    }

    /// `tau D` at table coordinate `u` in `[0, 1]` (f64, for building).
    pub fn tau_d_of_coord(self, u: f64) -> f64 {
        match self {
            GammaSpacing::Uniform => u / (1.0 - u),
            // 1 + tau D = 1 / (1 - u)^2.
            GammaSpacing::Quadratic => {
                let w = 1.0 - u;
                (1.0 - w * w) / (w * w)
            }
        }
    }

    /// Gamma at table coordinate `u`.
    pub fn gamma_of_coord(self, u: f64) -> f64 {
        match self {
            GammaSpacing::Uniform => u,
            GammaSpacing::Quadratic => 1.0 - (1.0 - u) * (1.0 - u),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            GammaSpacing::Uniform => "uniform",
            GammaSpacing::Quadratic => "quadratic",
        }
    }
}

/// Smallest and largest accepted table sizes (nodes per axis).
pub const PSI_TABLE_MIN: usize = 2;
pub const PSI_TABLE_MAX: usize = 8192;

/// Psi sampled on an `N x N` grid of (gamma_b, gamma_f), f32, looked up
/// bilinearly. Row-major with gamma_f selecting the row:
/// `values[i_f * N + i_b]` (back along x, front along y, as the texture).
#[derive(Debug, Clone, PartialEq)]
pub struct PsiTable {
    size: usize,
    spacing: GammaSpacing,
    values: Vec<f32>,
    /// `size - 1` as f32 and the last cell index, for the lookup.
    last: f32,
    last_cell: u32,
}

/// The table's lookups at one (gamma_b, gamma_f) beside Psi in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PsiAt {
    /// tau D of each end, from gamma = tau D / (1 + tau D).
    pub tau_b_d: f64,
    pub tau_f_d: f64,
    pub bilinear: f32,
    pub nearest: f32,
    pub exact: f64,
}

impl PsiAt {
    pub fn error_bilinear(&self) -> f64 {
        (f64::from(self.bilinear) - self.exact).abs()
    }

    pub fn error_nearest(&self) -> f64 {
        (f64::from(self.nearest) - self.exact).abs()
    }
}

/// tau D of a gamma (infinite at 1).
fn tau_d_of(gamma: f32) -> f64 {
    let g = f64::from(gamma);
    if g >= 1.0 {
        f64::INFINITY
    } else {
        g / (1.0 - g)
    }
}

impl PsiTable {
    /// Computes the table in f64 (in parallel) and rounds it to f32.
    pub fn build(size: usize, spacing: GammaSpacing) -> Result<PsiTable, IntegrateError> {
        if !(PSI_TABLE_MIN..=PSI_TABLE_MAX).contains(&size) {
            return Err(IntegrateError::PsiTableSize {
                size,
                min: PSI_TABLE_MIN,
                max: PSI_TABLE_MAX,
            });
        }
        let last = (size - 1) as f64;
        let tau_d: Vec<f64> = (0..size)
            .map(|i| {
                if i == size - 1 {
                    f64::INFINITY
                } else {
                    spacing.tau_d_of_coord(i as f64 / last)
                }
            })
            .collect();
        let mut values = vec![0.0f32; size * size];
        values
            .par_chunks_mut(size)
            .zip(&tau_d)
            .for_each(|(row, &front)| {
                for (value, &back) in row.iter_mut().zip(&tau_d) {
                    *value = psi(back, front) as f32;
                }
            });
        Ok(PsiTable {
            size,
            spacing,
            values,
            last: (size - 1) as f32,
            last_cell: (size - 2) as u32,
        })
    }

    /// The process-wide table of `size` nodes per axis with the default
    /// spacing, built on first use and shared afterwards.
    pub fn shared(size: usize) -> Result<Arc<PsiTable>, IntegrateError> {
        static CACHE: OnceLock<Mutex<HashMap<usize, Arc<PsiTable>>>> = OnceLock::new();
        let cache = CACHE.get_or_init(Default::default);
        // Held while building: a second caller waits instead of rebuilding.
        let mut tables = cache
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some(table) = tables.get(&size) {
            return Ok(Arc::clone(table));
        }
        let table = Arc::new(PsiTable::build(size, GammaSpacing::default())?);
        tables.insert(size, Arc::clone(&table));
        Ok(table)
    }

    /// Nodes per axis.
    pub fn size(&self) -> usize {
        self.size
    }

    pub fn spacing(&self) -> GammaSpacing {
        self.spacing
    }

    /// The samples, `values[i_f * size + i_b]`.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// Gamma of node `i` on either axis.
    pub fn node_gamma(&self, i: usize) -> f64 {
        self.spacing
            .gamma_of_coord(i as f64 / (self.size - 1) as f64)
    }

    /// Bilinear lookup by `(tau_b D, tau_f D)`, both `>= 0`: the bits of
    /// `PsiTable::bilinear` at [`GammaSpacing::coord_of_tau_d`].
    #[inline(always)]
    pub fn lookup(&self, tau_d_back: f32, tau_d_front: f32) -> f32 {
        self.interpolate(self.coord(tau_d_back), self.coord(tau_d_front))
    }

    /// The node coordinate in `[0, size - 1]` of `tau D`: the clamp of
    /// [`PsiTable::bilinear`] written as the selects of SSE's `max` and
    /// `min` (a NaN passes through, as through `f32::clamp`), which the
    /// compiler emits for them, as wide as the CPU allows when a loop runs
    /// it over many lanes.
    #[inline(always)]
    fn coord(&self, tau_d: f32) -> f32 {
        let u = self.spacing.coord_of_tau_d(tau_d);
        let above = if 0.0 > u { 0.0 } else { u };
        let below = if 1.0 < above { 1.0 } else { above };
        below * self.last
    }

    /// [`PsiTable::lookup`] of `N` segments at once, lane by lane with its
    /// operations (so its bits), written as loops over the lanes so that
    /// the coordinates vectorize (eight lanes at a time with AVX); the four
    /// table reads per lane are AVX2 gathers of eight lanes where `wide`
    /// holds their token, else scalar.
    #[inline(always)]
    pub fn lookup_lanes<const N: usize>(
        &self,
        tau_d_back: &[f32; N],
        tau_d_front: &[f32; N],
        wide: Option<Wide>,
    ) -> [f32; N] {
        let mut x = [0.0f32; N];
        let mut y = [0.0f32; N];
        for k in 0..N {
            x[k] = self.coord(tau_d_back[k]);
            y[k] = self.coord(tau_d_front[k]);
        }
        let (i, fx) = cells(&x, self.last_cell);
        let (j, fy) = cells(&y, self.last_cell);
        // The four nodes of each lane's cell. Cells are at most
        // `last_cell = n - 2` on both axes, so the last node read is at
        // most `n^2 - 1`. Each lane's nodes come through one slice of the
        // cell's two rows (one bound check per lane, in a plain loop that
        // inlines). The start is computed in u32 (`n^2` values fit, see
        // `PsiTable::build`), so that its sum with `n + 2` cannot overflow
        // the index: the check is the end against the length alone.
        let row = self.size as u32;
        let (n, span) = (row as usize, row as usize + 2);
        let mut corner = [0u32; N];
        for k in 0..N {
            corner[k] = j[k].wrapping_mul(row).wrapping_add(i[k]);
        }
        // The nodes lane by lane: `near` the cell's lower row, `far` its
        // upper one.
        let mut nodes = [[0.0f32; N]; 4];
        if !self.gather_nodes(&corner, row, &mut nodes, wide) {
            for k in 0..N {
                let base = corner[k] as usize;
                let rows = &self.values[base..base + span];
                [nodes[0][k], nodes[1][k]] = [rows[0], rows[1]];
                [nodes[2][k], nodes[3][k]] = [rows[n], rows[n + 1]];
            }
        }
        let mut out = [0.0f32; N];
        for k in 0..N {
            let near = [nodes[0][k], nodes[1][k]];
            let far = [nodes[2][k], nodes[3][k]];
            out[k] = bilinear_in_cell(near, far, fx[k], fy[k]);
        }
        out
    }

    /// The nodes of the cells at `corner` in rows of `row` values (see
    /// [`PsiTable::lookup_lanes`]), eight lanes to an AVX2 gather where the
    /// caller holds the token; false where they are left to the caller.
    #[inline(always)]
    fn gather_nodes<const N: usize>(
        &self,
        corner: &[u32; N],
        row: u32,
        nodes: &mut [[f32; N]; 4],
        wide: Option<Wide>,
    ) -> bool {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = wide
            && N.is_multiple_of(8)
        {
            for q in 0..N / 8 {
                let lanes: &[u32; 8] = corner[8 * q..8 * q + 8].try_into().expect("eight lanes");
                let Some(cell) = avx2.gather_cells(&self.values, lanes, row) else {
                    return false;
                };
                for (node, values) in nodes.iter_mut().zip(cell) {
                    node[8 * q..8 * q + 8].copy_from_slice(&values);
                }
            }
            return true;
        }
        let _ = (corner, row, nodes, wide);
        false
    }

    /// Bilinear lookup by `(gamma_b, gamma_f)` in `[0, 1]`.
    /// The bilinear and nearest lookups at `(gamma_back, gamma_front)` and
    /// Psi there in f64 (what `tetray psi` prints).
    pub fn at_gamma(&self, gamma_back: f32, gamma_front: f32) -> PsiAt {
        let (tau_b_d, tau_f_d) = (tau_d_of(gamma_back), tau_d_of(gamma_front));
        PsiAt {
            tau_b_d,
            tau_f_d,
            bilinear: self.lookup_gamma(gamma_back, gamma_front),
            nearest: self.lookup_gamma_nearest(gamma_back, gamma_front),
            exact: psi(tau_b_d, tau_f_d),
        }
    }

    pub fn lookup_gamma(&self, gamma_back: f32, gamma_front: f32) -> f32 {
        self.bilinear(
            self.spacing.coord_of_gamma(gamma_back),
            self.spacing.coord_of_gamma(gamma_front),
        )
    }

    /// Nearest-node lookup by `(gamma_b, gamma_f)` (for studying the table
    /// error, dissertation fig. 5.4).
    pub fn lookup_gamma_nearest(&self, gamma_back: f32, gamma_front: f32) -> f32 {
        let last = (self.size - 1) as f32;
        let index = |g: f32| {
            let u = self.spacing.coord_of_gamma(g.clamp(0.0, 1.0));
            ((u * last).round() as usize).min(self.size - 1)
        };
        self.values[index(gamma_front) * self.size + index(gamma_back)]
    }

    /// Bilinear interpolation at table coordinates `(u_b, u_f)` in `[0, 1]`.
    #[inline(always)]
    fn bilinear(&self, u_back: f32, u_front: f32) -> f32 {
        // A NaN coordinate passes through the clamp and gives NaN.
        let x = u_back.clamp(0.0, 1.0) * self.last;
        let y = u_front.clamp(0.0, 1.0) * self.last;
        self.interpolate(x, y)
    }

    /// Bilinear interpolation at node coordinates `(x, y)` in
    /// `[0, size - 1]`.
    #[inline(always)]
    fn interpolate(&self, x: f32, y: f32) -> f32 {
        let n = self.size;
        let (i, fx) = cell(x, self.last_cell);
        let (j, fy) = cell(y, self.last_cell);
        let base = j as usize * n + i as usize;
        let (Some(near), Some(far)) = (
            self.values.get(base..base + 2),
            self.values.get(base + n..base + n + 2),
        ) else {
            return f32::NAN;
        };
        bilinear_in_cell([near[0], near[1]], [far[0], far[1]], fx, fy)
    }
}

/// `1.5 * 2^23`: in `[2^23, 2^24)` f32 values are spaced by 1, so adding it
/// rounds to an integer that the low bits of the sum hold.
const ROUNDER: f32 = 12_582_912.0;

/// The cell `i <= last_cell` holding table coordinate `x >= 0` and the
/// position `x - i` in it, without a float-to-int conversion: `x - 0.5`
/// rounded to the nearest integer is `floor(x)` (or `x - 1` at a tie, when
/// the position is 1: bilinear interpolation is continuous, so either cell
/// gives the same value). NaN lands in some cell with a NaN position.
#[inline(always)]
fn cell(x: f32, last_cell: u32) -> (u32, f32) {
    let rounded = (x - 0.5) + ROUNDER;
    let i = rounded.to_bits().wrapping_sub(ROUNDER.to_bits());
    let i = i.min(last_cell);
    // A cell index is far below 2^31: converted as signed, one instruction
    // (an unsigned conversion takes five in vector lanes), the same value.
    (i, x - i as i32 as f32)
}

/// [`cell`] of each lane.
#[inline(always)]
fn cells<const N: usize>(x: &[f32; N], last_cell: u32) -> ([u32; N], [f32; N]) {
    let mut i = [0u32; N];
    let mut fraction = [0.0f32; N];
    for (k, &x) in x.iter().enumerate() {
        (i[k], fraction[k]) = cell(x, last_cell);
    }
    (i, fraction)
}

/// The value at position `(fx, fy)` in a cell whose nodes are `near` (the
/// lower row) and `far`.
#[inline(always)]
fn bilinear_in_cell(near: [f32; 2], far: [f32; 2], fx: f32, fy: f32) -> f32 {
    let bottom = near[0] + (near[1] - near[0]) * fx;
    let top = far[0] + (far[1] - far[0]) * fx;
    bottom + (top - bottom) * fy
}

/// Inputs for tests of the lookups: `tau D` of zero, tiny, moderate, huge,
/// infinite and NaN, then `count` non-negative finite values up to about
/// 2^7 from an xorshift generator started at `seed`.
#[cfg(test)]
pub(crate) fn test_tau_d(seed: u32, count: usize) -> Vec<f32> {
    let mut values = vec![
        0.0,
        1e-30,
        1e-7,
        1e-6,
        0.5,
        1.0,
        3.0,
        87.0,
        200.0,
        1e3,
        1e30,
        f32::INFINITY,
        f32::NAN,
    ];
    let mut state = seed;
    for _ in 0..count {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        values.push(f32::from_bits(state % 0x4300_0000));
    }
    values
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lane_parallel_lookup_gives_the_scalar_bits() {
        // The lookup computes both coordinates in SIMD lanes; it must give
        // what the scalar coordinate and clamp give, to the bit, including
        // zero, infinity and NaN.
        let values = test_tau_d(0x9e37_79b9, 2000);
        for spacing in [GammaSpacing::Uniform, GammaSpacing::Quadratic] {
            let table = PsiTable::build(64, spacing).expect("table");
            for (i, &a) in values.iter().enumerate() {
                let b = values[(i * 7 + 3) % values.len()];
                let lanes = table.lookup(a, b);
                let scalar = table.bilinear(spacing.coord_of_tau_d(a), spacing.coord_of_tau_d(b));
                assert_eq!(
                    lanes.to_bits(),
                    scalar.to_bits(),
                    "{spacing:?} at ({a}, {b})"
                );
            }
            // Several segments at once: each lane the single lookup's bits.
            for (k, back) in values.chunks_exact(8).enumerate() {
                let back: [f32; 8] = back.try_into().expect("8 lanes");
                let front = std::array::from_fn(|i| values[(k * 13 + i * 5 + 1) % values.len()]);
                for wide in [None, tetray_wide::token(true)] {
                    let lanes = tetray_wide::run(true, || table.lookup_lanes(&back, &front, wide));
                    for i in 0..8 {
                        let single = table.lookup(back[i], front[i]);
                        assert_eq!(lanes[i].to_bits(), single.to_bits(), "{spacing:?} lane {i}");
                    }
                }
            }
        }
    }
}
