//! Structured (i, j, k) grids as the VTK formats describe them, turned into
//! the cells of a [`CellGrid`]: extents, image and rectilinear point
//! positions, and one VTK hexahedron per grid cell.
//!
//! Point `(i, j, k)` of an `ni x nj x nk` grid has index `i + ni (j + nj k)`
//! (VTK's order, i fastest), and so does cell `(i, j, k)` of the
//! `(ni - 1) x (nj - 1) x (nk - 1)` cells. The hexahedra go to `assemble`,
//! whose splitter cuts every quadrilateral face through its smallest point
//! index (`split.rs`), so neighbouring hexahedra conform. A flat grid (one
//! point along an axis) gives quadrilaterals, lines or a vertex: no volume
//! cell, which the readers report.

use super::CellError;
use super::grid::CellGrid;

/// VTK cell type ids used here (vtkCellType.h).
const VTK_VERTEX: i64 = 1;
const VTK_LINE: i64 = 3;
const VTK_QUAD: i64 = 9;
const VTK_HEXAHEDRON: i64 = 12;

/// Points along each axis of an extent: 0 where it ends before it starts
/// (a file's DIMENSIONS of 0), and no overflow for any i64 bounds (a
/// count too large to index is [`point_count`]'s error).
pub fn extent_dims(extent: &[i64; 6]) -> [usize; 3] {
    [0, 1, 2].map(|a| {
        let points = extent[2 * a + 1]
            .saturating_sub(extent[2 * a])
            .saturating_add(1);
        usize::try_from(points).unwrap_or(0)
    })
}

/// Checks that a grid of `dims` points can be indexed (u32 points, no
/// overflow) and returns the point count.
pub fn point_count(dims: [usize; 3], file: &str, section: &str) -> Result<usize, CellError> {
    dims.iter()
        .try_fold(1usize, |n, &d| n.checked_mul(d))
        .filter(|&n| u32::try_from(n).is_ok())
        .ok_or_else(|| CellError::Unsupported {
            file: file.into(),
            section: section.into(),
            what: "grid size (tetrahedra index points with u32)",
            value: format!("{} x {} x {}", dims[0], dims[1], dims[2]),
        })
}

/// The cells of a grid of `dims` points: one per hexahedron, or per
/// quadrilateral / line / vertex of a flat grid.
pub fn cell_count(dims: [usize; 3]) -> usize {
    let cells: Vec<usize> = dims.iter().filter(|&&d| d > 1).map(|&d| d - 1).collect();
    if dims.contains(&0) {
        0
    } else {
        cells.iter().product()
    }
}

/// Appends the cells of a grid of `dims` points (already checked with
/// [`point_count`]) to `grid`, indexing its points from 0.
pub fn add_cells(dims: [usize; 3], grid: &mut CellGrid) {
    let axes: Vec<usize> = (0..3).filter(|&a| dims[a] > 1).collect();
    let (type_id, corners): (i64, &[[usize; 3]]) = match axes.len() {
        3 => (
            VTK_HEXAHEDRON,
            &[
                [0, 0, 0],
                [1, 0, 0],
                [1, 1, 0],
                [0, 1, 0],
                [0, 0, 1],
                [1, 0, 1],
                [1, 1, 1],
                [0, 1, 1],
            ],
        ),
        2 => (VTK_QUAD, &[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
        1 => (VTK_LINE, &[[0, 0, 0], [1, 0, 0]]),
        _ => (VTK_VERTEX, &[[0, 0, 0]]),
    };
    let n = cell_count(dims);
    let cell_dims = dims.map(|d| d.saturating_sub(1).max(1));
    let [ni, nj, _] = dims;
    if grid.offsets.is_empty() {
        grid.offsets.push(0);
    }
    grid.connectivity.reserve(n * corners.len());
    for c in 0..n {
        let at = [
            c % cell_dims[0],
            (c / cell_dims[0]) % cell_dims[1],
            c / (cell_dims[0] * cell_dims[1]),
        ];
        for local in corners {
            // Local corner axes 0, 1, 2 map to the grid's non-flat axes.
            let mut p = at;
            for (slot, &axis) in axes.iter().enumerate() {
                p[axis] += local[slot];
            }
            grid.connectivity
                .push((p[0] + ni * (p[1] + nj * p[2])) as i64);
        }
        grid.offsets.push(grid.connectivity.len());
    }
    grid.types.extend(std::iter::repeat_n(type_id, n));
}

/// Point positions of an image (`vtkImageData`): `origin + direction *
/// (index * spacing)`, with `index` the absolute (i, j, k) of the extent.
pub fn image_points(
    extent: &[i64; 6],
    origin: [f64; 3],
    spacing: [f64; 3],
    direction: [f64; 9],
) -> Vec<f64> {
    let dims = extent_dims(extent);
    let mut points = Vec::with_capacity(dims.iter().product::<usize>() * 3);
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                let index = [i, j, k];
                let local: [f64; 3] =
                    [0, 1, 2].map(|a| (extent[2 * a] + index[a] as i64) as f64 * spacing[a]);
                for row in 0..3 {
                    let d = &direction[3 * row..3 * row + 3];
                    points.push(origin[row] + d[0] * local[0] + d[1] * local[1] + d[2] * local[2]);
                }
            }
        }
    }
    points
}

/// Point positions of a rectilinear grid: every (x, y, z) of the three
/// coordinate lists, x fastest.
pub fn rectilinear_points(x: &[f64], y: &[f64], z: &[f64]) -> Vec<f64> {
    let mut points = Vec::with_capacity(x.len() * y.len() * z.len() * 3);
    for &pz in z {
        for &py in y {
            for &px in x {
                points.extend_from_slice(&[px, py, pz]);
            }
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hexahedra_of_a_small_grid() {
        let mut grid = CellGrid::default();
        add_cells([3, 2, 2], &mut grid);
        assert_eq!(grid.types, vec![12, 12]);
        assert_eq!(grid.offsets, vec![0, 8, 16]);
        assert_eq!(&grid.connectivity[..8], &[0, 1, 4, 3, 6, 7, 10, 9]);
        assert_eq!(&grid.connectivity[8..], &[1, 2, 5, 4, 7, 8, 11, 10]);
    }

    #[test]
    fn flat_grids_give_surface_cells() {
        let mut grid = CellGrid::default();
        add_cells([3, 1, 2], &mut grid);
        assert_eq!(grid.types, vec![9, 9]);
        // x and z vary: corners (i, k) -> i + 3 k.
        assert_eq!(&grid.connectivity[..4], &[0, 1, 4, 3]);
        assert_eq!(cell_count([1, 1, 1]), 1);
        assert_eq!(cell_count([4, 1, 1]), 3);
    }
}
