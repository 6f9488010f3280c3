//! A `.vti` (ImageData) or legacy STRUCTURED_POINTS file as the regular
//! grid it is, for renderers of regular grids (shear-warp): the same
//! parsing as the tetrahedral readers, stopped before the cells are split.

use std::path::Path;
use tetray_mesh::cells::CellError;

use tetray_mesh::ScalarField;
use tetray_mesh::cells::{CellGrid, per_tuple, to_f32};

use super::{ImageGeometry, ReadOptions, VtkError, VtkRead};

/// An axis-aligned image: point `(i, j, k)` at `origin + (i, j, k) *
/// spacing`, point fields in VTK order (`i` fastest).
#[derive(Debug, Clone, PartialEq)]
pub struct ImageGrid {
    pub dims: [usize; 3],
    pub origin: [f64; 3],
    pub spacing: [f64; 3],
    /// One value per point; multi-component arrays as their magnitude
    /// (`<name>_magnitude`), as the mesh readers load them.
    pub fields: Vec<ScalarField>,
    pub warnings: Vec<String>,
}

/// Reads a serial `.vti` file (one Piece) or a legacy `.vtk`
/// STRUCTURED_POINTS file as an [`ImageGrid`]. Anything else (other
/// datasets, several pieces, a rotated `Direction`, a non-positive
/// spacing) is an error naming the file.
pub fn read_image_grid(path: &Path) -> Result<ImageGrid, VtkError> {
    let file = path.display().to_string();
    let (grid, image) = read_raw_image(path, &file)?;
    image_grid(&grid, image, &file)
}

/// Reads an image file once as both what it is: its regular grid, and its
/// cells split into tetrahedra exactly as [`super::read_vtu_file_with`] or
/// [`super::read_legacy_file_with`] split them.
pub fn read_image_data_with(
    path: &Path,
    opts: &ReadOptions,
) -> Result<(VtkRead, ImageGrid), VtkError> {
    let file = path.display().to_string();
    let (grid, image) = read_raw_image(path, &file)?;
    let image = image_grid(&grid, image, &file)?;
    Ok((super::assemble(grid, &file, opts)?, image))
}

/// The raw cells of an XML or legacy file and, for image data, where its
/// points lie.
fn read_raw_image(path: &Path, file: &str) -> Result<(CellGrid, Option<ImageGeometry>), VtkError> {
    let bytes = super::read_path(path)?;
    let xml = bytes.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'<');
    if xml {
        let mut doc = super::xml::tree::parse(&bytes, file)?;
        if doc.dataset != "UnstructuredGrid" && !doc.pieces.is_empty() {
            super::xml::structured::read_raw_image(&mut doc, file)
        } else {
            Ok((super::xml::read_raw(&bytes, file)?, None))
        }
    } else {
        super::legacy::read::read_raw(&bytes, file)
    }
}

/// The regular grid of image data another reader assembled (VTKHDF).
pub(crate) fn image_grid_of(
    grid: &CellGrid,
    geometry: ImageGeometry,
    file: &str,
) -> Result<ImageGrid, VtkError> {
    image_grid(grid, Some(geometry), file)
}

fn image_grid(
    grid: &CellGrid,
    image: Option<ImageGeometry>,
    file: &str,
) -> Result<ImageGrid, VtkError> {
    let invalid = |message: String| {
        VtkError::Cell(CellError::Invalid {
            file: file.into(),
            section: grid.dataset.into(),
            message,
        })
    };
    let Some(image) = image.filter(|_| grid.dataset == "ImageData") else {
        return Err(invalid(format!(
            "a regular grid needs a single-piece ImageData (.vti) or STRUCTURED_POINTS file, \
             not {}",
            if grid.dataset.is_empty() {
                "this dataset"
            } else {
                grid.dataset
            }
        )));
    };
    let identity = [1., 0., 0., 0., 1., 0., 0., 0., 1.];
    if image.direction != identity {
        return Err(invalid(format!(
            "Direction {:?} rotates the image: only axis-aligned images are regular grids here",
            image.direction
        )));
    }
    if image.spacing.iter().any(|&h| !(h.is_finite() && h > 0.0)) {
        return Err(invalid(format!(
            "spacing {:?} must be positive along every axis",
            image.spacing
        )));
    }
    let npoints = image.dims.iter().product::<usize>();
    let mut warnings = grid.warnings.clone();
    let mut fields = Vec::new();
    for array in &grid.point_arrays {
        if array.name == "vtkGhostType" {
            warnings.push("ghost flags ignored: the image is read whole".into());
            continue;
        }
        let (name, values) = per_tuple(array, npoints, file)?;
        fields.push(ScalarField {
            name,
            values: to_f32(&values, &array.section, file)?,
        });
    }
    if !grid.cell_arrays.is_empty() {
        warnings.push(format!(
            "{} cell arrays skipped: a regular grid carries point data",
            grid.cell_arrays.len()
        ));
    }
    Ok(ImageGrid {
        dims: image.dims,
        origin: image.origin,
        spacing: image.spacing,
        fields,
        warnings,
    })
}
