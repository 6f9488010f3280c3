//! From the arrays of a parsed file (either format) to a [`TetMesh`]:
//! index and finiteness checks, cell splitting, point fields.

use std::collections::BTreeMap;

use glam::Vec3;

use super::cells::{classify, type_name, CellKind};
use super::split::split_cell;
use super::{CellCounts, PieceCounts, VtkError, VtkRead};
use crate::{ScalarField, TetMesh};

/// A named point or cell array as read, `components` values per tuple.
#[derive(Debug, Clone)]
pub(crate) struct RawArray {
    pub name: String,
    pub components: usize,
    pub values: Vec<f64>,
    /// Where it came from, for messages ("line 12, POINT_DATA SCALARS \"p\"").
    pub section: String,
    /// Which tuples hold a value (`None`: all). Cell arrays only: a cell
    /// without one adds nothing to the average at its points (an Exodus
    /// element variable that some blocks lack); its `values` entries are
    /// ignored but must be finite.
    pub defined: Option<Vec<bool>>,
}

/// An unstructured grid as both formats describe it.
#[derive(Debug, Clone, Default)]
pub(crate) struct RawGrid {
    /// x, y, z per point.
    pub points: Vec<f64>,
    pub points_section: String,
    /// Start of each cell in `connectivity`, plus the end: `ncells + 1`
    /// entries (or empty when there are no cells).
    pub offsets: Vec<usize>,
    pub connectivity: Vec<i64>,
    pub types: Vec<i64>,
    pub point_arrays: Vec<RawArray>,
    pub cell_arrays: Vec<RawArray>,
    pub warnings: Vec<String>,
    /// The VTK dataset type read ("UnstructuredGrid", "StructuredGrid"...).
    pub dataset: &'static str,
    /// The point array holding global point ids, when the file marks one
    /// (`<PointData GlobalIds="...">`): pieces are welded by it.
    pub global_ids: Option<String>,
    /// Pieces, welding and ghost cells, for the load report.
    pub pieces: PieceCounts,
    /// A single-piece ImageData / STRUCTURED_POINTS: its index space.
    pub image: Option<ImageGeometry>,
}

/// Where the points of an image lie: point `(i, j, k)` (from 0) at
/// `origin + direction * ((i, j, k) * spacing)`, `direction` row-major.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ImageGeometry {
    pub dims: [usize; 3],
    pub origin: [f64; 3],
    pub spacing: [f64; 3],
    pub direction: [f64; 9],
}

/// Checks what the reader can see, splits the cells and builds the mesh.
pub(crate) fn assemble(mut grid: RawGrid, file: &str) -> Result<VtkRead, VtkError> {
    let npoints = grid.points.len() / 3;
    if u32::try_from(npoints).is_err() {
        return Err(VtkError::Unsupported {
            file: file.into(),
            section: grid.points_section,
            what: "point count (tetrahedra index points with u32)",
            value: npoints.to_string(),
        });
    }
    let points = finite_points(&grid.points, &grid.points_section, file)?;
    let mut warnings = std::mem::take(&mut grid.warnings);
    let cells = CellTable::new(&grid, npoints, file)?;

    let mut tets = Vec::new();
    let mut counts = CellCounts::default();
    let mut lower_dim: BTreeMap<i64, usize> = BTreeMap::new();
    let mut dropped = 0;
    let mut volume_cell = vec![false; cells.len()];
    for (c, &type_id) in grid.types.iter().enumerate() {
        let ids = cells.cell(c);
        let kind = classify(type_id);
        match kind {
            CellKind::LowerDim => {
                *lower_dim.entry(type_id).or_insert(0) += 1;
                continue;
            }
            CellKind::Unsupported3d | CellKind::Unknown => {
                return Err(VtkError::UnsupportedCell {
                    file: file.into(),
                    cell: c,
                    type_id,
                    type_name: type_name(type_id),
                });
            }
            _ => {}
        }
        let expected = kind.point_count().unwrap_or(0);
        if ids.len() != expected {
            return Err(VtkError::CellSize {
                file: file.into(),
                cell: c,
                type_id,
                type_name: type_name(type_id),
                expected,
                found: ids.len(),
            });
        }
        volume_cell[c] = true;
        let before = tets.len();
        dropped += split_cell(kind, ids, &mut tets);
        let made = tets.len() - before;
        match kind {
            CellKind::Tetra => counts.tetra += 1,
            CellKind::Hexahedron => counts.hexahedra += 1,
            CellKind::Voxel => counts.voxels += 1,
            CellKind::Wedge => counts.wedges += 1,
            CellKind::Pyramid => counts.pyramids += 1,
            _ => {}
        }
        if kind != CellKind::Tetra {
            counts.tets_from_split += made;
        }
    }
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
    if dropped > 0 {
        warnings.push(format!(
            "dropped {dropped} zero-volume tetrahedra from cells with repeated point indices"
        ));
    }

    let mut fields = Vec::new();
    for array in &grid.point_arrays {
        let (name, values) = per_tuple(array, npoints, file)?;
        fields.push(ScalarField {
            name,
            values: to_f32(&values, &array.section, file)?,
        });
    }
    if !grid.cell_arrays.is_empty() {
        let users = cells.point_users(&volume_cell, npoints);
        for array in &grid.cell_arrays {
            let (mut name, cell_values) = per_tuple(array, cells.len(), file)?;
            let averaged = match &array.defined {
                None => cells.average_to_points(&cell_values, &volume_cell, &users),
                Some(defined) => {
                    let used = mask_cells(&volume_cell, defined, &array.section, file)?;
                    let users = cells.point_users(&used, npoints);
                    cells.average_to_points(&cell_values, &used, &users)
                }
            };
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
    })
}

/// The volume cells that also have a value of a masked cell array.
fn mask_cells(
    volume_cell: &[bool],
    defined: &[bool],
    section: &str,
    file: &str,
) -> Result<Vec<bool>, VtkError> {
    if defined.len() != volume_cell.len() {
        return Err(VtkError::CountMismatch {
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

fn finite_points(xyz: &[f64], section: &str, file: &str) -> Result<Vec<Vec3>, VtkError> {
    let mut points = Vec::with_capacity(xyz.len() / 3);
    for (i, p) in xyz.chunks_exact(3).enumerate() {
        let q = Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32);
        for (axis, (&wide, narrow)) in p.iter().zip(q.to_array()).enumerate() {
            if !narrow.is_finite() {
                return Err(VtkError::NonFinite {
                    file: file.into(),
                    section: format!("{section}, point {i} coordinate {}", ["x", "y", "z"][axis]),
                    index: 3 * i + axis,
                    value: wide,
                });
            }
        }
        points.push(q);
    }
    Ok(points)
}

/// One value per tuple: the value itself, or the Euclidean norm of a
/// multi-component tuple (named `<name>_magnitude`). Checks the count.
pub(crate) fn per_tuple(
    array: &RawArray,
    tuples: usize,
    file: &str,
) -> Result<(String, Vec<f64>), VtkError> {
    let k = array.components.max(1);
    if array.values.len() != tuples.saturating_mul(k) {
        return Err(VtkError::CountMismatch {
            file: file.into(),
            section: array.section.clone(),
            what: format!("values ({tuples} tuples of {k} components)"),
            expected: tuples.saturating_mul(k),
            found: array.values.len(),
        });
    }
    if let Some(i) = array.values.iter().position(|v| !v.is_finite()) {
        return Err(VtkError::NonFinite {
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

pub(crate) fn to_f32(values: &[f64], section: &str, file: &str) -> Result<Vec<f32>, VtkError> {
    let mut out = Vec::with_capacity(values.len());
    for (i, &v) in values.iter().enumerate() {
        let x = v as f32;
        if !x.is_finite() {
            return Err(VtkError::NonFinite {
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

/// Cells as validated u32 point-index slices.
struct CellTable<'a> {
    offsets: &'a [usize],
    ids: Vec<u32>,
}

impl<'a> CellTable<'a> {
    fn new(grid: &'a RawGrid, npoints: usize, file: &str) -> Result<Self, VtkError> {
        let ncells = grid.types.len();
        let offsets: &[usize] = if grid.offsets.is_empty() {
            &[0]
        } else {
            &grid.offsets
        };
        let invalid = |message: String| VtkError::Invalid {
            file: file.into(),
            section: "cells".into(),
            message,
        };
        if offsets.len() != ncells + 1 || offsets[0] != 0 {
            return Err(invalid(format!(
                "{} cell offsets for {ncells} cell types",
                offsets.len().saturating_sub(1)
            )));
        }
        let mut ids = Vec::with_capacity(grid.connectivity.len());
        for c in 0..ncells {
            let (start, end) = (offsets[c], offsets[c + 1]);
            if end < start || end > grid.connectivity.len() {
                return Err(invalid(format!(
                    "cell {c} spans connectivity entries {start}..{end} of {}",
                    grid.connectivity.len()
                )));
            }
            for &index in &grid.connectivity[start..end] {
                match u32::try_from(index) {
                    Ok(i) if (i as usize) < npoints => ids.push(i),
                    _ => {
                        return Err(VtkError::BadIndex {
                            file: file.into(),
                            cell: c,
                            index,
                            npoints,
                        })
                    }
                }
            }
        }
        if offsets[ncells] != grid.connectivity.len() {
            return Err(invalid(format!(
                "the cells use {} connectivity entries but there are {}",
                offsets[ncells],
                grid.connectivity.len()
            )));
        }
        Ok(CellTable { offsets, ids })
    }

    fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    fn cell(&self, c: usize) -> &[u32] {
        &self.ids[self.offsets[c]..self.offsets[c + 1]]
    }

    /// Distinct points of cell `c` (collapsed cells repeat some).
    fn distinct(&self, c: usize) -> impl Iterator<Item = u32> + '_ {
        let ids = self.cell(c);
        ids.iter()
            .enumerate()
            .filter(move |&(i, id)| !ids[..i].contains(id))
            .map(|(_, &id)| id)
    }

    /// How many volume cells use each point.
    fn point_users(&self, volume_cell: &[bool], npoints: usize) -> Vec<u32> {
        let mut users = vec![0u32; npoints];
        for c in (0..self.len()).filter(|&c| volume_cell[c]) {
            for p in self.distinct(c) {
                users[p as usize] += 1;
            }
        }
        users
    }

    /// Mean over the volume cells using each point; 0 where none does.
    fn average_to_points(&self, per_cell: &[f64], volume_cell: &[bool], users: &[u32]) -> Vec<f64> {
        let mut sum = vec![0.0f64; users.len()];
        for c in (0..self.len()).filter(|&c| volume_cell[c]) {
            for p in self.distinct(c) {
                sum[p as usize] += per_cell[c];
            }
        }
        sum.iter()
            .zip(users)
            .map(|(&s, &n)| if n == 0 { 0.0 } else { s / n as f64 })
            .collect()
    }
}
