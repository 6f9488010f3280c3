//! Piecewise polynomials fitted once to an accurate but slow function:
//! on each of `N` equal intervals, the function's Chebyshev series cut
//! after `D` terms (near-minimax: its error is within a small factor of
//! the best polynomial's), stored in monomial form in the interval's own
//! variable `u` in `[-1, 1]`, so that an evaluation is one Horner sum of
//! `D - 1` multiply-adds.

use std::f64::consts::PI;

use crate::fastmath::horner;

/// `f` on `[start, start + N / per_unit)` as `N` polynomials of degree
/// `D - 1`.
pub struct Piecewise<const D: usize, const N: usize> {
    start: f64,
    per_unit: f64,
    /// Monomial coefficients in `u` per interval, constant term first.
    coefficients: [[f64; D]; N],
}

impl<const D: usize, const N: usize> Piecewise<D, N> {
    /// Fits `f` on `N` intervals of width `1 / per_unit` from `start` on.
    ///
    /// Each interval's polynomial is the Chebyshev series of `f` from its
    /// values at `2 D` Chebyshev nodes, cut after `D` terms. Its
    /// coefficients are sums of `2 D` products that cancel to the small
    /// high-order terms, and the Chebyshev polynomials at the nodes carry
    /// rounding of their own (a few units in the last place of `f`, `D`
    /// of them adding up); so the fit is refined: the series of what the
    /// polynomial misses at the nodes is added to it, twice, each time
    /// with errors relative to that small remainder.
    pub fn fit(f: impl Fn(f64) -> f64, start: f64, per_unit: f64) -> Self {
        let m = 2 * D;
        let nodes: Vec<f64> = (0..m)
            .map(|k| (PI * (k as f64 + 0.5) / m as f64).cos())
            .collect();
        // T_j(u_k) for j < D by the three-term recurrence.
        let basis: Vec<[f64; D]> = nodes
            .iter()
            .map(|&u| {
                let mut t = [0.0; D];
                t[0] = 1.0;
                if D > 1 {
                    t[1] = u;
                }
                for j in 2..D {
                    let (older, previous) = (t[j - 2], t[j - 1]);
                    t[j] = 2.0 * u * previous - older;
                }
                t
            })
            .collect();
        let chebyshev = chebyshev_monomials::<D>();
        // The monomial coefficients of the cut series of `values`.
        let project = |values: &[f64]| {
            let mut monomial = [0.0; D];
            for (j, t_j) in chebyshev.iter().enumerate() {
                let sum: f64 = values.iter().zip(&basis).map(|(v, t)| v * t[j]).sum();
                let a = sum * if j == 0 { 1.0 } else { 2.0 } / m as f64;
                for (c, &t) in monomial.iter_mut().zip(t_j) {
                    *c += a * t;
                }
            }
            monomial
        };
        let coefficients = std::array::from_fn(|i| {
            let half = 0.5 / per_unit;
            let mid = start + (i as f64 + 0.5) / per_unit;
            let values: Vec<f64> = nodes.iter().map(|&u| f(mid + half * u)).collect();
            let mut c = project(&values);
            for _ in 0..2 {
                let missed: Vec<f64> = values
                    .iter()
                    .zip(&nodes)
                    .map(|(&v, &u)| v - horner(&c, u))
                    .collect();
                for (c, d) in c.iter_mut().zip(project(&missed)) {
                    *c += d;
                }
            }
            c
        });
        Piecewise {
            start,
            per_unit,
            coefficients,
        }
    }

    /// The end of the fitted range.
    pub fn end(&self) -> f64 {
        self.start + N as f64 / self.per_unit
    }

    /// The fitted polynomial at `x`, for `x` in `[start, end)` (outside,
    /// the first or last interval's polynomial, extrapolated; NaN gives
    /// the first).
    #[inline(always)]
    pub fn eval(&self, x: f64) -> f64 {
        let t = (x - self.start) * self.per_unit;
        // `as` saturates: negative and NaN give 0.
        let i = (t as usize).min(N - 1);
        let u = 2.0 * (t - i as f64) - 1.0;
        horner(&self.coefficients[i], u)
    }
}

/// The monomial coefficients of the Chebyshev polynomials `T_0` to
/// `T_{D-1}` (integers, exact in f64 for `D <= 53`), by
/// `T_{j+1} = 2 u T_j - T_{j-1}`.
fn chebyshev_monomials<const D: usize>() -> [[f64; D]; D] {
    let mut t = [[0.0; D]; D];
    t[0][0] = 1.0;
    if D > 1 {
        t[1][1] = 1.0;
    }
    for j in 1..D.saturating_sub(1) {
        for m in 0..D {
            let shifted = if m > 0 { 2.0 * t[j][m - 1] } else { 0.0 };
            t[j + 1][m] = shifted - t[j - 1][m];
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chebyshev_polynomials_in_monomials() {
        let t = chebyshev_monomials::<6>();
        // T_5(u) = 16 u^5 - 20 u^3 + 5 u.
        assert_eq!(t[5], [0.0, 5.0, 0.0, -20.0, 0.0, 16.0]);
        // T_j(cos theta) = cos(j theta).
        for (j, t_j) in t.iter().enumerate() {
            let theta: f64 = 0.7;
            let u = theta.cos();
            let value: f64 = t_j.iter().rev().fold(0.0, |s, &c| s * u + c);
            assert!((value - (j as f64 * theta).cos()).abs() < 1e-14);
        }
    }

    /// A polynomial of degree below `D` is reproduced to rounding, and a
    /// smooth function to the interpolation's error, including at the
    /// intervals' ends.
    #[test]
    fn reproduces_polynomials_and_fits_smooth_functions() {
        let cubic = |x: f64| 2.0 - 3.0 * x + 0.5 * x * x * x;
        let fit = Piecewise::<6, 5>::fit(cubic, -1.0, 2.0);
        assert_eq!(fit.end(), 1.5);
        for i in 0..=1000 {
            let x = -1.0 + 2.5 * f64::from(i) / 1000.0;
            let x = x.min(1.5 - 1e-12);
            assert!((fit.eval(x) - cubic(x)).abs() < 1e-14, "{x}");
        }
        // exp on intervals of width 1/4, degree 11: error below
        // (1/8)^12 / 12! / 2^11 relative, far under rounding.
        let exp = Piecewise::<12, 8>::fit(f64::exp, 0.0, 4.0);
        for i in 0..2000 {
            let x = 2.0 * f64::from(i) / 2000.0;
            let relative = (exp.eval(x) - x.exp()).abs() / x.exp();
            assert!(relative < 4e-16, "exp({x}): {relative:e}");
        }
    }
}
