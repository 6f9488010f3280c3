//! A VTKHDF `UnstructuredGrid`: the partitions of one time step read into
//! the cell model and welded into one grid.

use hdf5_reader::group::Group;
use tetray_mesh::cells::{CellArray, CellError, CellGrid, drop_ghosts, from_face_tables, weld};

use super::H5;
use super::VtkHdfError;
use super::steps::Steps;

/// The per-partition counts of the file, all steps together.
struct Counts {
    points: Vec<usize>,
    cells: Vec<usize>,
    connectivity: Vec<usize>,
    /// Polyhedra: faces, face connectivity ids and polyhedron-to-face ids
    /// per partition (empty when the file has no polyhedra).
    faces: Vec<usize>,
    face_ids: Vec<usize>,
    polyhedron_faces: Vec<usize>,
}

/// Where one partition's data starts in each concatenated dataset.
#[derive(Debug, Clone, Copy, Default)]
struct Start {
    point: usize,
    cell: usize,
    offset: usize,
    connectivity: usize,
    face: usize,
    face_id: usize,
    polyhedron_face: usize,
    polyhedron_offset: usize,
}

pub(super) fn read(
    h5: &H5,
    root: &Group,
    steps: &Steps,
    step: Option<usize>,
) -> Result<CellGrid, VtkHdfError> {
    let counts = Counts::read(h5, root)?;
    let parts = counts.points.len();
    let (first, count) = step_parts(h5, steps, step, parts)?;
    // Where the step's first partition starts: the step's offsets where
    // the file gives them, else after every partition before it.
    let before = |v: &[usize]| v[..first].iter().sum::<usize>();
    let at = |name: &str, default: usize| -> Result<usize, VtkHdfError> {
        match steps.offset(name, step) {
            Some(v) => usize::try_from(v)
                .map_err(|_| h5.invalid(&format!("Steps/{name}"), format!("offset {v}"))),
            None => Ok(default),
        }
    };
    let cell = at("CellOffsets", before(&counts.cells))?;
    let mut start = Start {
        point: at("PointOffsets", before(&counts.points))?,
        cell,
        // Offsets hold one more entry per partition than it has cells.
        offset: cell + first,
        connectivity: at("ConnectivityIdOffsets", before(&counts.connectivity))?,
        face: 0,
        face_id: 0,
        polyhedron_face: 0,
        polyhedron_offset: cell + first,
    };
    if !counts.faces.is_empty() {
        start.face = at("FaceOffsetsOffsets", before(&counts.faces) + first)?;
        start.face_id = at("FaceConnectivityOffsets", before(&counts.face_ids))?;
        start.polyhedron_face = at(
            "PolyhedronToFaceIdOffsets",
            before(&counts.polyhedron_faces),
        )?;
    }
    let mut grids = Vec::with_capacity(count);
    for part in first..first + count {
        grids.push(read_part(h5, root, steps, step, &counts, part, start)?);
        start.point += counts.points[part];
        start.cell += counts.cells[part];
        start.offset += counts.cells[part] + 1;
        start.polyhedron_offset += counts.cells[part] + 1;
        start.connectivity += counts.connectivity[part];
        if !counts.faces.is_empty() {
            start.face += counts.faces[part] + 1;
            start.face_id += counts.face_ids[part];
            start.polyhedron_face += counts.polyhedron_faces[part];
        }
    }
    let cell_error = |e: CellError| VtkHdfError::from(crate::vtk::VtkError::from(e));
    for grid in &mut grids {
        drop_ghosts(grid, &h5.name).map_err(cell_error)?;
    }
    let count = grids.len();
    let mut grid = if count == 1 {
        grids.pop().expect("one partition")
    } else {
        weld(grids, &h5.name).map_err(cell_error)?
    };
    grid.pieces.pieces = count;
    Ok(grid)
}

impl Counts {
    fn read(h5: &H5, root: &Group) -> Result<Counts, VtkHdfError> {
        let list = |name: &str, required: bool| -> Result<Vec<usize>, VtkHdfError> {
            let ds = match h5.dataset(root, name) {
                Some(ds) => ds,
                None if required => {
                    return Err(VtkHdfError::Missing {
                        file: h5.name.clone(),
                        what: format!("dataset /VTKHDF/{name}"),
                    });
                }
                None => return Ok(Vec::new()),
            };
            h5.all_i64(&ds, name)?
                .into_iter()
                .map(|n| {
                    usize::try_from(n)
                        .map_err(|_| h5.invalid(name, format!("count {n} is negative")))
                })
                .collect()
        };
        let counts = Counts {
            points: list("NumberOfPoints", true)?,
            cells: list("NumberOfCells", true)?,
            connectivity: list("NumberOfConnectivityIds", true)?,
            faces: list("NumberOfFaces", false)?,
            face_ids: list("NumberOfFaceConnectivityIds", false)?,
            polyhedron_faces: list("NumberOfPolyhedronToFaceIds", false)?,
        };
        let n = counts.points.len();
        let same = |v: &[usize], optional: bool| v.len() == n || (optional && v.is_empty());
        if !(same(&counts.cells, false)
            && same(&counts.connectivity, false)
            && same(&counts.faces, true)
            && same(&counts.face_ids, true)
            && same(&counts.polyhedron_faces, true))
        {
            return Err(h5.invalid(
                "NumberOf*",
                format!(
                    "the partition counts differ in length: {} points, {} cells, {} \
                     connectivity",
                    n,
                    counts.cells.len(),
                    counts.connectivity.len()
                ),
            ));
        }
        if n == 0 {
            return Err(h5.invalid("NumberOfPoints", "no partition".into()));
        }
        let polyhedral = [&counts.faces, &counts.face_ids, &counts.polyhedron_faces];
        if polyhedral.iter().any(|v| v.is_empty()) && polyhedral.iter().any(|v| !v.is_empty()) {
            return Err(h5.invalid(
                "NumberOfFaces",
                "NumberOfFaces, NumberOfFaceConnectivityIds and NumberOfPolyhedronToFaceIds \
                 come together"
                    .into(),
            ));
        }
        Ok(counts)
    }
}

/// The partitions of `step`: the first and how many.
fn step_parts(
    h5: &H5,
    steps: &Steps,
    step: Option<usize>,
    parts: usize,
) -> Result<(usize, usize), VtkHdfError> {
    if !steps.temporal() {
        return Ok((0, parts));
    }
    let nsteps = steps.times.len();
    let first = steps.offset("PartOffsets", step).unwrap_or(0);
    let count = match steps.offset("NumberOfParts", step) {
        Some(n) => n,
        // Without NumberOfParts the steps hold as many partitions each
        // when the counts are per step, else they share them all.
        None if parts.is_multiple_of(nsteps)
            && (0..nsteps).any(|s| steps.offset("PartOffsets", Some(s)) != Some(0)) =>
        {
            (parts / nsteps) as i64
        }
        None => parts as i64 - first,
    };
    let ok = first >= 0 && count >= 0 && (first + count) as usize <= parts;
    if !ok {
        return Err(h5.invalid(
            "Steps",
            format!(
                "step {} names partitions {first} to {} of the {parts} the file holds",
                step.unwrap_or(0),
                first + count
            ),
        ));
    }
    Ok((first as usize, count as usize))
}

#[allow(clippy::too_many_arguments)]
fn read_part(
    h5: &H5,
    root: &Group,
    steps: &Steps,
    step: Option<usize>,
    counts: &Counts,
    part: usize,
    start: Start,
) -> Result<CellGrid, VtkHdfError> {
    let (np, nc, nconn) = (
        counts.points[part],
        counts.cells[part],
        counts.connectivity[part],
    );
    let section = |what: &str| format!("partition {part} {what}");
    let dataset = |name: &str| h5.require_dataset(root, "/VTKHDF", name);

    let (points, width) = h5.rows_f64(&dataset("Points")?, "Points", start.point, np)?;
    if width != 3 && np > 0 {
        return Err(h5.invalid("Points", format!("{width} coordinates per point, not 3")));
    }
    let (types, _) = h5.rows_i64(&dataset("Types")?, "Types", start.cell, nc)?;
    let (offsets, _) = h5.rows_i64(&dataset("Offsets")?, "Offsets", start.offset, nc + 1)?;
    let (connectivity, _) = h5.rows_i64(
        &dataset("Connectivity")?,
        "Connectivity",
        start.connectivity,
        nconn,
    )?;
    let offsets = relative_offsets(h5, &offsets, nconn, part)?;

    let mut grid = CellGrid {
        points,
        points_section: section("Points"),
        offsets,
        connectivity,
        types,
        dataset: "UnstructuredGrid",
        ..CellGrid::default()
    };
    grid.point_arrays = arrays(h5, steps, step, "PointData", start.point, np, part)?;
    grid.global_ids = global_ids(h5);
    grid.cell_arrays = arrays(h5, steps, step, "CellData", start.cell, nc, part)?;
    if grid.types.contains(&42) {
        polyhedra(h5, root, counts, part, start, &mut grid)?;
    }
    Ok(grid)
}

/// A partition's offsets relative to its own connectivity: they must rise
/// from their first value to the first plus the connectivity's length.
fn relative_offsets(
    h5: &H5,
    offsets: &[i64],
    nconn: usize,
    part: usize,
) -> Result<Vec<usize>, VtkHdfError> {
    let first = offsets.first().copied().unwrap_or(0);
    let mut out = Vec::with_capacity(offsets.len());
    let mut last = 0usize;
    for (c, &o) in offsets.iter().enumerate() {
        let rel = o
            .checked_sub(first)
            .and_then(|r| usize::try_from(r).ok())
            .filter(|&r| r >= last && r <= nconn);
        let Some(rel) = rel else {
            return Err(h5.invalid(
                "Offsets",
                format!(
                    "partition {part}, entry {c}: {o} does not rise within the partition's {nconn} \
                     connectivity ids"
                ),
            ));
        };
        out.push(rel);
        last = rel;
    }
    if last != nconn && !offsets.is_empty() {
        return Err(h5.invalid(
            "Offsets",
            format!("partition {part} ends at {last} of its {nconn} connectivity ids"),
        ));
    }
    Ok(out)
}

/// The point or cell arrays of a partition: `count` tuples from `start`
/// (or from the step's own offset for that array).
fn arrays(
    h5: &H5,
    steps: &Steps,
    step: Option<usize>,
    kind: &str,
    start: usize,
    count: usize,
    part: usize,
) -> Result<Vec<CellArray>, VtkHdfError> {
    let path = format!("/VTKHDF/{kind}");
    let Some(group) = h5.group(&path) else {
        return Ok(Vec::new());
    };
    let base_name = if kind == "PointData" {
        "PointOffsets"
    } else {
        "CellOffsets"
    };
    let mut out = Vec::new();
    for name in h5.dataset_names(&group, &path)? {
        let ds = h5.require_dataset(&group, &path, &name)?;
        let what = format!("{kind}/{name}");
        // The array's own step offset replaces the geometry's.
        let own = steps.offset(&format!("{kind}Offsets/{name}"), step);
        let geometry = steps.offset(base_name, step);
        let from = match (own, geometry) {
            (Some(o), Some(g)) => {
                let shift = o - g;
                usize::try_from(start as i64 + shift)
                    .map_err(|_| h5.invalid(&what, format!("step offset {o}")))?
            }
            (Some(o), None) => usize::try_from(o)
                .map_err(|_| h5.invalid(&what, format!("step offset {o}")))?
                .saturating_add(start),
            _ => start,
        };
        if !is_numeric(ds.dtype()) {
            continue;
        }
        let (values, components) = h5.rows_f64(&ds, &what, from, count)?;
        out.push(CellArray {
            name,
            components: components.max(1),
            values,
            section: format!("partition {part} {what}"),
            defined: None,
        });
    }
    Ok(out)
}

/// The point array marked as global ids (its `Attribute` is
/// `GlobalIds`), which welds the partitions.
fn global_ids(h5: &H5) -> Option<String> {
    let group = h5.group("/VTKHDF/PointData")?;
    let names = h5.dataset_names(&group, "/VTKHDF/PointData").ok()?;
    names.into_iter().find(|name| {
        h5.dataset(&group, name)
            .and_then(|ds| ds.attribute("Attribute").ok())
            .and_then(|a| a.read_strings().ok())
            .and_then(|v| v.into_iter().next())
            .is_some_and(|v| v.trim_end_matches('\0').eq_ignore_ascii_case("GlobalIds"))
    })
}

fn is_numeric(dtype: &hdf5_reader::Datatype) -> bool {
    matches!(
        dtype,
        hdf5_reader::Datatype::FloatingPoint { .. } | hdf5_reader::Datatype::FixedPoint { .. }
    )
}

/// The faces of the partition's polyhedra from the face tables.
fn polyhedra(
    h5: &H5,
    root: &Group,
    counts: &Counts,
    part: usize,
    start: Start,
    grid: &mut CellGrid,
) -> Result<(), VtkHdfError> {
    if counts.faces.is_empty() {
        return Err(h5.invalid(
            "polyhedra",
            format!(
                "partition {part} has polyhedra (type 42) but the file has no NumberOfFaces, \
                 FaceOffsets, FaceConnectivity, PolyhedronOffsets and PolyhedronToFaces"
            ),
        ));
    }
    let dataset = |name: &str| h5.require_dataset(root, "/VTKHDF", name);
    let nc = counts.cells[part];
    let (face_offsets, _) = h5.rows_i64(
        &dataset("FaceOffsets")?,
        "FaceOffsets",
        start.face,
        counts.faces[part] + 1,
    )?;
    let (face_connectivity, _) = h5.rows_i64(
        &dataset("FaceConnectivity")?,
        "FaceConnectivity",
        start.face_id,
        counts.face_ids[part],
    )?;
    let (polyhedron_offsets, _) = h5.rows_i64(
        &dataset("PolyhedronOffsets")?,
        "PolyhedronOffsets",
        start.polyhedron_offset,
        nc + 1,
    )?;
    let (to_faces, _) = h5.rows_i64(
        &dataset("PolyhedronToFaces")?,
        "PolyhedronToFaces",
        start.polyhedron_face,
        counts.polyhedron_faces[part],
    )?;
    // The tables' offsets start at 0 with one entry more than their
    // items; the shared parser takes the ends.
    let ends = |o: &[i64]| -> Vec<i64> {
        let first = o.first().copied().unwrap_or(0);
        o.iter().skip(1).map(|v| v - first).collect()
    };
    let per_cell = from_face_tables(
        &face_connectivity,
        &ends(&face_offsets),
        &to_faces,
        &ends(&polyhedron_offsets),
        &grid.types,
    )
    .map_err(|(cell, message)| {
        crate::vtk::VtkError::Cell(CellError::BadPolyhedron {
            file: h5.name.clone(),
            cell,
            message,
        })
    })?;
    let npoints = grid.points.len() / 3;
    for (c, faces) in per_cell {
        if let Some(&index) = faces
            .iter()
            .flatten()
            .find(|&&i| i < 0 || i as u64 >= npoints as u64)
        {
            return Err(crate::vtk::VtkError::Cell(CellError::BadIndex {
                file: h5.name.clone(),
                cell: c,
                index,
                npoints,
            })
            .into());
        }
        grid.polyhedron_faces.insert(c, faces);
    }
    Ok(())
}
