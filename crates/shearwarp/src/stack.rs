//! The grid seen along one principal axis: its slices copied so that every
//! scanline is contiguous (Lacroute keeps one copy per axis too), and the
//! run-length encoding of each cell row by empty-space class.

use rayon::prelude::*;

use crate::RegularGrid;
use crate::classify::Classifier;

/// A run of cells `start..end` of one row sharing `class` (0: may be
/// visible).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Run {
    pub start: u32,
    pub end: u32,
    pub class: u16,
}

/// Slices perpendicular to axis `c`: `x` along axis `a`, `y` along `b`.
#[derive(Debug, Clone)]
pub(crate) struct Stack {
    pub na: usize,
    pub nb: usize,
    /// `data[(k * nb + y) * na + x]`, `k` the slice along `c`.
    pub data: Vec<f32>,
    /// Runs of every cell row `(k, y)` (row `k * nb + y`), cells being the
    /// `x..=x+1` by `y..=y+1` points (clipped at the last point).
    runs: Vec<Run>,
    row_start: Vec<u32>,
}

/// The two other axes of principal axis `c`, in cyclic order.
pub(crate) fn axes_of(c: usize) -> [usize; 3] {
    [(c + 1) % 3, (c + 2) % 3, c]
}

impl Stack {
    pub fn build(grid: &RegularGrid, c: usize, classifier: &Classifier) -> Stack {
        let axes = axes_of(c);
        let dims = grid.dims();
        let [na, nb, nc] = axes.map(|a| dims[a]);
        let stride = [1, dims[0], dims[0] * dims[1]];
        let values = grid.values();
        let mut data = vec![0.0f32; na * nb * nc];
        data.par_chunks_mut(na * nb)
            .enumerate()
            .for_each(|(k, slice)| {
                for y in 0..nb {
                    for x in 0..na {
                        let index = x * stride[axes[0]] + y * stride[axes[1]] + k * stride[axes[2]];
                        slice[y * na + x] = values[index];
                    }
                }
            });
        let rows: Vec<Vec<Run>> = (0..nb * nc)
            .into_par_iter()
            .map(|row| {
                let (k, y) = (row / nb, row % nb);
                let y1 = (y + 1).min(nb - 1);
                let at = |x: usize, y: usize| data[(k * nb + y) * na + x];
                let mut runs: Vec<Run> = Vec::new();
                for x in 0..na {
                    let x1 = (x + 1).min(na - 1);
                    let v = [at(x, y), at(x1, y), at(x, y1), at(x1, y1)];
                    let lo = v.iter().copied().fold(f32::INFINITY, f32::min);
                    let hi = v.iter().copied().fold(f32::NEG_INFINITY, f32::max);
                    let class = classifier.class_of(lo, hi);
                    match runs.last_mut() {
                        Some(r) if r.class == class => r.end += 1,
                        _ => runs.push(Run {
                            start: x as u32,
                            end: x as u32 + 1,
                            class,
                        }),
                    }
                }
                runs
            })
            .collect();
        let mut row_start = Vec::with_capacity(rows.len() + 1);
        let mut runs = Vec::new();
        for r in rows {
            row_start.push(runs.len() as u32);
            runs.extend(r);
        }
        row_start.push(runs.len() as u32);
        Stack {
            na,
            nb,
            data,
            runs,
            row_start,
        }
    }

    /// The run holding cell `x` of row `(k, y)`.
    #[inline]
    pub fn run(&self, k: usize, y: usize, x: usize) -> Run {
        let row = k * self.nb + y;
        let runs = &self.runs[self.row_start[row] as usize..self.row_start[row + 1] as usize];
        let i = runs.partition_point(|r| (r.end as usize) <= x);
        runs[i.min(runs.len() - 1)]
    }
}
