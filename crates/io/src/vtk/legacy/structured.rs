//! The structured datasets of legacy `.vtk` files (VTK file formats,
//! "Dataset Format"):
//! - STRUCTURED_POINTS: `DIMENSIONS nx ny nz`, `ORIGIN x y z`, `SPACING sx
//!   sy sz` (`ASPECT_RATIO` in old files);
//! - STRUCTURED_GRID: `DIMENSIONS`, then `POINTS n type` (read by the
//!   unstructured path);
//! - RECTILINEAR_GRID: `DIMENSIONS`, then `X_COORDINATES nx type` and the
//!   same for y and z.
//!
//! Cells come from the dimensions (`structured_grid.rs`); POINT_DATA holds
//! `nx ny nz` tuples and CELL_DATA one per cell.

use super::lex::Cursor;
use crate::vtk::ImageGeometry;
use crate::vtk::VtkError;
use crate::vtk::numeric::Scalar;
use tetray_mesh::cells::CellError;
use tetray_mesh::cells::CellGrid;
use tetray_mesh::cells::{add_cells, cell_count, image_points, point_count, rectilinear_points};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    StructuredPoints,
    StructuredGrid,
    RectilinearGrid,
}

impl Kind {
    pub fn of(dataset: &str) -> Option<Kind> {
        match dataset.to_ascii_uppercase().as_str() {
            "STRUCTURED_POINTS" => Some(Kind::StructuredPoints),
            "STRUCTURED_GRID" => Some(Kind::StructuredGrid),
            "RECTILINEAR_GRID" => Some(Kind::RectilinearGrid),
            _ => None,
        }
    }

    pub fn dataset(self) -> &'static str {
        match self {
            Kind::StructuredPoints => "ImageData",
            Kind::StructuredGrid => "StructuredGrid",
            Kind::RectilinearGrid => "RectilinearGrid",
        }
    }

    fn keyword(self) -> &'static str {
        match self {
            Kind::StructuredPoints => "STRUCTURED_POINTS",
            Kind::StructuredGrid => "STRUCTURED_GRID",
            Kind::RectilinearGrid => "RECTILINEAR_GRID",
        }
    }
}

/// What the structured sections declared.
pub(super) struct Structured {
    pub kind: Kind,
    dims: Option<([usize; 3], usize)>,
    origin: Option<[f64; 3]>,
    spacing: Option<[f64; 3]>,
    coordinates: [Option<Vec<f64>>; 3],
}

impl Structured {
    pub fn new(kind: Kind) -> Self {
        Structured {
            kind,
            dims: None,
            origin: None,
            spacing: None,
            coordinates: [None, None, None],
        }
    }

    /// Reads a structured section; `false` when `keyword` is not one.
    pub fn section(&mut self, keyword: &str, cur: &mut Cursor<'_>) -> Result<bool, VtkError> {
        let line = cur.line();
        match keyword {
            "DIMENSIONS" => {
                let dims = [0, 1, 2].map(|_| cur.count("a dimension"));
                let [a, b, c] = dims;
                self.dims = Some(([a?, b?, c?], line));
            }
            "ORIGIN" => self.origin = Some(three(cur, "ORIGIN")?),
            "SPACING" | "ASPECT_RATIO" => self.spacing = Some(three(cur, keyword)?),
            "X_COORDINATES" | "Y_COORDINATES" | "Z_COORDINATES" => {
                let axis = usize::from(keyword.as_bytes()[0] - b'X');
                let n = cur.count(&format!("the {keyword} count"))?;
                let section = format!("line {line}, {keyword}");
                let name = cur.word(&format!("the data type of {section}"))?;
                let ty = Scalar::from_legacy_name(name).ok_or_else(|| {
                    VtkError::Cell(CellError::Unsupported {
                        file: cur.file.into(),
                        section: section.clone(),
                        what: "data type",
                        value: name.into(),
                    })
                })?;
                self.coordinates[axis] = Some(cur.floats(ty, n, &section)?);
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The point and cell counts the dimensions give, checked.
    pub fn counts(&self, file: &str) -> Result<(usize, usize), VtkError> {
        let (dims, line) = self.dims.ok_or_else(|| {
            VtkError::Cell(CellError::Invalid {
                file: file.into(),
                section: self.kind.keyword().into(),
                message: "no DIMENSIONS".into(),
            })
        })?;
        let n = point_count(dims, file, &format!("line {line}, DIMENSIONS"))?;
        let cells = cell_count(dims);
        // An image's (and a rectilinear grid's) points and cells are made,
        // not read: nothing in the file bounds them but the memory.
        crate::preflight::check(
            file,
            || format!("the grid ({} x {} x {} points)", dims[0], dims[1], dims[2]),
            crate::preflight::grid_bytes(n as u64, cells as u64),
        )?;
        Ok((n, cells))
    }

    /// A STRUCTURED_POINTS dataset's index space (after [`Self::finish`]).
    pub fn image(&self) -> Option<ImageGeometry> {
        let (Kind::StructuredPoints, Some((dims, _))) = (self.kind, self.dims) else {
            return None;
        };
        Some(ImageGeometry {
            dims,
            origin: self.origin.unwrap_or([0.; 3]),
            spacing: self.spacing.unwrap_or([1.; 3]),
            direction: [1., 0., 0., 0., 1., 0., 0., 0., 1.],
        })
    }

    /// Fills the grid's points (unless POINTS gave them) and cells.
    pub fn finish(&self, grid: &mut CellGrid, file: &str) -> Result<(), VtkError> {
        let (npoints, _) = self.counts(file)?;
        let Some((dims, line)) = self.dims else {
            return Ok(());
        };
        let keyword = self.kind.keyword();
        let invalid = |message: String| {
            VtkError::Cell(CellError::Invalid {
                file: file.into(),
                section: keyword.into(),
                message,
            })
        };
        if !grid.types.is_empty() {
            return Err(invalid("CELLS in a structured dataset".into()));
        }
        match self.kind {
            Kind::StructuredPoints => {
                let extent = [0, 1, 2].map(|a| [0, dims[a] as i64 - 1]).concat();
                let extent: [i64; 6] = extent.try_into().unwrap_or([0; 6]);
                let identity = [1., 0., 0., 0., 1., 0., 0., 0., 1.];
                let origin = self.origin.unwrap_or([0.; 3]);
                let spacing = self.spacing.unwrap_or([1.; 3]);
                grid.points = image_points(&extent, origin, spacing, identity);
                grid.points_section = format!("line {line}, DIMENSIONS/ORIGIN/SPACING");
            }
            Kind::RectilinearGrid => {
                let mut axes = Vec::with_capacity(3);
                for (a, c) in self.coordinates.iter().enumerate() {
                    let name = ["X", "Y", "Z"][a];
                    let Some(c) = c else {
                        return Err(invalid(format!("no {name}_COORDINATES")));
                    };
                    if c.len() != dims[a] {
                        return Err(VtkError::Cell(CellError::CountMismatch {
                            file: file.into(),
                            section: format!("{name}_COORDINATES"),
                            what: format!("coordinates (DIMENSIONS on line {line})"),
                            expected: dims[a],
                            found: c.len(),
                        }));
                    }
                    axes.push(c.as_slice());
                }
                grid.points = rectilinear_points(axes[0], axes[1], axes[2]);
                grid.points_section = format!("line {line}, X/Y/Z_COORDINATES");
            }
            Kind::StructuredGrid => {
                if grid.points.len() != 3 * npoints {
                    return Err(VtkError::Cell(CellError::CountMismatch {
                        file: file.into(),
                        section: grid.points_section.clone(),
                        what: format!("points (DIMENSIONS {dims:?} on line {line})"),
                        expected: npoints,
                        found: grid.points.len() / 3,
                    }));
                }
            }
        }
        add_cells(dims, grid);
        Ok(())
    }
}

/// Three ASCII numbers (ORIGIN and SPACING are text in BINARY files too).
fn three(cur: &mut Cursor<'_>, keyword: &str) -> Result<[f64; 3], VtkError> {
    let mut out = [0.0; 3];
    for v in &mut out {
        let w = cur.word(&format!("three {keyword} values"))?;
        *v = w
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| cur.syntax(format!("{keyword}: \"{w}\" is not a finite number")))?;
    }
    Ok(out)
}
