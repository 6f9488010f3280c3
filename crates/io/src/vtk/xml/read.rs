//! Serial VTK XML reader: the UnstructuredGrid (`.vtu`) Pieces are decoded
//! and concatenated into one raw grid; the structured datasets (`.vts`,
//! `.vtr`, `.vti`) go to `structured.rs`.

use super::data::ArrayDecoder;
use super::tree::{VtuDoc, XmlArray, XmlPiece};
use crate::vtk::VtkError;
use crate::vtk::numeric::Scalar;
use tetray_mesh::cells as polyhedron;
use tetray_mesh::cells::CellError;
use tetray_mesh::cells::merge_arrays as merge;
use tetray_mesh::cells::{CellArray, CellGrid};

/// The raw grid of a parsed `.vtu` (UnstructuredGrid) file.
pub(crate) fn read_unstructured(doc: &VtuDoc, name: &str) -> Result<CellGrid, VtkError> {
    let decoder = ArrayDecoder { file: name, doc };
    let mut grid = CellGrid {
        points_section: "Points".into(),
        dataset: "UnstructuredGrid",
        ..CellGrid::default()
    };
    let mut point_arrays = Vec::new();
    let mut cell_arrays = Vec::new();
    for (k, piece) in doc.pieces.iter().enumerate() {
        let points_before = grid.points.len() / 3;
        let cells_before = grid.types.len();
        read_points(&decoder, piece, k, &mut grid)?;
        read_cells(&decoder, piece, k, points_before, cells_before, &mut grid)?;
        let points = read_arrays(&decoder, piece, k, false, &mut grid.warnings)?;
        let cells = read_arrays(&decoder, piece, k, true, &mut grid.warnings)?;
        // Empty pieces (common in parallel output) constrain nothing.
        if piece.npoints > 0 {
            point_arrays.push(points);
        }
        if piece.ncells > 0 {
            cell_arrays.push(cells);
        }
    }
    grid.point_arrays = merge(point_arrays, &mut grid.warnings);
    grid.cell_arrays = merge(cell_arrays, &mut grid.warnings);
    grid.global_ids = common_global_ids(&doc.pieces);
    Ok(grid)
}

/// The global point id array's name when every piece marks the same one.
pub(crate) fn common_global_ids(pieces: &[XmlPiece]) -> Option<String> {
    let first = pieces.first()?.global_ids.clone()?;
    pieces
        .iter()
        .all(|p| p.global_ids.as_deref() == Some(first.as_str()))
        .then_some(first)
}

pub(crate) fn piece_error(file: &str, piece: &XmlPiece, k: usize, message: String) -> VtkError {
    VtkError::Cell(CellError::Invalid {
        file: file.into(),
        section: format!("line {}, Piece {k}", piece.line),
        message,
    })
}

pub(crate) fn section(a: &XmlArray, k: usize, place: &str) -> String {
    let name = a.name.as_deref().unwrap_or("");
    format!("line {}, Piece {k} {place} DataArray \"{name}\"", a.line)
}

pub(crate) fn expect_count(
    file: &str,
    section: &str,
    what: &str,
    expected: usize,
    found: usize,
) -> Result<(), VtkError> {
    if expected == found {
        return Ok(());
    }
    Err(VtkError::Cell(CellError::CountMismatch {
        file: file.into(),
        section: section.into(),
        what: what.into(),
        expected,
        found,
    }))
}

pub(crate) fn read_points(
    d: &ArrayDecoder<'_, '_>,
    piece: &XmlPiece,
    k: usize,
    grid: &mut CellGrid,
) -> Result<(), VtkError> {
    if piece.npoints == 0 {
        return Ok(());
    }
    let Some(a) = &piece.points else {
        return Err(piece_error(
            d.file,
            piece,
            k,
            "no <Points> DataArray".into(),
        ));
    };
    let section = section(a, k, "Points");
    if a.components != 3 {
        return Err(VtkError::Cell(CellError::Invalid {
            file: d.file.into(),
            section,
            message: format!("points have {} components, not 3", a.components),
        }));
    }
    let xyz = d.floats(a, &section)?;
    let what = format!(
        "coordinates (3 for each of NumberOfPoints={})",
        piece.npoints
    );
    expect_count(
        d.file,
        &section,
        &what,
        piece.npoints.saturating_mul(3),
        xyz.len(),
    )?;
    grid.points.extend(xyz);
    Ok(())
}

/// Appends the piece's cells, its point indices shifted by the points of
/// the pieces before it (each piece indexes its own points).
fn read_cells(
    d: &ArrayDecoder<'_, '_>,
    piece: &XmlPiece,
    k: usize,
    points_before: usize,
    cells_before: usize,
    grid: &mut CellGrid,
) -> Result<(), VtkError> {
    if piece.ncells == 0 {
        return Ok(());
    }
    let find = |name: &str| {
        piece
            .cells
            .iter()
            .find(|a| a.name.as_deref() == Some(name))
            .ok_or_else(|| {
                piece_error(
                    d.file,
                    piece,
                    k,
                    format!("<Cells> has no DataArray named \"{name}\""),
                )
            })
    };
    let (conn_array, offsets_array, types_array) =
        (find("connectivity")?, find("offsets")?, find("types")?);

    let offsets_section = section(offsets_array, k, "Cells");
    let offsets = d.ints(offsets_array, &offsets_section)?;
    let what = format!("offsets (NumberOfCells={})", piece.ncells);
    expect_count(d.file, &offsets_section, &what, piece.ncells, offsets.len())?;
    let types_section = section(types_array, k, "Cells");
    let types = d.ints(types_array, &types_section)?;
    let what = format!("cell types (NumberOfCells={})", piece.ncells);
    expect_count(d.file, &types_section, &what, piece.ncells, types.len())?;
    let conn_section = section(conn_array, k, "Cells");
    let connectivity = d.ints(conn_array, &conn_section)?;

    // VTK stores the end of each cell; check they never decrease.
    let mut previous = 0usize;
    for (c, &end) in offsets.iter().enumerate() {
        let end = usize::try_from(end)
            .ok()
            .filter(|&e| e >= previous && e <= connectivity.len());
        let Some(end) = end else {
            return Err(VtkError::Cell(CellError::Invalid {
                file: d.file.into(),
                section: offsets_section,
                message: format!(
                    "offset {c} is {}: offsets must not decrease and must stay within the {} connectivity entries",
                    offsets[c],
                    connectivity.len()
                ),
            }));
        };
        previous = end;
    }
    let what = "connectivity entries (the last offset)";
    expect_count(d.file, &conn_section, what, previous, connectivity.len())?;

    // The first index out of range, named with its cell (offsets were
    // checked: every entry belongs to the cell whose end is past it).
    let bad = tetray_mesh::first_position(&connectivity, |&i| {
        i < 0 || i as u64 >= piece.npoints as u64
    });
    if let Some(at) = bad {
        return Err(VtkError::Cell(CellError::BadIndex {
            file: d.file.into(),
            cell: cells_before + offsets.partition_point(|&end| end as usize <= at),
            index: connectivity[at],
            npoints: piece.npoints,
        }));
    }
    let start = grid.connectivity.len();
    if grid.offsets.is_empty() {
        grid.offsets.push(0);
    }
    // Offsets were checked to lie in 0..=len above.
    grid.offsets
        .extend(offsets.iter().map(|&o| start + o as usize));
    // The first piece's arrays are moved, not copied (at 10 M tetrahedra
    // the connectivity alone is 320 MB).
    if start == 0 && points_before == 0 {
        grid.connectivity = connectivity;
    } else {
        let shift = points_before as i64;
        grid.connectivity
            .extend(connectivity.iter().map(|&index| index + shift));
    }
    if types.contains(&42) {
        read_polyhedra(d, piece, k, &types, points_before, cells_before, grid)?;
    }
    if grid.types.is_empty() {
        grid.types = types;
    } else {
        grid.types.extend(types);
    }
    Ok(())
}

/// The faces of the piece's polyhedra (see `polyhedron.rs` for the two
/// layouts), their point indices shifted like the connectivity's.
fn read_polyhedra(
    d: &ArrayDecoder<'_, '_>,
    piece: &XmlPiece,
    k: usize,
    types: &[i64],
    points_before: usize,
    cells_before: usize,
    grid: &mut CellGrid,
) -> Result<(), VtkError> {
    let array = |name: &str| -> Result<Option<Vec<i64>>, VtkError> {
        let found = piece.cells.iter().find(|a| a.name.as_deref() == Some(name));
        found
            .map(|a| d.ints(a, &section(a, k, "Cells")))
            .transpose()
    };
    let per_cell = if let (Some(faces), Some(offsets)) = (array("faces")?, array("faceoffsets")?) {
        polyhedron::from_face_stream(&faces, &offsets, types)
    } else if let (Some(fc), Some(fo), Some(pf), Some(po)) = (
        array("face_connectivity")?,
        array("face_offsets")?,
        array("polyhedron_to_faces")?,
        array("polyhedron_offsets")?,
    ) {
        polyhedron::from_face_tables(&fc, &fo, &pf, &po, types)
    } else {
        return Err(piece_error(
            d.file,
            piece,
            k,
            "polyhedra (type 42) but <Cells> has neither \"faces\" + \"faceoffsets\" nor \
             \"face_connectivity\" + \"face_offsets\" + \"polyhedron_to_faces\" + \
             \"polyhedron_offsets\""
                .into(),
        ));
    };
    let per_cell = per_cell.map_err(|(c, message)| {
        VtkError::Cell(CellError::BadPolyhedron {
            file: d.file.into(),
            cell: cells_before + c,
            message,
        })
    })?;
    for (c, mut faces) in per_cell {
        for index in faces.iter_mut().flatten() {
            if *index < 0 || *index as u64 >= piece.npoints as u64 {
                return Err(VtkError::Cell(CellError::BadIndex {
                    file: d.file.into(),
                    cell: cells_before + c,
                    index: *index,
                    npoints: piece.npoints,
                }));
            }
            *index += points_before as i64;
        }
        grid.polyhedron_faces.insert(cells_before + c, faces);
    }
    Ok(())
}

/// The PointData (or CellData) arrays of one piece. Arrays of a type that
/// is not numeric (String, Bit) are skipped with a warning.
pub(crate) fn read_arrays(
    d: &ArrayDecoder<'_, '_>,
    piece: &XmlPiece,
    k: usize,
    cells: bool,
    warnings: &mut Vec<String>,
) -> Result<Vec<CellArray>, VtkError> {
    let (place, arrays, tuples) = if cells {
        ("CellData", &piece.cell_data, piece.ncells)
    } else {
        ("PointData", &piece.point_data, piece.npoints)
    };
    let mut out = Vec::new();
    for (i, a) in arrays.iter().enumerate() {
        let section = section(a, k, place);
        if Scalar::from_vtu_name(&a.type_name).is_none() {
            warnings.push(format!(
                "{section}: skipped, type \"{}\" is not numeric",
                a.type_name
            ));
            continue;
        }
        let values = d.floats(a, &section)?;
        let what = format!("values ({tuples} tuples of {} components)", a.components);
        expect_count(
            d.file,
            &section,
            &what,
            tuples.saturating_mul(a.components),
            values.len(),
        )?;
        out.push(CellArray {
            name: a.name.clone().unwrap_or_else(|| format!("{place}_{i}")),
            components: a.components,
            values,
            section,
            defined: None,
        });
    }
    Ok(out)
}
