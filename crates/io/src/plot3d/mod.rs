//! PLOT3D binary files: a structured curvilinear grid (xyz) and its
//! solution (q), read into a tetrahedral mesh with point scalars, or as
//! structured arrays ([`Plot3dGrid`]); and written back (`write.rs`).
//!
//! The layout (byte order, IBLANK, grid count, Fortran records) is decided
//! from the header and the file size (see `layout.rs`). Every hexahedron is
//! split into 5 tetrahedra with alternating parity
//! ([`tetray_mesh::structured`]), so the mesh is conforming; `split.rs` counts
//! that split without building it ([`plot3d_split_counts`]).

mod grid;
mod layout;
mod split;
mod write;

use std::path::Path;

use glam::Vec3;
use rayon::prelude::*;

use tetray_mesh::structured::hex_count;
use tetray_mesh::{ScalarField, TetMesh};

use crate::IoError;
pub use grid::{
    Plot3dGrid, Plot3dSolution, Plot3dSource, read_plot3d_grid_bytes, read_plot3d_grid_files,
};
use split::{Split, split_grid};
pub use split::{SplitCounts, plot3d_split_counts};
pub use write::{
    plot3d_q_bytes, plot3d_xyz_bytes, write_plot3d_files, write_plot3d_q, write_plot3d_xyz,
};

/// Ratio of specific heats of the ideal gas used for `pressure`.
pub const GAMMA: f64 = 1.4;

/// What the PLOT3D reader returns.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot3dRead {
    pub mesh: TetMesh,
    /// Points along i, j, k.
    pub dims: [usize; 3],
    /// The face diagonals of the split join points with `(i + j + k) % 2 ==
    /// diagonal_parity` (see [`tetray_mesh::structured::structured_tets`]).
    pub diagonal_parity: usize,
    /// Hexahedra of the grid (before blanking).
    pub hexahedra: usize,
    /// Hexahedra left out because a corner has IBLANK 0.
    pub blanked_hexahedra: usize,
    /// Tetrahedra of the split that were flat (collapsed hexahedra) and
    /// were dropped.
    pub degenerate_dropped: usize,
    /// Tetrahedra that came out negatively oriented (a left-handed grid, or
    /// a folded cell) and were reoriented.
    pub reoriented: usize,
    /// Trailing bytes, layouts, dropped cells, as sentences.
    pub warnings: Vec<String>,
    /// The four solution constants fsmach, alpha, re, time (when a q file
    /// was read).
    pub conditions: Option<[f32; 4]>,
}

/// A file's bytes, or [`IoError::Io`] naming it.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, IoError> {
    std::fs::read(path).map_err(|source| IoError::Io {
        file: path.display().to_string(),
        source,
    })
}

/// Reads a grid file and optionally its solution file. Without a solution
/// the mesh has no fields.
///
/// # Errors
/// [`IoError::Io`] when a file cannot be read; the errors of
/// [`read_plot3d_bytes`].
pub fn read_plot3d_files(xyz: &Path, q: Option<&Path>) -> Result<Plot3dRead, IoError> {
    let xyz_bytes = read_file(xyz)?;
    let q_bytes = q.map(read_file).transpose()?;
    let names = Names {
        xyz: xyz.display().to_string(),
        q: q.map_or_else(String::new, |q| q.display().to_string()),
    };
    read_plot3d(&xyz_bytes, q_bytes.as_deref(), &names)
}

/// Reads a grid and optionally its solution held in memory; `name` is
/// used in messages (the solution as "`name` (q)").
///
/// # Errors
/// [`IoError::Plot3dHeader`] for a header that fits no known layout,
/// [`IoError::Plot3dTruncated`] for a file too short for its header,
/// [`IoError::Plot3dDimsMismatch`] when the solution is for another grid.
pub fn read_plot3d_bytes(xyz: &[u8], q: Option<&[u8]>, name: &str) -> Result<Plot3dRead, IoError> {
    let names = Names {
        xyz: name.to_string(),
        q: format!("{name} (q)"),
    };
    read_plot3d(xyz, q, &names)
}

struct Names {
    xyz: String,
    q: String,
}

fn read_plot3d(xyz: &[u8], q: Option<&[u8]>, names: &Names) -> Result<Plot3dRead, IoError> {
    let grid::Parsed { grid, mut warnings } = grid::parse(xyz, q, &names.xyz, &names.q)?;
    let Plot3dGrid {
        dims,
        xyz: [x, y, z],
        iblank,
        solution,
    } = grid;
    let points: Vec<Vec3> = (0..x.len())
        .into_par_iter()
        .map(|i| Vec3::new(x[i], y[i], z[i]))
        .collect();
    drop((x, y, z));
    let conditions = solution.as_ref().map(|s| s.conditions);
    let fields = solution.map_or_else(Vec::new, derived_fields);

    let Split { tets, counts } = split_grid(dims, &points, iblank.as_deref());
    let SplitCounts {
        diagonal_parity,
        blanked_hexahedra,
        degenerate_dropped,
        reoriented,
        ..
    } = counts;
    let hexahedra = hex_count(dims);
    if blanked_hexahedra > 0 {
        warnings.push(format!(
            "{blanked_hexahedra} hexahedra with a corner blanked (IBLANK 0) were left out"
        ));
    }
    if degenerate_dropped > 0 {
        warnings.push(format!(
            "{degenerate_dropped} flat tetrahedra from collapsed hexahedra were dropped"
        ));
    }
    if reoriented > 0 && reoriented < tets.len() {
        warnings.push(format!(
            "{reoriented} of {} tetrahedra were inverted (folded grid cells?) and were reoriented",
            tets.len()
        ));
    }
    Ok(Plot3dRead {
        mesh: TetMesh {
            points,
            tets,
            fields,
        },
        dims,
        diagonal_parity,
        hexahedra,
        blanked_hexahedra,
        degenerate_dropped,
        reoriented,
        warnings,
        conditions,
    })
}

/// The scalar fields of a solution, density first.
fn derived_fields(solution: Plot3dSolution) -> Vec<ScalarField> {
    let [rho, mx, my, mz, energy] = solution.q;
    let n = rho.len();

    // Derived in f64: |m|, |m| / rho and the ideal-gas pressure
    // p = (gamma - 1) (E - |m|^2 / (2 rho)). A zero density gives an
    // infinite value, which validation reports with the field and point.
    let momentum: Vec<f64> = (0..n)
        .into_par_iter()
        .map(|i| Vec3::new(mx[i], my[i], mz[i]).as_dvec3().length())
        .collect();
    let derive = |f: &(dyn Fn(usize) -> f64 + Sync)| -> Vec<f32> {
        (0..n).into_par_iter().map(|i| f(i) as f32).collect()
    };
    let velocity = derive(&|i| momentum[i] / f64::from(rho[i]));
    let pressure = derive(&|i| {
        let rho = f64::from(rho[i]);
        (GAMMA - 1.0) * (f64::from(energy[i]) - 0.5 * momentum[i] * momentum[i] / rho)
    });
    let momentum_magnitude = momentum.iter().map(|&m| m as f32).collect();
    let field = |name: &str, values: Vec<f32>| ScalarField {
        name: name.to_string(),
        values,
    };
    vec![
        field("density", rho),
        field("pressure", pressure),
        field("velocity_magnitude", velocity),
        field("stagnation_energy", energy),
        field("momentum_magnitude", momentum_magnitude),
    ]
}
