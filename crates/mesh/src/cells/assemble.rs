//! From the arrays of a parsed file (either format) to a [`TetMesh`]:
//! index and finiteness checks, cell splitting, point fields. Points the
//! splits add come after the file's, with every point array interpolated
//! to them with the weights that place them.

use std::collections::BTreeMap;

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::added_points::AddedPoints;
use super::cell_table::CellTable;
use super::cell_types::{CellKind, classify, type_name};
use super::grid::{CellArray, CellGrid};
use super::poly_grid::{checked_faces, separate_inline_faces};
use super::polyhedron::{prism_faces, split_polyhedron};
use super::split::{hexahedron_cones, split_cell};
use super::split_centred::hexahedron_centred;
use super::split_quadratic::{Subdivision, subdivide};
use super::{CellCounts, CellError, ReadOptions, SubdividedCells, VtkRead};
use crate::{ScalarField, TetMesh, first_index, first_position};

/// Checks what the reader can see, splits the cells and builds the mesh.
pub fn assemble_with(grid: CellGrid, file: &str, opts: &ReadOptions) -> Result<VtkRead, CellError> {
    let origin = centring(&grid.points);
    assemble_at(grid, file, opts, origin)
}

/// [`assemble_with`] with the points stored relative to `origin` (a part
/// of a mesh split over processes takes the whole mesh's, so that shared
/// points round to the same f32 coordinates in every part).
pub fn assemble_at(
    mut grid: CellGrid,
    file: &str,
    opts: &ReadOptions,
    origin: DVec3,
) -> Result<VtkRead, CellError> {
    let npoints = grid.points.len() / 3;
    if u32::try_from(npoints).is_err() {
        return Err(CellError::Unsupported {
            file: file.into(),
            section: grid.points_section,
            what: "point count (tetrahedra index points with u32)",
            value: npoints.to_string(),
        });
    }
    let mut points = finite_points(&grid.points, origin, &grid.points_section, file)?;
    separate_inline_faces(&mut grid, file)?;
    let mut warnings = std::mem::take(&mut grid.warnings);
    let cells = CellTable::new(
        &grid.offsets,
        &grid.connectivity,
        grid.types.len(),
        npoints,
        file,
    )?;
    // The cells hold the indices now (as u32).
    grid.connectivity = Vec::new();

    // A grid of tetrahedra alone (the common large mesh) is taken over in
    // parallel: each cell is one tetrahedron, as the loop below makes it.
    let only_tetra = first_position(&grid.types, |&t| classify(t) != CellKind::Tetra).is_none()
        && first_index(cells.len(), |c| cells.cell(c).len() != 4).is_none();
    let (mut tets, mut tet_cells) = if only_tetra {
        let tets = cells
            .ids
            .par_chunks_exact(4)
            .map(|v| [v[0], v[1], v[2], v[3]])
            .collect();
        let tet_cells = (0..cells.len())
            .into_par_iter()
            .map(|c| grid.cell_number(c))
            .collect();
        (tets, tet_cells)
    } else {
        // At least one tetrahedron per cell in a volume mesh: reserved so
        // that a tetrahedral mesh never reallocates (old and new buffers
        // together).
        (
            Vec::with_capacity(grid.types.len()),
            Vec::with_capacity(grid.types.len()),
        )
    };
    let mut added = AddedPoints::new(npoints);
    let mut counts = CellCounts {
        tetra: if only_tetra { cells.len() } else { 0 },
        ..CellCounts::default()
    };
    let mut subdivided: BTreeMap<i64, SubdividedCells> = BTreeMap::new();
    let mut lower_dim: BTreeMap<i64, usize> = BTreeMap::new();
    let mut dropped = 0;
    let mut resplit = 0;
    let mut centred = 0;
    let mut volume_cell = vec![only_tetra; cells.len()];
    let serial_cells = if only_tetra { 0 } else { grid.types.len() };
    for (c, &type_id) in grid.types.iter().enumerate().take(serial_cells) {
        let ids = cells.cell(c);
        let kind = classify(type_id);
        match kind {
            CellKind::LowerDim => {
                *lower_dim.entry(type_id).or_insert(0) += 1;
                continue;
            }
            CellKind::Unsupported3d | CellKind::Unknown => {
                return Err(CellError::UnsupportedCell {
                    file: file.into(),
                    cell: c,
                    type_id,
                    type_name: type_name(type_id),
                });
            }
            _ => {}
        }
        if let Some(expected) = kind.point_count()
            && ids.len() != expected
        {
            return Err(CellError::CellSize {
                file: file.into(),
                cell: c,
                type_id,
                type_name: type_name(type_id),
                expected,
                found: ids.len(),
            });
        }
        volume_cell[c] = true;
        let (tets_before, points_before) = (tets.len(), added.len());
        match kind {
            _ if kind.is_higher_order() => {
                let mut s = Subdivision {
                    points: &grid.points,
                    added: &mut added,
                    tets: &mut tets,
                    dropped: 0,
                };
                subdivide(kind, ids, opts.linearize, &mut s);
                dropped += s.dropped;
            }
            CellKind::Polyhedron | CellKind::PentagonalPrism | CellKind::HexagonalPrism => {
                let faces = match kind {
                    CellKind::PentagonalPrism => prism_faces(ids, 5),
                    CellKind::HexagonalPrism => prism_faces(ids, 6),
                    _ => checked_faces(&grid.polyhedron_faces, c, npoints, file)?,
                };
                dropped += split_polyhedron(&faces, &mut added, &mut tets);
            }
            _ => {
                dropped += split_cell(kind, ids, &mut tets);
                if kind == CellKind::Hexahedron
                    && !one_orientation(&tets[tets_before..], &grid.points)
                {
                    let cones = hexahedron_cones(ids);
                    if let Some(better) =
                        cones.into_iter().find(|c| one_orientation(c, &grid.points))
                    {
                        tets.truncate(tets_before);
                        tets.extend(better);
                        resplit += 1;
                    } else if let Some(split) = hexahedron_centred(ids, &grid.points) {
                        tets.truncate(tets_before);
                        let c = added.private(split.weights);
                        tets.extend(split.faces.iter().map(|&[a, b, d]| [c, a, b, d]));
                        centred += 1;
                    }
                }
            }
        }
        let made = tets.len() - tets_before;
        tet_cells.resize(tets.len(), grid.cell_number(c));
        match kind {
            CellKind::Tetra => counts.tetra += 1,
            CellKind::Hexahedron => counts.hexahedra += 1,
            CellKind::Voxel => counts.voxels += 1,
            CellKind::Wedge => counts.wedges += 1,
            CellKind::Pyramid => counts.pyramids += 1,
            _ => {
                let entry = subdivided.entry(type_id).or_insert(SubdividedCells {
                    type_id,
                    name: type_name(type_id),
                    cells: 0,
                    tets: 0,
                    points_added: 0,
                });
                entry.cells += 1;
                entry.tets += made;
                entry.points_added += added.len() - points_before;
            }
        }
        if kind != CellKind::Tetra {
            counts.tets_from_split += made;
        }
    }
    counts.subdivided = subdivided.into_values().collect();
    counts.points_added = added.len();
    let total_points = npoints + added.len();
    if u32::try_from(total_points).is_err() {
        return Err(CellError::Unsupported {
            file: file.into(),
            section: grid.points_section,
            what: "point count with the points the splits add (tetrahedra index points with u32)",
            value: total_points.to_string(),
        });
    }
    added.extend(&mut grid.points, 3);
    // Interpolation weights below 0 extrapolate: recheck the new points.
    let section = format!("{} (points added by the splits)", grid.points_section);
    points.extend(finite_points(
        &grid.points[3 * npoints..],
        origin,
        &section,
        file,
    )?);
    counts.skipped_lower_dim = lower_dim.values().sum();
    if counts.skipped_lower_dim > 0 {
        let per_type: Vec<String> = lower_dim
            .iter()
            .map(|(&t, &n)| format!("{n} {} (type {t})", type_name(t)))
            .collect();
        warnings.push(format!(
            "skipped {} lower-dimensional cells: {}",
            counts.skipped_lower_dim,
            per_type.join(", ")
        ));
    }
    if resplit > 0 {
        warnings.push(format!(
            "{resplit} distorted hexahedra split from another corner (same face diagonals, so \
             still conforming): the default split made tetrahedra of both orientations"
        ));
    }
    if centred > 0 {
        warnings.push(format!(
            "{centred} folded hexahedra split around a point added inside each (no split over \
             their corners has one orientation; the cones from the point over their faces do)"
        ));
    }
    if dropped > 0 {
        warnings.push(format!(
            "dropped {dropped} zero-volume tetrahedra from cells with repeated point indices"
        ));
    }

    let mut fields = Vec::new();
    for array in &mut grid.point_arrays {
        check_tuples(array, npoints, file)?;
        added.extend(&mut array.values, array.components);
        let (name, values) = per_tuple(array, total_points, file)?;
        fields.push(ScalarField {
            name,
            values: to_f32(&values, &array.section, file)?,
        });
    }
    if !grid.cell_arrays.is_empty() {
        let users = cells.point_users(&volume_cell, npoints);
        for array in &grid.cell_arrays {
            let (mut name, cell_values) = per_tuple(array, cells.len(), file)?;
            let mut averaged = match &array.defined {
                None => cells.average_to_points(&cell_values, &volume_cell, &users),
                Some(defined) => {
                    let used = mask_cells(&volume_cell, defined, &array.section, file)?;
                    let users = cells.point_users(&used, npoints);
                    cells.average_to_points(&cell_values, &used, &users)
                }
            };
            added.extend(&mut averaged, 1);
            let renamed = fields.iter().any(|f| f.name == name);
            if renamed {
                name.push_str("_cell");
            }
            warnings.push(format!(
                "cell field \"{name}\" converted to point data by averaging over the volume cells \
                 using each point{} (0 at points in no such cell){}",
                if array.defined.is_some() {
                    " that have a value"
                } else {
                    ""
                },
                if renamed {
                    "; renamed: a point field has its name"
                } else {
                    ""
                }
            ));
            fields.push(ScalarField {
                name,
                values: to_f32(&averaged, &array.section, file)?,
            });
        }
    }

    Ok(VtkRead {
        mesh: TetMesh {
            points,
            tets,
            fields,
        },
        warnings,
        cells: counts,
        dataset: grid.dataset,
        pieces: grid.pieces,
        origin,
        tet_cells,
    })
}

/// The volume cells that also have a value of a masked cell array.
fn mask_cells(
    volume_cell: &[bool],
    defined: &[bool],
    section: &str,
    file: &str,
) -> Result<Vec<bool>, CellError> {
    if defined.len() != volume_cell.len() {
        return Err(CellError::CountMismatch {
            file: file.into(),
            section: section.into(),
            what: "cells with a value or not".into(),
            expected: volume_cell.len(),
            found: defined.len(),
        });
    }
    Ok(volume_cell
        .iter()
        .zip(defined)
        .map(|(&v, &d)| v && d)
        .collect())
}

/// The origin the points are stored relative to ([`crate::centring_origin`]:
/// the centre of their bounds when they lie far from zero; `xyz` holds x,
/// y, z per point, in f64 as read).
fn centring(xyz: &[f64]) -> DVec3 {
    let wide = |p: &[f64]| DVec3::new(p[0], p[1], p[2]);
    crate::geometry::bounds_f64(xyz.chunks_exact(3).map(wide))
        .map_or(DVec3::ZERO, |(lo, hi)| crate::centring_origin(lo, hi))
}

/// The points relative to `origin`, computed in f64 and only then rounded
/// to f32. A coordinate that is not finite, or beyond f32's range, is an
/// error (as every value read).
fn finite_points(
    xyz: &[f64],
    origin: DVec3,
    section: &str,
    file: &str,
) -> Result<Vec<Vec3>, CellError> {
    let not_finite = |i: usize, axis: usize, value: f64| CellError::NonFinite {
        file: file.into(),
        section: format!("{section}, point {i} coordinate {}", ["x", "y", "z"][axis]),
        index: 3 * i + axis,
        value,
    };
    if let Some(at) = xyz.iter().position(|&v| !(v as f32).is_finite()) {
        return Err(not_finite(at / 3, at % 3, xyz[at]));
    }
    let wide = |p: &[f64]| DVec3::new(p[0], p[1], p[2]);
    let mut points = Vec::with_capacity(xyz.len() / 3);
    for (i, p) in xyz.chunks_exact(3).enumerate() {
        let q = (wide(p) - origin).as_vec3();
        if let Some(axis) = (0..3).find(|&a| !q[a].is_finite()) {
            return Err(not_finite(i, axis, p[axis]));
        }
        points.push(q);
    }
    Ok(points)
}

/// Whether the tetrahedra (of one cell) all have the same strict
/// orientation on the file's f64 points (`xyz`: x, y, z per point): all
/// positive for a well-shaped cell, all negative for one listed inverted.
/// Volumes are taken relative to each tetrahedron's first point, so far
/// coordinates lose nothing of the cell's shape.
fn one_orientation(tets: &[[u32; 4]], xyz: &[f64]) -> bool {
    let point = |i: u32| {
        let i = 3 * i as usize;
        DVec3::new(xyz[i], xyz[i + 1], xyz[i + 2])
    };
    let mut signs = tets.iter().map(|t| {
        let p = t.map(point);
        let v = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]));
        if v > 0.0 {
            1
        } else if v < 0.0 {
            -1
        } else {
            0
        }
    });
    let Some(first) = signs.next() else {
        return true;
    };
    first != 0 && signs.all(|s| s == first)
}

/// Checks an array has `tuples` tuples.
fn check_tuples(array: &CellArray, tuples: usize, file: &str) -> Result<(), CellError> {
    let k = array.components.max(1);
    if array.values.len() != tuples.saturating_mul(k) {
        return Err(CellError::CountMismatch {
            file: file.into(),
            section: array.section.clone(),
            what: format!("values ({tuples} tuples of {k} components)"),
            expected: tuples.saturating_mul(k),
            found: array.values.len(),
        });
    }
    Ok(())
}

/// One value per tuple: the value itself, or the Euclidean norm of a
/// multi-component tuple (named `<name>_magnitude`). Checks the count.
pub fn per_tuple(
    array: &CellArray,
    tuples: usize,
    file: &str,
) -> Result<(String, Vec<f64>), CellError> {
    let k = array.components.max(1);
    check_tuples(array, tuples, file)?;
    if let Some(i) = array.values.iter().position(|v| !v.is_finite()) {
        return Err(CellError::NonFinite {
            file: file.into(),
            section: array.section.clone(),
            index: i,
            value: array.values[i],
        });
    }
    if k == 1 {
        return Ok((array.name.clone(), array.values.clone()));
    }
    let norms = array
        .values
        .chunks_exact(k)
        .map(|t| t.iter().map(|v| v * v).sum::<f64>().sqrt())
        .collect();
    Ok((format!("{}_magnitude", array.name), norms))
}

/// The values as f32; NaN, infinities and values beyond f32's range are
/// errors naming `section` and the value's index.
pub fn to_f32(values: &[f64], section: &str, file: &str) -> Result<Vec<f32>, CellError> {
    let mut out = Vec::with_capacity(values.len());
    for (i, &v) in values.iter().enumerate() {
        let x = v as f32;
        if !x.is_finite() {
            return Err(CellError::NonFinite {
                file: file.into(),
                section: format!("{section} (as f32)"),
                index: i,
                value: v,
            });
        }
        out.push(x);
    }
    Ok(out)
}
