//! The cell model every reader produces: f64 points, cells with their VTK
//! type, point and cell arrays, and what the pieces of a file carried.

use super::PieceCounts;
use super::polyhedron::PolyhedronFaces;

/// A named point or cell array as read, `components` values per tuple.
#[derive(Debug, Clone)]
pub struct CellArray {
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
pub struct CellGrid {
    /// x, y, z per point.
    pub points: Vec<f64>,
    pub points_section: String,
    /// Start of each cell in `connectivity`, plus the end: `ncells + 1`
    /// entries (or empty when there are no cells).
    pub offsets: Vec<usize>,
    pub connectivity: Vec<i64>,
    pub types: Vec<i64>,
    pub point_arrays: Vec<CellArray>,
    pub cell_arrays: Vec<CellArray>,
    /// Faces of the polyhedra (type 42) whose file lists them apart from
    /// the connectivity (XML); a polyhedron missing here carries its face
    /// stream in the connectivity (legacy).
    pub polyhedron_faces: PolyhedronFaces,
    pub warnings: Vec<String>,
    /// The VTK dataset type read ("UnstructuredGrid", "StructuredGrid"...).
    pub dataset: &'static str,
    /// The point array holding global point ids, when the file marks one
    /// (`<PointData GlobalIds="...">`): pieces are welded by it.
    pub global_ids: Option<String>,
    /// Pieces, welding and ghost cells, for the load report.
    pub pieces: PieceCounts,
    /// The number of each cell in the file(s) read, for reports of cells
    /// left out (empty: each cell's index). It differs from the index once
    /// cells are dropped or grids joined: a file's cells are numbered as it
    /// lists them, ghost and hidden cells included; the cells of joined
    /// pieces and blocks are numbered on from those of the pieces before
    /// them, in the order the parallel or multi-block file names them (see
    /// `pieces.rs`); Exodus elements by their 0-based number across all
    /// element blocks, skipped blocks included.
    pub cell_numbers: Vec<u32>,
    /// How many cells the numbering spans (the cells read, dropped ones
    /// included); only meaningful when `cell_numbers` is not empty.
    pub cells_numbered: usize,
}

impl CellGrid {
    /// The number of cell `c` in the file(s) read (see `cell_numbers`).
    pub fn cell_number(&self, c: usize) -> u32 {
        self.cell_numbers.get(c).copied().unwrap_or(c as u32)
    }

    /// How many cell numbers the grid spans, dropped cells included.
    pub fn numbered_cells(&self) -> usize {
        if self.cell_numbers.is_empty() {
            self.types.len()
        } else {
            self.cells_numbered
        }
    }
}
