//! Ghost cells, blanking and joining pieces: what turns the raw grids of
//! several pieces (of a parallel file or of multi-block leaves) into one
//! raw grid whose cells meet face to face.
//!
//! Ghost flags (vtkDataSetAttributes.h, the `vtkGhostType` array):
//! cells DUPLICATECELL = 1 (owned by another piece) and HIDDENCELL = 32
//! (blanked); points HIDDENPOINT = 2 (blanked: every cell using it is
//! hidden). DUPLICATEPOINT = 1 only says another piece owns the point; the
//! point is kept and welded.
//!
//! Welding: a point of a later piece becomes the point of an earlier piece
//! with the same global id (the point array `<PointData GlobalIds>` names,
//! else one named `GlobalNodeId`, when every piece has one) or else with
//! bit-equal coordinates. Points of
//! one piece are never merged with each other: a piece's own duplicates are
//! the validation's business.

use std::collections::HashMap;

use super::CellError;
use super::grid::{CellArray, CellGrid};
use super::poly_grid::{keep_cell_faces, separate_inline_faces, shift_faces};

const GHOST_ARRAY: &str = "vtkGhostType";
const DUPLICATE_CELL: u8 = 1;
const HIDDEN_CELL: u8 = 32;
const HIDDEN_POINT: u8 = 2;

/// A raw grid read alone, made ready for `assemble`: ghost and blanked
/// cells dropped, ghost and global-id arrays removed from the fields.
pub fn finish_grid(mut grid: CellGrid, file: &str) -> Result<CellGrid, CellError> {
    drop_ghosts(&mut grid, file)?;
    drop_global_ids(&mut grid);
    Ok(grid)
}

/// The name Exodus files converted by VTK (IOSS) give global point ids.
const GLOBAL_NODE_ID: &str = "GlobalNodeId";

/// The point array of global ids: the one the file marks, else one named
/// `GlobalNodeId`.
fn global_id_array(grid: &CellGrid) -> Option<&CellArray> {
    let name = grid.global_ids.as_deref().unwrap_or(GLOBAL_NODE_ID);
    grid.point_arrays
        .iter()
        .find(|a| a.name == name && a.components == 1)
}

/// Removes the point array holding global ids: ids are not a physical field.
pub fn drop_global_ids(grid: &mut CellGrid) {
    if let Some(name) = global_id_array(grid).map(|a| a.name.clone()) {
        grid.point_arrays.retain(|a| a.name != name);
    }
    grid.global_ids = None;
}

/// One flag byte per tuple of a `vtkGhostType` array, removed from `arrays`.
fn take_flags(
    arrays: &mut Vec<CellArray>,
    tuples: usize,
    file: &str,
) -> Result<Option<Vec<u8>>, CellError> {
    let Some(at) = arrays.iter().position(|a| a.name == GHOST_ARRAY) else {
        return Ok(None);
    };
    let array = arrays.remove(at);
    if array.components != 1 || array.values.len() != tuples {
        return Err(CellError::CountMismatch {
            file: file.into(),
            section: array.section,
            what: format!("ghost flags (one per each of {tuples} tuples)"),
            expected: tuples,
            found: array.values.len() / array.components.max(1),
        });
    }
    Ok(Some(array.values.iter().map(|&v| v as u8).collect()))
}

/// Drops duplicate and hidden cells and the cells touching hidden points,
/// then the points no cell uses any more; counts them in `grid.pieces`.
pub fn drop_ghosts(grid: &mut CellGrid, file: &str) -> Result<(), CellError> {
    // A legacy polyhedron's face stream is not a list of its points.
    separate_inline_faces(grid, file)?;
    let npoints = grid.points.len() / 3;
    let ncells = grid.types.len();
    let point_flags = take_flags(&mut grid.point_arrays, npoints, file)?;
    let cell_flags = take_flags(&mut grid.cell_arrays, ncells, file)?;
    if point_flags.is_none() && cell_flags.is_none() {
        return Ok(());
    }
    let mut keep = vec![true; ncells];
    for (c, kept) in keep.iter_mut().enumerate() {
        let flags = cell_flags.as_ref().map_or(0, |f| f[c]);
        let hidden_point = point_flags.as_ref().is_some_and(|f| {
            cell_points(grid, c).any(|p| {
                usize::try_from(p)
                    .ok()
                    .and_then(|p| f.get(p))
                    .is_some_and(|&flag| flag & HIDDEN_POINT != 0)
            })
        });
        if flags & DUPLICATE_CELL != 0 {
            grid.pieces.ghost_cells_dropped += 1;
            *kept = false;
        } else if flags & HIDDEN_CELL != 0 || hidden_point {
            grid.pieces.hidden_cells_dropped += 1;
            *kept = false;
        }
    }
    if keep.iter().all(|&k| k) {
        return Ok(());
    }
    keep_cells(grid, &keep);
    drop_unused_points(grid);
    Ok(())
}

fn cell_points(grid: &CellGrid, c: usize) -> impl Iterator<Item = i64> + '_ {
    let (start, end) = (
        grid.offsets.get(c).copied().unwrap_or(0),
        grid.offsets.get(c + 1).copied().unwrap_or(0),
    );
    grid.connectivity
        .get(start..end)
        .unwrap_or(&[])
        .iter()
        .copied()
}

fn keep_cells(grid: &mut CellGrid, keep: &[bool]) {
    let numbers: Vec<u32> = (0..keep.len())
        .filter(|&c| keep[c])
        .map(|c| grid.cell_number(c))
        .collect();
    grid.cells_numbered = grid.numbered_cells();
    grid.cell_numbers = numbers;
    let mut offsets = vec![0];
    let mut connectivity = Vec::with_capacity(grid.connectivity.len());
    let mut types = Vec::new();
    for (c, _) in keep.iter().enumerate().filter(|&(_, &k)| k) {
        connectivity.extend(cell_points(grid, c));
        offsets.push(connectivity.len());
        types.push(grid.types[c]);
    }
    for array in &mut grid.cell_arrays {
        let k = array.components.max(1);
        if array.values.len() == keep.len() * k {
            let values = array
                .values
                .chunks_exact(k)
                .zip(keep)
                .filter(|&(_, &kept)| kept)
                .flat_map(|(t, _)| t.iter().copied())
                .collect();
            array.values = values;
        }
    }
    grid.offsets = offsets;
    grid.connectivity = connectivity;
    grid.types = types;
    keep_cell_faces(&mut grid.polyhedron_faces, keep);
}

/// Removes the points no cell uses (index checks are `assemble`'s: an
/// out-of-range index is left as it is, so it is still reported).
fn drop_unused_points(grid: &mut CellGrid) {
    let npoints = grid.points.len() / 3;
    let mut new_index = vec![u32::MAX; npoints];
    for &p in &grid.connectivity {
        if let Some(slot) = usize::try_from(p).ok().and_then(|p| new_index.get_mut(p)) {
            *slot = 0;
        }
    }
    let mut next = 0u32;
    for slot in &mut new_index {
        if *slot == 0 {
            *slot = next;
            next += 1;
        }
    }
    if next as usize == npoints {
        return;
    }
    let renumber = |p: i64| match usize::try_from(p).ok().and_then(|i| new_index.get(i)) {
        // A face point no cell lists is out of range too.
        Some(&n) if n != u32::MAX => i64::from(n),
        // Keep it out of range for the new point count.
        _ => i64::MAX,
    };
    for p in &mut grid.connectivity {
        *p = renumber(*p);
    }
    grid.polyhedron_faces = shift_faces(std::mem::take(&mut grid.polyhedron_faces), 0, renumber);
    let kept = |values: &[f64], k: usize| -> Vec<f64> {
        values
            .chunks_exact(k)
            .zip(&new_index)
            .filter(|&(_, &n)| n != u32::MAX)
            .flat_map(|(t, _)| t.iter().copied())
            .collect()
    };
    grid.points = kept(&grid.points, 3);
    for array in &mut grid.point_arrays {
        let k = array.components.max(1);
        if array.values.len() == npoints * k {
            array.values = kept(&array.values, k);
        }
    }
}

/// How points of different pieces are recognised as one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum WeldKey {
    GlobalId(i64),
    /// x, y, z bits (with -0 read as +0).
    Position([u64; 3]),
}

/// Joins the grids of several pieces into one, welding shared points; the
/// grids' ghost cells must already be dropped. Arrays missing from some
/// piece are dropped with a warning (like the Pieces of one `.vtu`).
pub fn weld(grids: Vec<CellGrid>, file: &str) -> Result<CellGrid, CellError> {
    let by_id = grids
        .iter()
        .filter(|g| !g.points.is_empty())
        .all(|g| global_id_array(g).is_some());
    let mut out = CellGrid {
        points_section: "Points".into(),
        dataset: common_dataset(&grids),
        ..CellGrid::default()
    };
    out.offsets.push(0);
    let mut known: HashMap<WeldKey, u32> = HashMap::new();
    let mut point_arrays = Vec::new();
    let mut cell_arrays = Vec::new();
    for mut grid in grids {
        out.pieces.pieces += grid.pieces.pieces.max(1);
        out.pieces.ghost_cells_dropped += grid.pieces.ghost_cells_dropped;
        out.pieces.hidden_cells_dropped += grid.pieces.hidden_cells_dropped;
        out.pieces.welded_points += grid.pieces.welded_points;
        out.warnings.append(&mut grid.warnings);
        let id_array = global_id_array(&grid);
        let id_name = id_array.map(|a| a.name.clone());
        let ids = id_array.map(|a| a.values.clone());
        let npoints = grid.points.len() / 3;
        let base = out.points.len() / 3;
        let mut fresh: Vec<(WeldKey, u32)> = Vec::new();
        let mut map = Vec::with_capacity(npoints);
        let mut new_points = Vec::new();
        for (p, xyz) in grid.points.chunks_exact(3).enumerate() {
            let key = match (&ids, by_id) {
                (Some(ids), true) => WeldKey::GlobalId(ids.get(p).copied().unwrap_or(-1.0) as i64),
                _ => WeldKey::Position([0, 1, 2].map(|a| (xyz[a] + 0.0).to_bits())),
            };
            if let Some(&q) = known.get(&key) {
                map.push(Some(q));
                out.pieces.welded_points += 1;
            } else {
                let q = u32::try_from(base + new_points.len()).map_err(|_| too_many(file))?;
                fresh.push((key, q));
                new_points.push(p);
                map.push(None);
                out.points.extend_from_slice(xyz);
            }
        }
        // Points of this piece become weldable for the next pieces only.
        let mut next = fresh.iter().map(|&(_, q)| q);
        let map: Vec<u32> = map
            .into_iter()
            .map(|m| m.unwrap_or_else(|| next.next().unwrap_or(u32::MAX)))
            .collect();
        known.extend(fresh);
        let start = out.connectivity.len();
        let to_joined = |p: i64| {
            usize::try_from(p)
                .ok()
                .and_then(|p| map.get(p))
                .map_or(i64::MAX, |&q| i64::from(q))
        };
        out.connectivity
            .extend(grid.connectivity.iter().map(|&p| to_joined(p)));
        let faces = std::mem::take(&mut grid.polyhedron_faces);
        out.polyhedron_faces
            .extend(shift_faces(faces, out.types.len(), to_joined));
        out.offsets
            .extend(grid.offsets.iter().skip(1).map(|&o| start + o));
        // A piece's cells are numbered on from all the cells (ghost and
        // hidden ones included) of the pieces before it.
        let numbered = out.cells_numbered as u32;
        out.cell_numbers
            .extend((0..grid.types.len()).map(|c| numbered + grid.cell_number(c)));
        out.cells_numbered += grid.numbered_cells();
        out.types.extend_from_slice(&grid.types);
        if npoints > 0 {
            let arrays = grid
                .point_arrays
                .into_iter()
                .map(|mut a| {
                    let k = a.components.max(1);
                    if a.values.len() == npoints * k {
                        a.values = new_points
                            .iter()
                            .flat_map(|&p| a.values[p * k..(p + 1) * k].to_vec())
                            .collect();
                    }
                    a
                })
                .collect();
            point_arrays.push(arrays);
        }
        if !grid.types.is_empty() {
            cell_arrays.push(grid.cell_arrays);
        }
        if out.global_ids.is_none() && by_id {
            out.global_ids = id_name;
        }
    }
    out.point_arrays = merge_arrays(point_arrays, &mut out.warnings);
    out.cell_arrays = merge_arrays(cell_arrays, &mut out.warnings);
    Ok(out)
}

fn too_many(file: &str) -> CellError {
    CellError::Unsupported {
        file: file.into(),
        section: "pieces".into(),
        what: "point count (tetrahedra index points with u32)",
        value: "more than 2^32 - 1".into(),
    }
}

/// The dataset type of every grid, or "MultiBlock" when they differ.
fn common_dataset(grids: &[CellGrid]) -> &'static str {
    match grids.first() {
        Some(first) if grids.iter().all(|g| g.dataset == first.dataset) => first.dataset,
        Some(_) => "MultiBlock",
        None => "",
    }
}

/// Concatenates the arrays of the non-empty pieces; an array missing from
/// some piece (by name and component count) is dropped with a warning.
pub fn merge_arrays(per_piece: Vec<Vec<CellArray>>, warnings: &mut Vec<String>) -> Vec<CellArray> {
    let mut pieces = per_piece.into_iter();
    let Some(mut merged) = pieces.next() else {
        return Vec::new();
    };
    for mut piece in pieces {
        merged.retain_mut(|array| {
            let found = piece
                .iter()
                .position(|a| a.name == array.name && a.components == array.components);
            match found {
                Some(j) => {
                    let other = piece.swap_remove(j);
                    array.values.extend(other.values);
                    true
                }
                None => {
                    warnings.push(format!("{}: not in every Piece, dropped", array.section));
                    false
                }
            }
        });
        for extra in piece {
            warnings.push(format!("{}: not in every Piece, dropped", extra.section));
        }
    }
    merged
}
