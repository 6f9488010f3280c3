//! PLOT3D data as stored: the structured arrays of a grid file and its
//! solution, before any tetrahedra. What the reader parses, the writer
//! writes and a refinement interpolates.

use std::path::Path;

use glam::Vec3;
use rayon::prelude::*;

use super::layout::{Kind, detect};
use crate::IoError;

/// A single structured grid with its optional IBLANK and solution; point
/// `(i, j, k)` has index `i + ni (j + nj k)` in every array.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot3dGrid {
    /// Points along i, j, k.
    pub dims: [usize; 3],
    /// All x, all y, all z.
    pub xyz: [Vec<f32>; 3],
    /// One flag per point: 0 blanked (no valid data), 1 normal, negative:
    /// the number of another grid it is interpolated from.
    pub iblank: Option<Vec<i32>>,
    pub solution: Option<Plot3dSolution>,
}

/// The q file's content.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot3dSolution {
    /// fsmach, alpha, re, time.
    pub conditions: [f32; 4],
    /// Density, x/y/z momentum, stagnation energy: one value per point each.
    pub q: [Vec<f32>; 5],
}

/// Values of a structured PLOT3D grid and its solution point by point:
/// what the writer and the split counts need. A grid in memory is one; a
/// refinement computed on the fly is another, so neither has to be
/// materialised to be written.
pub trait Plot3dSource: Sync {
    /// Points along i, j, k.
    fn dims(&self) -> [usize; 3];
    /// Coordinate `axis` (0 x, 1 y, 2 z) of point `p`.
    fn coordinate(&self, axis: usize, p: usize) -> f32;
    /// Whether there is an IBLANK array.
    fn has_iblank(&self) -> bool;
    /// IBLANK of point `p` (1 without an IBLANK array).
    fn iblank(&self, p: usize) -> i32;
    /// fsmach, alpha, re, time; `None` when there is no solution.
    fn conditions(&self) -> Option<[f32; 4]>;
    /// Solution array `q` (0 density, 1..=3 momentum, 4 stagnation energy)
    /// at point `p`; only called when [`Plot3dSource::conditions`] is `Some`.
    fn solution(&self, q: usize, p: usize) -> f32;

    /// Number of points.
    fn point_count(&self) -> usize {
        self.dims().iter().product()
    }

    /// Position of point `p`.
    fn point(&self, p: usize) -> Vec3 {
        Vec3::new(
            self.coordinate(0, p),
            self.coordinate(1, p),
            self.coordinate(2, p),
        )
    }
}

impl Plot3dSource for Plot3dGrid {
    fn dims(&self) -> [usize; 3] {
        self.dims
    }

    fn coordinate(&self, axis: usize, p: usize) -> f32 {
        self.xyz[axis][p]
    }

    fn has_iblank(&self) -> bool {
        self.iblank.is_some()
    }

    fn iblank(&self, p: usize) -> i32 {
        self.iblank.as_ref().map_or(1, |b| b[p])
    }

    fn conditions(&self) -> Option<[f32; 4]> {
        self.solution.as_ref().map(|s| s.conditions)
    }

    fn solution(&self, q: usize, p: usize) -> f32 {
        self.solution.as_ref().map_or(0.0, |s| s.q[q][p])
    }
}

impl Plot3dGrid {
    /// Every value of `source`, held in memory (to refine a refinement).
    pub fn from_source(source: &impl Plot3dSource) -> Plot3dGrid {
        let n = source.point_count();
        let array = |f: &(dyn Fn(usize) -> f32 + Sync)| -> Vec<f32> {
            (0..n).into_par_iter().map(f).collect()
        };
        Plot3dGrid {
            dims: source.dims(),
            xyz: [0, 1, 2].map(|axis| array(&|p| source.coordinate(axis, p))),
            iblank: source
                .has_iblank()
                .then(|| (0..n).into_par_iter().map(|p| source.iblank(p)).collect()),
            solution: source.conditions().map(|conditions| Plot3dSolution {
                conditions,
                q: [0, 1, 2, 3, 4].map(|q| array(&|p| source.solution(q, p))),
            }),
        }
    }
}

/// Reads a grid file and optionally its solution file as structured arrays
/// (any layout the mesh reader accepts).
///
/// # Errors
/// [`IoError::Io`] when a file cannot be read; the errors of
/// [`read_plot3d_grid_bytes`].
pub fn read_plot3d_grid_files(xyz: &Path, q: Option<&Path>) -> Result<Plot3dGrid, IoError> {
    let xyz_bytes = super::read_file(xyz)?;
    let q_bytes = q.map(super::read_file).transpose()?;
    let q_name = q.map_or_else(String::new, |q| q.display().to_string());
    let parsed = parse(
        &xyz_bytes,
        q_bytes.as_deref(),
        &xyz.display().to_string(),
        &q_name,
    )?;
    Ok(parsed.grid)
}

/// Reads a grid and optionally its solution held in memory as structured
/// arrays; `name` is used in messages (the solution as "`name` (q)").
///
/// # Errors
/// As [`crate::read_plot3d_bytes`].
pub fn read_plot3d_grid_bytes(
    xyz: &[u8],
    q: Option<&[u8]>,
    name: &str,
) -> Result<Plot3dGrid, IoError> {
    Ok(parse(xyz, q, name, &format!("{name} (q)"))?.grid)
}

/// A parsed pair of files, with what was tolerated.
pub(crate) struct Parsed {
    pub grid: Plot3dGrid,
    /// Layout notes (trailing bytes), as sentences.
    pub warnings: Vec<String>,
}

/// Decides the layouts and copies the arrays out.
pub(crate) fn parse(
    xyz: &[u8],
    q: Option<&[u8]>,
    xyz_name: &str,
    q_name: &str,
) -> Result<Parsed, IoError> {
    let layout = detect(xyz, xyz_name, Kind::Grid)?;
    let dims = layout.dims;
    let n: usize = dims.iter().product();
    let mut warnings = Vec::new();
    if layout.trailing > 0 {
        warnings.push(format!(
            "{xyz_name}: {} bytes after the grid data were ignored ({})",
            layout.trailing, layout.description
        ));
    }
    let coordinate = |axis: usize| layout.endian.f32s(xyz, layout.data + 4 * axis * n, n);
    let iblank = layout
        .iblank
        .then(|| layout.endian.i32s(xyz, layout.data + 12 * n, n));
    let solution = match q {
        Some(q) => {
            let solution = detect(q, q_name, Kind::Solution)?;
            if solution.dims != dims {
                return Err(IoError::Plot3dDimsMismatch {
                    xyz_file: xyz_name.to_string(),
                    q_file: q_name.to_string(),
                    xyz_dims: dims,
                    q_dims: solution.dims,
                });
            }
            if solution.trailing > 0 {
                warnings.push(format!(
                    "{q_name}: {} bytes after the solution data were ignored",
                    solution.trailing
                ));
            }
            let c = solution.endian.f32s(q, solution.conditions, 4);
            Some(Plot3dSolution {
                conditions: [c[0], c[1], c[2], c[3]],
                q: [0, 1, 2, 3, 4].map(|a| solution.endian.f32s(q, solution.data + 4 * a * n, n)),
            })
        }
        None => None,
    };
    Ok(Parsed {
        grid: Plot3dGrid {
            dims,
            xyz: [0, 1, 2].map(coordinate),
            iblank,
            solution,
        },
        warnings,
    })
}
