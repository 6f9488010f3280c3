//! Some of a parallel file's pieces, for one process of a distributed
//! render: read, ghost cells dropped, welded among themselves, with their
//! points numbered in the whole file's order and stored relative to the
//! whole mesh's origin, so that their cells become exactly the tetrahedra
//! the whole file's would (hexahedra, wedges and pyramids are split by
//! comparing point numbers).

use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;
use tetray_mesh::cells::CellError;

use glam::DVec3;
use tetray_mesh::bounds_f64;
use tetray_mesh::cells::{CellGrid, assemble_at, drop_global_ids, weld};

use super::collection::{piece_paths, require_volume, serial_raw};
use super::{ReadOptions, VtkError, VtkRead};

/// The number of pieces a parallel file names (each must exist).
pub fn parallel_piece_count(path: &Path) -> Result<usize, VtkError> {
    Ok(piece_paths(path)?.len())
}

/// Pieces `pieces` of a parallel file, read and welded, not yet made
/// tetrahedra: [`PieceSubset::bounds`] lets the processes agree on the
/// whole mesh's origin first.
#[derive(Debug)]
pub struct PieceSubset {
    grid: CellGrid,
    name: String,
}

/// Reads pieces `pieces` of the parallel file `path`.
///
/// The pieces before them are read too, one at a time, keeping only the
/// numbers of the points they share with these: the whole file numbers a
/// point where it first appears, and the split of non-tetrahedral cells
/// depends on that order. Polyhedra (face streams) are not renumbered and
/// are refused.
pub fn read_piece_subset(path: &Path, pieces: Range<usize>) -> Result<PieceSubset, VtkError> {
    let name = path.display().to_string();
    let sources = piece_paths(path)?;
    if pieces.end > sources.len() {
        return Err(VtkError::Cell(CellError::Invalid {
            file: name,
            section: "<Piece>".into(),
            message: format!(
                "pieces {}..{} asked for, the file has {}",
                pieces.start,
                pieces.end,
                sources.len()
            ),
        }));
    }
    let grids = sources[pieces.clone()]
        .iter()
        .map(|p| serial_raw(p))
        .collect::<Result<Vec<_>, _>>()?;
    let mut grid = weld(grids, &name)?;
    grid.pieces.pieces = pieces.len();
    if !grid.polyhedron_faces.is_empty() {
        return Err(VtkError::Cell(CellError::Invalid {
            file: name,
            section: "polyhedra".into(),
            message: "a distributed render does not read polyhedra (type 42) from pieces".into(),
        }));
    }
    let key = |xyz: &[f64]| [0, 1, 2].map(|a| (xyz[a] + 0.0).to_bits());
    let index: HashMap<[u64; 3], usize> = grid
        .points
        .chunks_exact(3)
        .enumerate()
        .map(|(i, p)| (key(p), i))
        .collect();
    // Where each point first appears among the pieces before these.
    let mut earlier: Vec<Option<(usize, usize)>> = vec![None; index.len()];
    for (j, source) in sources[..pieces.start].iter().enumerate() {
        let before = serial_raw(source)?;
        for (i, p) in before.points.chunks_exact(3).enumerate() {
            let Some(&own) = index.get(&key(p)) else {
                continue;
            };
            if earlier[own].is_none() {
                earlier[own] = Some((j, i));
                // Welding keeps a shared point's values from the piece
                // where it first appears.
                take_values(&mut grid, own, &before, i);
            }
        }
    }
    renumber(&mut grid, &earlier);
    Ok(PieceSubset { grid, name })
}

/// Point `own` of `grid` takes the values of point `i` of `from` in every
/// point array both have.
fn take_values(grid: &mut CellGrid, own: usize, from: &CellGrid, i: usize) {
    for array in &mut grid.point_arrays {
        let k = array.components.max(1);
        let source = from
            .point_arrays
            .iter()
            .find(|a| a.name == array.name && a.components.max(1) == k);
        if let Some(source) = source
            && let (Some(to), Some(values)) = (
                array.values.get_mut(own * k..(own + 1) * k),
                source.values.get(i * k..(i + 1) * k),
            )
        {
            to.copy_from_slice(values);
        }
    }
}

/// Puts the points seen in earlier pieces first, in the order they appear
/// there, the others after them in their current order (first appearance
/// in these pieces): the whole file's relative order.
fn renumber(grid: &mut CellGrid, earlier: &[Option<(usize, usize)>]) {
    let n = earlier.len();
    let mut order: Vec<usize> = (0..n).filter(|&i| earlier[i].is_some()).collect();
    order.sort_by_key(|&i| earlier[i]);
    if order.is_empty() {
        return;
    }
    order.extend((0..n).filter(|&i| earlier[i].is_none()));
    let mut new_of = vec![0i64; n];
    for (new, &old) in order.iter().enumerate() {
        new_of[old] = new as i64;
    }
    let permute = |values: &[f64], k: usize| -> Vec<f64> {
        order
            .iter()
            .flat_map(|&old| values[old * k..(old + 1) * k].iter().copied())
            .collect()
    };
    grid.points = permute(&grid.points, 3);
    for array in &mut grid.point_arrays {
        let k = array.components.max(1);
        if array.values.len() == n * k {
            array.values = permute(&array.values, k);
        }
    }
    for p in &mut grid.connectivity {
        if let Some(&q) = usize::try_from(*p).ok().and_then(|i| new_of.get(i)) {
            *p = q;
        }
    }
}

impl PieceSubset {
    /// The parallel file's name, for messages.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Bounds of the pieces' points as read (f64); `None` without points.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        bounds_f64(
            self.grid
                .points
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2])),
        )
    }

    /// The pieces as tetrahedra, points relative to `origin` (the whole
    /// mesh's, [`tetray_mesh::centring_origin`] of the whole bounds).
    pub fn assemble(self, origin: DVec3, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
        let mut grid = self.grid;
        drop_global_ids(&mut grid);
        require_volume(&grid, &self.name, "")?;
        Ok(assemble_at(grid, &self.name, opts, origin)?)
    }
}
