//! A VTKHDF `ImageData`: the extent, origin, spacing and direction of the
//! root's attributes, arrays shaped (z, y, x[, components]) with a leading
//! time dimension in a temporal file.

use hdf5_reader::group::Group;
use tetray_mesh::cells::{
    CellArray, CellGrid, add_cells, cell_count, extent_dims, image_points, point_count,
};

use super::H5;
use super::VtkHdfError;
use super::steps::Steps;
use crate::vtk::ImageGeometry;

pub(super) fn read(
    h5: &H5,
    root: &Group,
    steps: &Steps,
    step: Option<usize>,
) -> Result<(CellGrid, ImageGeometry), VtkHdfError> {
    let attribute = |name: &str, len: usize| -> Result<Option<Vec<f64>>, VtkHdfError> {
        match h5.numeric_attribute(root, name) {
            Some(v) if v.len() == len && v.iter().all(|x| x.is_finite()) => Ok(Some(v)),
            Some(v) => Err(h5.invalid(
                name,
                format!("{} values where {len} finite numbers belong", v.len()),
            )),
            None => Ok(None),
        }
    };
    let whole = attribute("WholeExtent", 6)?.ok_or_else(|| VtkHdfError::Missing {
        file: h5.name.clone(),
        what: "WholeExtent attribute (the image's extent)".into(),
    })?;
    let extent: [i64; 6] = std::array::from_fn(|i| whole[i] as i64);
    if (0..3).any(|a| extent[2 * a + 1] < extent[2 * a]) {
        return Err(h5.invalid("WholeExtent", format!("{extent:?} is empty")));
    }
    let origin = attribute("Origin", 3)?.map_or([0.0; 3], |v| [v[0], v[1], v[2]]);
    let spacing = attribute("Spacing", 3)?.map_or([1.0; 3], |v| [v[0], v[1], v[2]]);
    let direction = attribute("Direction", 9)?.map_or([1., 0., 0., 0., 1., 0., 0., 0., 1.], |v| {
        std::array::from_fn(|i| v[i])
    });
    let dims = extent_dims(&extent);
    point_count(dims, &h5.name, "WholeExtent").map_err(crate::vtk::VtkError::from)?;
    let ncells = cell_count(dims);
    // An image's points and cells are made, not read: nothing in the file
    // bounds them but the memory they take.
    crate::preflight::check(
        &h5.name,
        || format!("the image ({} x {} x {} points)", dims[0], dims[1], dims[2]),
        crate::preflight::grid_bytes(dims.iter().map(|&d| d as u64).product(), ncells as u64),
    )?;
    // The arrays first: their sizes check the extent before the points and
    // cells it implies are made.
    let point_arrays = arrays(h5, steps, step, "PointData", dims)?;
    let cell_dims = if ncells == 0 {
        [0; 3]
    } else {
        dims.map(|d| d.saturating_sub(1).max(1))
    };
    let cell_arrays = arrays(h5, steps, step, "CellData", cell_dims)?;
    let mut grid = CellGrid {
        points: image_points(&extent, origin, spacing, direction),
        points_section: "WholeExtent".into(),
        dataset: "ImageData",
        point_arrays,
        cell_arrays,
        ..CellGrid::default()
    };
    add_cells(dims, &mut grid);
    let geometry = ImageGeometry {
        dims,
        origin: [0, 1, 2].map(|a| grid.points.get(a).copied().unwrap_or(origin[a])),
        spacing,
        direction,
    };
    Ok((grid, geometry))
}

/// The arrays of `kind` over a grid of `spatial` (x, y, z) tuples: the step's slice of a
/// temporal array, or the whole array.
fn arrays(
    h5: &H5,
    steps: &Steps,
    step: Option<usize>,
    kind: &str,
    spatial: [usize; 3],
) -> Result<Vec<CellArray>, VtkHdfError> {
    let tuples: usize = spatial.iter().product();
    let path = format!("/VTKHDF/{kind}");
    let Some(group) = h5.group(&path) else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for name in h5.dataset_names(&group, &path)? {
        let ds = h5.require_dataset(&group, &path, &name)?;
        if !matches!(
            ds.dtype(),
            hdf5_reader::Datatype::FloatingPoint { .. } | hdf5_reader::Datatype::FixedPoint { .. }
        ) {
            continue;
        }
        let what = format!("{kind}/{name}");
        let shape = H5::shape(&ds);
        // A temporal array has a leading time dimension, [~steps, z, y, x
        // (, components)]: the step's row is its offset, or the step itself
        // when the file stores none (rows may be replayed by several steps).
        let temporal =
            steps.temporal() && shape.len() >= 4 && shape[1..4].iter().rev().eq(spatial.iter());
        let (values, components) = if temporal {
            let row = match steps.offset(&format!("{kind}Offsets/{name}"), step) {
                Some(row) => usize::try_from(row)
                    .map_err(|_| h5.invalid(&what, format!("step offset {row} is negative")))?,
                None => step.unwrap_or(0),
            };
            if row >= shape[0] {
                return Err(h5.invalid(
                    &what,
                    format!("step row {row} is past its {} rows", shape[0]),
                ));
            }
            let (values, per_row) = h5.rows_f64(&ds, &what, row, 1)?;
            (values, per_row / tuples)
        } else if shape.len() >= 3 && shape[..3].iter().rev().eq(spatial.iter()) {
            let (values, per_row) = h5.rows_f64(&ds, &what, 0, shape[0])?;
            (values, per_row * shape[0] / tuples.max(1))
        } else if matches!(shape.len(), 1 | 2) && shape[0] == tuples {
            // Flattened, x fastest.
            let (values, per_row) = h5.rows_f64(&ds, &what, 0, shape[0])?;
            (values, per_row)
        } else {
            let expected: Vec<usize> = spatial.iter().rev().copied().collect();
            return Err(h5.invalid(
                &what,
                format!("shape {shape:?} is not the grid's {expected:?} (z, y, x)"),
            ));
        };
        out.push(CellArray {
            name,
            components: components.max(1),
            values,
            section: what,
            defined: None,
        });
    }
    Ok(out)
}
