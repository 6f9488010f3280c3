//! Serial XML structured datasets: `.vts` (StructuredGrid: `<Points>`),
//! `.vtr` (RectilinearGrid: three `<Coordinates>` arrays) and `.vti`
//! (ImageData: `Origin`, `Spacing`, `Direction` of the dataset element).
//! Each Piece covers its own `Extent` (inclusive point index ranges within
//! `WholeExtent`); several Pieces are welded on their shared faces.

use super::data::ArrayDecoder;
use tetray_mesh::cells::CellError;
use tetray_mesh::cells::CellGrid;
use tetray_mesh::cells::merge_arrays as merge;
use tetray_mesh::cells::weld;
use tetray_mesh::cells::{
    add_cells, cell_count, extent_dims, image_points, point_count, rectilinear_points,
};

use super::read::{common_global_ids, piece_error, read_arrays, read_points, section};
use super::tree::{VtuDoc, XmlPiece, find};
use crate::vtk::ImageGeometry;
use crate::vtk::VtkError;

/// The raw grid of a StructuredGrid, RectilinearGrid or ImageData document.
pub(crate) fn read_raw(doc: &mut VtuDoc<'_>, file: &str) -> Result<CellGrid, VtkError> {
    Ok(read_raw_image(doc, file)?.0)
}

/// [`read_raw`], and for a single-piece ImageData its index space.
pub(crate) fn read_raw_image(
    doc: &mut VtuDoc<'_>,
    file: &str,
) -> Result<(CellGrid, Option<ImageGeometry>), VtkError> {
    let dataset: &'static str = match doc.dataset.as_str() {
        "StructuredGrid" => "StructuredGrid",
        "RectilinearGrid" => "RectilinearGrid",
        _ => "ImageData",
    };
    let element = format!("<{dataset}>");
    let whole = find(&doc.dataset_attributes, "WholeExtent")
        .map(|text| parse_extent(text, file, &format!("{element} WholeExtent")))
        .transpose()?;
    let mut extents = Vec::with_capacity(doc.pieces.len());
    for (k, piece) in doc.pieces.iter_mut().enumerate() {
        let Some(text) = piece.attribute("Extent") else {
            return Err(piece_error(file, piece, k, "no Extent attribute".into()));
        };
        let place = format!("line {}, Piece {k} Extent", piece.line);
        let extent = parse_extent(text, file, &place)?;
        if let Some(w) = whole {
            let inside =
                (0..3).all(|a| extent[2 * a] >= w[2 * a] && extent[2 * a + 1] <= w[2 * a + 1]);
            if !inside {
                return Err(piece_error(
                    file,
                    piece,
                    k,
                    format!("Extent \"{text}\" is not inside WholeExtent {w:?}"),
                ));
            }
        }
        let dims = extent_dims(&extent);
        piece.npoints = point_count(dims, file, &place)?;
        piece.ncells = cell_count(dims);
        extents.push(extent);
    }
    // An image's (and a rectilinear grid's) points and cells are made, not
    // read: nothing in the file bounds them but the memory.
    let points: u64 = doc.pieces.iter().map(|p| p.npoints as u64).sum();
    let cells: u64 = doc.pieces.iter().map(|p| p.ncells as u64).sum();
    crate::preflight::check(
        file,
        || format!("the {dataset} ({points} points, {cells} cells)"),
        crate::preflight::grid_bytes(points, cells),
    )?;
    let image = if dataset == "ImageData" {
        Some(ImageFrame::of(&doc.dataset_attributes, file, &element)?)
    } else {
        None
    };
    let decoder = ArrayDecoder { file, doc };
    let mut geometry = None;
    let mut grids = Vec::with_capacity(doc.pieces.len());
    for (k, (piece, extent)) in doc.pieces.iter().zip(&extents).enumerate() {
        let dims = extent_dims(extent);
        let mut grid = CellGrid {
            points_section: format!("line {}, Piece {k} points", piece.line),
            dataset,
            ..CellGrid::default()
        };
        // Arrays first: their lengths check the extent before the points
        // and cells it implies are made.
        let points = read_arrays(&decoder, piece, k, false, &mut grid.warnings)?;
        let cells = read_arrays(&decoder, piece, k, true, &mut grid.warnings)?;
        match (dataset, &image) {
            ("StructuredGrid", _) => read_points(&decoder, piece, k, &mut grid)?,
            ("RectilinearGrid", _) => grid.points = coordinates(&decoder, piece, k, dims)?,
            (_, Some(frame)) => {
                grid.points = image_points(extent, frame.origin, frame.spacing, frame.direction);
                let start = [0, 1, 2].map(|a| grid.points[a]);
                geometry = Some(ImageGeometry {
                    dims,
                    origin: start,
                    spacing: frame.spacing,
                    direction: frame.direction,
                });
            }
            _ => {}
        }
        add_cells(dims, &mut grid);
        grid.point_arrays = merge(vec![points], &mut grid.warnings);
        grid.cell_arrays = merge(vec![cells], &mut grid.warnings);
        grid.global_ids = common_global_ids(std::slice::from_ref(piece));
        grids.push(grid);
    }
    if grids.len() == 1 {
        return Ok((grids.remove(0), geometry));
    }
    let mut joined = weld(grids, file)?;
    joined.dataset = dataset;
    Ok((joined, None))
}

/// The x, y and z coordinate arrays of a RectilinearGrid piece.
fn coordinates(
    d: &ArrayDecoder<'_, '_>,
    piece: &XmlPiece,
    k: usize,
    dims: [usize; 3],
) -> Result<Vec<f64>, VtkError> {
    if piece.coordinates.len() != 3 {
        return Err(piece_error(
            d.file,
            piece,
            k,
            format!(
                "<Coordinates> holds {} DataArrays, not 3 (x, y, z)",
                piece.coordinates.len()
            ),
        ));
    }
    let mut axes = Vec::with_capacity(3);
    for (axis, a) in piece.coordinates.iter().enumerate() {
        let place = section(a, k, "Coordinates");
        let values = d.floats(a, &place)?;
        if values.len() != dims[axis] {
            return Err(VtkError::Cell(CellError::CountMismatch {
                file: d.file.into(),
                section: place,
                what: format!(
                    "{} coordinates (the Extent's points along {})",
                    ["x", "y", "z"][axis],
                    ["x", "y", "z"][axis]
                ),
                expected: dims[axis],
                found: values.len(),
            }));
        }
        axes.push(values);
    }
    Ok(rectilinear_points(&axes[0], &axes[1], &axes[2]))
}

/// Where an image's index space lies in the world.
struct ImageFrame {
    origin: [f64; 3],
    spacing: [f64; 3],
    direction: [f64; 9],
}

impl ImageFrame {
    fn of(attributes: &[(String, String)], file: &str, element: &str) -> Result<Self, VtkError> {
        let numbers = |key: &str, default: &[f64]| -> Result<Vec<f64>, VtkError> {
            let Some(text) = find(attributes, key) else {
                return Ok(default.to_vec());
            };
            let values: Option<Vec<f64>> = text
                .split_ascii_whitespace()
                .map(|t| t.parse().ok().filter(|v: &f64| v.is_finite()))
                .collect();
            values.filter(|v| v.len() == default.len()).ok_or_else(|| {
                VtkError::Cell(CellError::Invalid {
                    file: file.into(),
                    section: format!("{element} {key}"),
                    message: format!("\"{text}\" is not {} finite numbers", default.len()),
                })
            })
        };
        let identity = [1., 0., 0., 0., 1., 0., 0., 0., 1.];
        let origin = numbers("Origin", &[0.; 3])?;
        let spacing = numbers("Spacing", &[1.; 3])?;
        let direction = numbers("Direction", &identity)?;
        Ok(ImageFrame {
            origin: [origin[0], origin[1], origin[2]],
            spacing: [spacing[0], spacing[1], spacing[2]],
            direction: std::array::from_fn(|i| direction[i]),
        })
    }
}

/// Parses an extent `x0 x1 y0 y1 z0 z1` (inclusive point index ranges).
fn parse_extent(text: &str, file: &str, section: &str) -> Result<[i64; 6], VtkError> {
    let invalid = |message: String| {
        VtkError::Cell(CellError::Invalid {
            file: file.into(),
            section: section.into(),
            message,
        })
    };
    let values: Vec<i64> = text
        .split_ascii_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| invalid(format!("extent \"{text}\" is not six integers")))?;
    let extent: [i64; 6] = values
        .try_into()
        .map_err(|_| invalid(format!("extent \"{text}\" is not six integers")))?;
    for axis in 0..3 {
        if extent[2 * axis + 1] < extent[2 * axis] {
            return Err(invalid(format!(
                "extent \"{text}\" ends before it starts along {}",
                ["x", "y", "z"][axis]
            )));
        }
    }
    Ok(extent)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extents_and_image_points() {
        let e = parse_extent(" 1 2 0 0 0 1", "f", "s").unwrap();
        assert_eq!(extent_dims(&e), [2, 1, 2]);
        assert!(parse_extent("0 1 0 1 0", "f", "s").is_err());
        assert!(parse_extent("0 1 2 1 0 1", "f", "s").is_err());
        let identity = [1., 0., 0., 0., 1., 0., 0., 0., 1.];
        let p = image_points(&e, [10., 0., 0.], [0.5, 1., 2.], identity);
        assert_eq!(&p[..6], &[10.5, 0., 0., 11., 0., 0.]);
        assert_eq!(&p[6..9], &[10.5, 0., 2.]);
        // A direction swapping x and y.
        let swap = [0., 1., 0., 1., 0., 0., 0., 0., 1.];
        let q = image_points(&e, [0.; 3], [1.; 3], swap);
        assert_eq!(&q[..3], &[0., 1., 0.]);
    }
}
