//! Exodus II reader (SEACAS; netCDF classic CDF-1/2/5 or netCDF-4/HDF5
//! containers, read by the pure-Rust `netcdf-reader`).
//!
//! The reader turns the file into the same raw grid as the VTK readers
//! (points in f64, cells with their VTK type, point and cell arrays); the
//! shared VTK assembly step splits the cells and makes the fields.
//!
//! Conventions:
//! - element blocks of a volume type (tetra, hex, wedge, pyramid, linear or
//!   quadratic) are joined into one mesh, in VTK node order (one table per
//!   cell type in `elements.rs`); circle, sphere, bar, beam, truss,
//!   triangle, quad and shell blocks are skipped with a warning that names
//!   them; a file with no volume block is an error;
//! - one time step is read: the one asked for, the one whose time is
//!   nearest the time asked for, else the first;
//! - nodal variables become point arrays, element variables cell arrays
//!   (averaged to points over the blocks that define them); x/y/z
//!   component triples (`VX VY VZ`, `V_X V_Y V_Z`, `vel_x vel_y vel_z`)
//!   are also one 3-component array (`V`, `vel`), kept beside the
//!   components;
//! - quadratic blocks become VTK's quadratic cells (24-27, 29), subdivided
//!   through their mid-edge, face and body nodes like those of a VTK file
//!   (or reduced to their corners with [`Linearize::Corners`]).

mod elements;
mod error;
mod nc;
mod read;
mod vars;

use std::path::Path;

pub use error::ExodusError;

pub use tetray_mesh::ElementBlock;
use tetray_mesh::TetMesh;
use tetray_mesh::cells::{CellCounts, Linearize, ReadOptions, assemble_with};

/// Which time step to read. At most one of the two may be given.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ExodusOptions {
    /// 0-based time step (default: the first).
    pub time_step: Option<usize>,
    /// Read the step whose stored time is nearest this one.
    pub time: Option<f64>,
    /// Quadratic blocks (TETRA10, HEX20, HEX27, WEDGE15, PYRAMID13):
    /// subdivided through all their nodes (default) or their corners only.
    pub linearize: Linearize,
}

/// What [`read_exodus_file`] returns.
#[derive(Debug, Clone, PartialEq)]
pub struct ExodusRead {
    pub mesh: TetMesh,
    /// Things read past or converted (skipped blocks, cell data averaged...).
    pub warnings: Vec<String>,
    pub cells: CellCounts,
    /// The stored times (`time_whole`), one per time step.
    pub times: Vec<f64>,
    /// The step read (0-based), `None` when the file stores none.
    pub time_step: Option<usize>,
    pub blocks: Vec<ElementBlock>,
    /// The netCDF container ("Cdf1", "Nc4"...).
    pub container: String,
    /// The points are stored relative to this origin (f64; see
    /// [`tetray_mesh::centring_origin`]): a node's coordinates in the file are
    /// `origin + point`.
    pub origin: glam::DVec3,
    /// Per tetrahedron, the 0-based number of the element it was split
    /// from, counted across all element blocks (skipped blocks included).
    pub tet_cells: Vec<u32>,
}

/// Reads an Exodus II file.
///
/// # Errors
/// [`ExodusError`] naming the file and what is wrong with it.
pub fn read_exodus_file(path: &Path, opts: &ExodusOptions) -> Result<ExodusRead, ExodusError> {
    let name = path.display().to_string();
    // Not read whole: a file larger than the memory is refused by the
    // preflight on its header's sizes, before anything large is read.
    read(nc::Nc::open(path, &name)?, &name, opts)
}

/// Reads an Exodus II file held in memory; `name` is used in messages.
///
/// # Errors
/// As [`read_exodus_file`].
pub fn read_exodus_bytes(
    bytes: &[u8],
    name: &str,
    opts: &ExodusOptions,
) -> Result<ExodusRead, ExodusError> {
    read(nc::Nc::from_bytes(bytes.to_vec(), name)?, name, opts)
}

fn read(nc: nc::Nc<'_>, name: &str, opts: &ExodusOptions) -> Result<ExodusRead, ExodusError> {
    let (grid, meta) = read::read_raw(nc, name, opts)?;
    let vtk = ReadOptions {
        linearize: opts.linearize,
    };
    let read = assemble_with(grid, name, &vtk)?;
    Ok(ExodusRead {
        mesh: read.mesh,
        warnings: read.warnings,
        cells: read.cells,
        times: meta.times,
        time_step: meta.time_step,
        blocks: meta.blocks,
        container: meta.container,
        origin: read.origin,
        tet_cells: read.tet_cells,
    })
}

/// A kept (volume) block: where its elements start among the grid's cells.
pub(crate) struct KeptBlock {
    /// 1-based position among the file's blocks (the `N` of `connectN`).
    pub number: usize,
    pub first_cell: usize,
    pub cells: usize,
}
