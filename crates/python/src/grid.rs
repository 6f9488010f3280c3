//! `Grid`: a dataset handed over from Python as arrays, held as the raw
//! [`CellGrid`] every reader produces. Shapes, offsets and array lengths
//! are checked here (the readers check the same of a file before building
//! a grid); point indices, NaN points and cell types are checked by the
//! assembly itself, with the messages a file gets.

use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tetray_mesh::cells::{self, CellArray, CellGrid};

use crate::value_error;

/// A mesh from Python: points, VTK cells and point/cell arrays, or a
/// structured grid's points and dimensions.
#[pyclass(module = "tetray._native", frozen)]
pub struct Grid {
    pub(crate) grid: CellGrid,
    pub(crate) name: String,
}

#[pymethods]
impl Grid {
    /// An unstructured grid: `points` (n, 3) float64, `connectivity` and
    /// `offsets` (VTK's: `offsets` has one entry per cell plus one, from 0)
    /// int64, `celltypes` int64 (VTK cell type ids), and dicts of point and
    /// cell arrays, each (n,) or (n, k) float64.
    #[staticmethod]
    #[pyo3(signature = (points, connectivity, offsets, celltypes, point_data, cell_data, name))]
    fn unstructured(
        points: PyReadonlyArray2<'_, f64>,
        connectivity: PyReadonlyArray1<'_, i64>,
        offsets: PyReadonlyArray1<'_, i64>,
        celltypes: PyReadonlyArray1<'_, i64>,
        point_data: &Bound<'_, PyDict>,
        cell_data: &Bound<'_, PyDict>,
        name: String,
    ) -> PyResult<Grid> {
        let npoints = points_shape(&points)?;
        let types = celltypes.as_array().to_vec();
        let offsets = offsets.as_array();
        let connectivity = connectivity.as_array().to_vec();
        if offsets.len() != types.len() + 1 {
            return Err(value_error(format!(
                "offsets: {} entries for {} cells; VTK offsets have one per cell plus one \
                 (starting at 0)",
                offsets.len(),
                types.len()
            )));
        }
        let mut checked = Vec::with_capacity(offsets.len());
        let mut previous = 0usize;
        for (c, &o) in offsets.iter().enumerate() {
            let ok = usize::try_from(o)
                .ok()
                .filter(|&o| o >= previous && o <= connectivity.len() && (c > 0 || o == 0));
            let Some(o) = ok else {
                return Err(value_error(format!(
                    "offsets[{c}] is {o}: offsets must start at 0, never decrease and stay \
                     within the {} connectivity entries",
                    connectivity.len()
                )));
            };
            checked.push(o);
            previous = o;
        }
        if previous != connectivity.len() {
            return Err(value_error(format!(
                "the last offset is {previous} but there are {} connectivity entries",
                connectivity.len()
            )));
        }
        let ncells = types.len();
        let mut grid = CellGrid {
            points: flat_points(&points),
            points_section: "points".into(),
            offsets: if ncells == 0 { Vec::new() } else { checked },
            connectivity,
            types,
            dataset: "UnstructuredGrid",
            ..CellGrid::default()
        };
        grid.point_arrays = arrays(point_data, npoints, "point_data")?;
        grid.cell_arrays = arrays(cell_data, ncells, "cell_data")?;
        Ok(Grid { grid, name })
    }

    /// A structured grid of `dims` points (i fastest, VTK's order) at
    /// `points` (n, 3): one hexahedron per grid cell, as a `.vts` or `.vti`
    /// file's grid. `dataset` is "StructuredGrid", "RectilinearGrid" or
    /// "ImageData" (for the report).
    #[staticmethod]
    #[pyo3(signature = (dims, points, point_data, cell_data, dataset, name))]
    fn structured(
        dims: (usize, usize, usize),
        points: PyReadonlyArray2<'_, f64>,
        point_data: &Bound<'_, PyDict>,
        cell_data: &Bound<'_, PyDict>,
        dataset: &str,
        name: String,
    ) -> PyResult<Grid> {
        let dims = [dims.0, dims.1, dims.2];
        let npoints = points_shape(&points)?;
        let expected = cells::point_count(dims, &name, "dimensions")
            .map_err(|e| value_error(e.to_string()))?;
        if expected != npoints {
            return Err(value_error(format!(
                "dimensions {}x{}x{} need {expected} points, got {npoints}",
                dims[0], dims[1], dims[2]
            )));
        }
        let dataset: &'static str = match dataset {
            "StructuredGrid" => "StructuredGrid",
            "RectilinearGrid" => "RectilinearGrid",
            "ImageData" => "ImageData",
            other => return Err(value_error(format!("unknown structured dataset {other:?}"))),
        };
        let mut grid = CellGrid {
            points: flat_points(&points),
            points_section: "points".into(),
            dataset,
            ..CellGrid::default()
        };
        cells::add_cells(dims, &mut grid);
        grid.point_arrays = arrays(point_data, npoints, "point_data")?;
        grid.cell_arrays = arrays(cell_data, cells::cell_count(dims), "cell_data")?;
        Ok(Grid { grid, name })
    }

    /// Points, cells (as given) and arrays.
    fn __repr__(&self) -> String {
        format!(
            "<tetray Grid {:?}: {} points, {} cells, {} point arrays, {} cell arrays>",
            self.name,
            self.grid.points.len() / 3,
            self.grid.types.len(),
            self.grid.point_arrays.len(),
            self.grid.cell_arrays.len()
        )
    }
}

/// The number of points of an (n, 3) array.
fn points_shape(points: &PyReadonlyArray2<'_, f64>) -> PyResult<usize> {
    match points.shape() {
        [n, 3] => Ok(*n),
        shape => Err(value_error(format!(
            "points must have shape (n, 3), got {shape:?}"
        ))),
    }
}

/// x, y, z per point: one pass over the array (a copy: the grid owns its
/// points, as a reader's does).
fn flat_points(points: &PyReadonlyArray2<'_, f64>) -> Vec<f64> {
    match points.as_slice() {
        Ok(slice) => slice.to_vec(),
        Err(_) => points.as_array().iter().copied().collect(),
    }
}

/// The arrays of a dict: name -> (tuples,) or (tuples, k) float64.
fn arrays(dict: &Bound<'_, PyDict>, tuples: usize, place: &str) -> PyResult<Vec<CellArray>> {
    let mut out = Vec::with_capacity(dict.len());
    for (key, value) in dict.iter() {
        let name: String = key
            .extract()
            .map_err(|_| value_error(format!("{place}: array names must be strings")))?;
        let section = format!("{place}[{name:?}]");
        let (values, components) = match value.extract::<PyReadonlyArray1<'_, f64>>() {
            Ok(a) => (a.as_array().to_vec(), 1),
            _ => match value.extract::<PyReadonlyArray2<'_, f64>>() {
                Ok(a) => {
                    let k = a.shape()[1];
                    (a.as_array().iter().copied().collect(), k)
                }
                _ => {
                    return Err(value_error(format!(
                        "{section}: expected a float64 array of shape (n,) or (n, k)"
                    )));
                }
            },
        };
        if components == 0 || values.len() != tuples * components {
            return Err(value_error(format!(
                "{section}: {} values in {components} components for {tuples} tuples",
                values.len()
            )));
        }
        out.push(CellArray {
            name,
            components,
            values,
            section,
            defined: None,
        });
    }
    Ok(out)
}
