//! Synthetic tetrahedral meshes with known geometry, for tests (exact
//! answers: chord lengths through boxes) and for generating example data.
//!
//! Every builder returns a positively oriented, conforming mesh without
//! fields; attach point scalars with [`add_field`].

use crate::{ScalarField, TetMesh};
use glam::{DVec3, Vec3};

/// Why a synthetic mesh could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BuildError {
    #[error("box min {min:?} max {max:?} must be finite with min < max on every axis")]
    BadBox { min: [f32; 3], max: [f32; 3] },
    #[error("grid needs at least one cell per axis, got {0:?}")]
    NoCells([u32; 3]),
    #[error("grid of {0:?} cells is too large for u32 point indices")]
    TooLarge([u32; 3]),
    #[error("hole cells {lo:?}..{hi:?} are empty or outside the {cells:?} grid")]
    BadHole {
        lo: [u32; 3],
        hi: [u32; 3],
        cells: [u32; 3],
    },
    #[error("jitter {0} must be in [0, 0.25) cell widths")]
    BadJitter(f32),
    #[error("tetrahedron {tet} is degenerate (volume {volume}) after jittering; lower the jitter")]
    DegenerateTet { tet: usize, volume: f64 },
    #[error("meshes to merge have different fields")]
    FieldMismatch,
}

/// How each hexahedral cell of a grid is split into tetrahedra.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CellSplit {
    /// 5 tetrahedra, diagonal parity alternating cell to cell (the split of
    /// the dissertation's PLOT3D meshes).
    #[default]
    Five,
    /// 6 tetrahedra around the main diagonal of every cell (Kuhn split).
    Six,
}

/// A point scalar field defined in closed form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ScalarSpec {
    Constant(f32),
    /// `offset + gradient . p`: linear, so exactly represented by linear
    /// interpolation on any tetrahedralization.
    Linear {
        offset: f32,
        gradient: Vec3,
    },
}

impl ScalarSpec {
    /// The value at `p`, in f64 for reference computations.
    pub fn eval(&self, p: DVec3) -> f64 {
        match *self {
            ScalarSpec::Constant(c) => f64::from(c),
            ScalarSpec::Linear { offset, gradient } => {
                f64::from(offset) + gradient.as_dvec3().dot(p)
            }
        }
    }
}

/// Adds (or replaces) the field `name` sampled from `spec` at every point.
pub fn add_field(mesh: &mut TetMesh, name: &str, spec: ScalarSpec) {
    let values = mesh
        .points
        .iter()
        .map(|p| spec.eval(p.as_dvec3()) as f32)
        .collect();
    mesh.fields.retain(|f| f.name != name);
    mesh.fields.push(ScalarField {
        name: name.to_string(),
        values,
    });
}

/// The box `[min, max]` split into `cells` hexahedra, each split into
/// tetrahedra by `split`.
pub fn box_grid(
    min: Vec3,
    max: Vec3,
    cells: [u32; 3],
    split: CellSplit,
) -> Result<TetMesh, BuildError> {
    let grid = Grid::new(min, max, cells)?;
    grid.build(split, |_| true, |_| Vec3::ZERO)
}

/// A box grid minus the cells `hole_lo..hole_hi` (per axis, half open): with
/// the hole inside, rays leave the mesh into the hole and enter it again.
pub fn hollow_box(
    min: Vec3,
    max: Vec3,
    cells: [u32; 3],
    hole_lo: [u32; 3],
    hole_hi: [u32; 3],
    split: CellSplit,
) -> Result<TetMesh, BuildError> {
    let grid = Grid::new(min, max, cells)?;
    let valid = (0..3).all(|a| hole_lo[a] < hole_hi[a] && hole_hi[a] <= cells[a]);
    if !valid {
        return Err(BuildError::BadHole {
            lo: hole_lo,
            hi: hole_hi,
            cells,
        });
    }
    let in_hole = |c: [u32; 3]| (0..3).all(|a| hole_lo[a] <= c[a] && c[a] < hole_hi[a]);
    grid.build(split, |c| !in_hole(c), |_| Vec3::ZERO)
}

/// An irregular tetrahedralization of the box `[min, max]`: the grid points
/// are moved by up to `jitter` cell widths (pseudo-random from `seed`, so
/// deterministic), points on the box surface only within it, so the mesh
/// still fills the box exactly. Fails rather than return a degenerate
/// tetrahedron.
pub fn jittered_box(
    min: Vec3,
    max: Vec3,
    cells: [u32; 3],
    jitter: f32,
    seed: u64,
    split: CellSplit,
) -> Result<TetMesh, BuildError> {
    if !(0.0..0.25).contains(&jitter) {
        return Err(BuildError::BadJitter(jitter));
    }
    let grid = Grid::new(min, max, cells)?;
    let cell = grid.cell_size();
    let mut rng = SplitMix64(seed);
    let offset = |c: [u32; 3]| {
        let mut d = Vec3::ZERO;
        for a in 0..3 {
            let r = rng.next_unit() * 2.0 - 1.0;
            // Surface points slide only along the surface.
            if c[a] > 0 && c[a] < cells[a] {
                d[a] = r * jitter * cell[a];
            }
        }
        d
    };
    grid.build(split, |_| true, offset)
}

/// Two box grids in one mesh (they must not overlap): rays cross a gap.
pub fn two_boxes(
    a: (Vec3, Vec3, [u32; 3]),
    b: (Vec3, Vec3, [u32; 3]),
    split: CellSplit,
) -> Result<TetMesh, BuildError> {
    let first = box_grid(a.0, a.1, a.2, split)?;
    let second = box_grid(b.0, b.1, b.2, split)?;
    merge(first, second)
}

/// Concatenates two meshes (no points are shared; fields must match by name
/// and order).
pub fn merge(mut a: TetMesh, b: TetMesh) -> Result<TetMesh, BuildError> {
    let same_fields = a.fields.len() == b.fields.len()
        && a.fields
            .iter()
            .zip(&b.fields)
            .all(|(x, y)| x.name == y.name);
    if !same_fields {
        return Err(BuildError::FieldMismatch);
    }
    let base = u32::try_from(a.points.len()).map_err(|_| BuildError::TooLarge([0; 3]))?;
    a.points.extend_from_slice(&b.points);
    if u32::try_from(a.points.len()).is_err() {
        return Err(BuildError::TooLarge([0; 3]));
    }
    a.tets.extend(b.tets.iter().map(|t| t.map(|v| v + base)));
    for (fa, fb) in a.fields.iter_mut().zip(b.fields) {
        fa.values.extend(fb.values);
    }
    Ok(a)
}

/// Corners of a cell as `dx + 2 dy + 4 dz`.
const FIVE_EVEN: [[usize; 4]; 5] = [
    [0, 3, 5, 6],
    [1, 0, 3, 5],
    [2, 0, 3, 6],
    [4, 0, 5, 6],
    [7, 3, 5, 6],
];
const FIVE_ODD: [[usize; 4]; 5] = [
    [1, 2, 4, 7],
    [0, 1, 2, 4],
    [3, 1, 2, 7],
    [5, 1, 4, 7],
    [6, 2, 4, 7],
];
/// One tetrahedron per axis order: 0 -> e_a -> e_a + e_b -> 7.
const SIX: [[usize; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 1, 5, 7],
    [0, 2, 3, 7],
    [0, 2, 6, 7],
    [0, 4, 5, 7],
    [0, 4, 6, 7],
];

struct Grid {
    min: Vec3,
    max: Vec3,
    cells: [u32; 3],
}

impl Grid {
    fn new(min: Vec3, max: Vec3, cells: [u32; 3]) -> Result<Grid, BuildError> {
        if !min.is_finite() || !max.is_finite() || !min.cmplt(max).all() {
            return Err(BuildError::BadBox {
                min: min.to_array(),
                max: max.to_array(),
            });
        }
        if cells.contains(&0) {
            return Err(BuildError::NoCells(cells));
        }
        let points = cells
            .iter()
            .try_fold(1u64, |n, &c| n.checked_mul(u64::from(c) + 1));
        let tets = cells
            .iter()
            .try_fold(6u64, |n, &c| n.checked_mul(u64::from(c)));
        match (points, tets) {
            (Some(p), Some(t)) if p < u64::from(u32::MAX) && t < u64::from(u32::MAX) => {}
            _ => return Err(BuildError::TooLarge(cells)),
        }
        Ok(Grid { min, max, cells })
    }

    fn cell_size(&self) -> Vec3 {
        (self.max - self.min)
            / Vec3::new(
                self.cells[0] as f32,
                self.cells[1] as f32,
                self.cells[2] as f32,
            )
    }

    fn point_index(&self, c: [u32; 3]) -> u32 {
        let [nx, ny, _] = self.cells.map(|n| n + 1);
        c[0] + nx * (c[1] + ny * c[2])
    }

    /// Grid point `c`: interpolated so that the last point is exactly `max`.
    fn point(&self, c: [u32; 3]) -> Vec3 {
        let mut p = Vec3::ZERO;
        for a in 0..3 {
            let f = c[a] as f32 / self.cells[a] as f32;
            p[a] = if c[a] == self.cells[a] {
                self.max[a]
            } else {
                self.min[a] + (self.max[a] - self.min[a]) * f
            };
        }
        p
    }

    fn build(
        &self,
        split: CellSplit,
        keep: impl Fn([u32; 3]) -> bool,
        mut offset: impl FnMut([u32; 3]) -> Vec3,
    ) -> Result<TetMesh, BuildError> {
        let [nx, ny, nz] = self.cells;
        let mut points = Vec::with_capacity(((nx + 1) * (ny + 1) * (nz + 1)) as usize);
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    points.push(self.point([i, j, k]) + offset([i, j, k]));
                }
            }
        }
        let mut tets = Vec::new();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    if !keep([i, j, k]) {
                        continue;
                    }
                    let corner = |c: usize| {
                        self.point_index([
                            i + (c & 1) as u32,
                            j + ((c >> 1) & 1) as u32,
                            k + ((c >> 2) & 1) as u32,
                        ])
                    };
                    let local: &[[usize; 4]] = match split {
                        CellSplit::Five if (i + j + k) % 2 == 0 => &FIVE_EVEN,
                        CellSplit::Five => &FIVE_ODD,
                        CellSplit::Six => &SIX,
                    };
                    for t in local {
                        tets.push(t.map(corner));
                    }
                }
            }
        }
        // A regular cell's smallest tetrahedron has 1/6 of its volume; a
        // jittered one below 1% of that is treated as degenerate.
        let cell = self.cell_size().as_dvec3();
        let min_volume = 0.01 * cell.x * cell.y * cell.z / 6.0;
        for (index, tet) in tets.iter_mut().enumerate() {
            let volume = signed_volume(&points, *tet);
            if volume.abs() < min_volume {
                return Err(BuildError::DegenerateTet { tet: index, volume });
            }
            if volume < 0.0 {
                tet.swap(2, 3);
            }
        }
        Ok(TetMesh {
            points,
            tets,
            fields: Vec::new(),
        })
    }
}

/// `(p1 - p0) . ((p2 - p0) x (p3 - p0)) / 6`, in f64.
fn signed_volume(points: &[Vec3], tet: [u32; 4]) -> f64 {
    let [p0, p1, p2, p3] = tet.map(|v| points[v as usize].as_dvec3());
    (p1 - p0).dot((p2 - p0).cross(p3 - p0)) / 6.0
}

/// A small deterministic generator (SplitMix64); tests need reproducible
/// meshes, not statistical quality.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn next_unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
}
