//! PLOT3D binary readers: a structured curvilinear grid (xyz) and its
//! solution (q), turned into a tetrahedral mesh with point scalars.
//!
//! The layout (byte order, IBLANK, grid count, Fortran records) is decided
//! from the header and the file size (see `layout.rs`). Every hexahedron is
//! split into 5 tetrahedra with alternating parity
//! ([`crate::structured`]), so the mesh is conforming.

mod layout;

use std::path::Path;

use glam::Vec3;
use rayon::prelude::*;

use crate::structured::{hex_count, structured_tets};
use crate::{tet_shape, MeshError, ScalarField, TetMesh};
use layout::{detect, Kind, Layout};

/// Ratio of specific heats of the ideal gas used for `pressure`.
pub const GAMMA: f64 = 1.4;

/// What the PLOT3D reader returns.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot3dRead {
    pub mesh: TetMesh,
    /// Points along i, j, k.
    pub dims: [usize; 3],
    /// The face diagonals of the split join points with `(i + j + k) % 2 ==
    /// diagonal_parity` (see [`crate::structured::structured_tets`]).
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

/// Reads a grid file and optionally its solution file. Without a solution
/// the mesh has no fields.
///
/// # Errors
/// [`MeshError::Io`] when a file cannot be read; the errors of
/// [`read_plot3d_bytes`].
pub fn read_plot3d_files(xyz: &Path, q: Option<&Path>) -> Result<Plot3dRead, MeshError> {
    let read = |path: &Path| {
        std::fs::read(path).map_err(|source| MeshError::Io {
            file: path.display().to_string(),
            source,
        })
    };
    let xyz_bytes = read(xyz)?;
    let q_bytes = q.map(read).transpose()?;
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
/// [`MeshError::Plot3dHeader`] for a header that fits no known layout,
/// [`MeshError::Plot3dTruncated`] for a file too short for its header,
/// [`MeshError::Plot3dDimsMismatch`] when the solution is for another grid.
pub fn read_plot3d_bytes(
    xyz: &[u8],
    q: Option<&[u8]>,
    name: &str,
) -> Result<Plot3dRead, MeshError> {
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

fn read_plot3d(xyz: &[u8], q: Option<&[u8]>, names: &Names) -> Result<Plot3dRead, MeshError> {
    let grid = detect(xyz, &names.xyz, Kind::Grid)?;
    let dims = grid.dims;
    let n: usize = dims.iter().product();
    let mut warnings = Vec::new();
    if grid.trailing > 0 {
        warnings.push(format!(
            "{}: {} bytes after the grid data were ignored ({})",
            names.xyz, grid.trailing, grid.description
        ));
    }
    let coords = grid.endian.f32s(xyz, grid.data, 3 * n);
    let points: Vec<Vec3> = (0..n)
        .map(|i| Vec3::new(coords[i], coords[n + i], coords[2 * n + i]))
        .collect();
    let iblank = grid
        .iblank
        .then(|| grid.endian.i32s(xyz, grid.data + 12 * n, n));

    let (fields, conditions) = match q {
        Some(q) => {
            let (fields, conditions, solution) = read_solution(q, names, &grid)?;
            if solution.trailing > 0 {
                warnings.push(format!(
                    "{}: {} bytes after the solution data were ignored",
                    names.q, solution.trailing
                ));
            }
            (fields, Some(conditions))
        }
        None => (Vec::new(), None),
    };

    let split = split_grid(dims, &points, iblank.as_deref());
    let Split {
        tets,
        diagonal_parity,
        blanked_hexahedra,
        degenerate_dropped,
        reoriented,
    } = split;
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

/// Reads the solution and derives the scalar fields, density first.
fn read_solution(
    q: &[u8],
    names: &Names,
    grid: &Layout,
) -> Result<(Vec<ScalarField>, [f32; 4], Layout), MeshError> {
    let solution = detect(q, &names.q, Kind::Solution)?;
    if solution.dims != grid.dims {
        return Err(MeshError::Plot3dDimsMismatch {
            xyz_file: names.xyz.clone(),
            q_file: names.q.clone(),
            xyz_dims: grid.dims,
            q_dims: solution.dims,
        });
    }
    let n: usize = grid.dims.iter().product();
    let c = solution.endian.f32s(q, solution.conditions, 4);
    let conditions = [c[0], c[1], c[2], c[3]];
    let values = solution.endian.f32s(q, solution.data, 5 * n);
    let array = |a: usize| &values[a * n..(a + 1) * n];
    let (rho, mx, my, mz, energy) = (array(0), array(1), array(2), array(3), array(4));

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
    let fields = vec![
        field("density", rho.to_vec()),
        field("pressure", pressure),
        field("velocity_magnitude", velocity),
        field("stagnation_energy", energy.to_vec()),
        field("momentum_magnitude", momentum_magnitude),
    ];
    Ok((fields, conditions, solution))
}

/// The tetrahedra of a grid, and what was done to get them.
struct Split {
    tets: Vec<[u32; 4]>,
    diagonal_parity: usize,
    blanked_hexahedra: usize,
    degenerate_dropped: usize,
    reoriented: usize,
}

/// Splits the grid both conforming ways and keeps the one with the fewest
/// inverted tetrahedra, then the fewest degenerate ones (parity 0 on a
/// tie). A hexahedron with a concave corner can give an inverted corner
/// tetrahedron with one diagonal choice and none with the other (the
/// Combustor has two such cells); since both choices are conforming the
/// better one costs nothing.
///
/// Flat tetrahedra are dropped. A hexahedron collapsed to a prism (grid
/// lines merging at a wall or an axis, duplicated points) splits into some
/// tetrahedra of zero volume: they hold no volume, so the rendering
/// integral does not change without them, while their faces are slivers a
/// ray cannot walk through reliably. Removing whole tetrahedra keeps the
/// boundary closed; it only exposes faces lying on faces of the remaining
/// tetrahedra, which the walk crosses by leaving and re-entering the mesh.
/// Inverted tetrahedra left over (a folded grid) are reoriented here, and
/// validation then rejects the overlap they make.
fn split_grid(dims: [usize; 3], points: &[Vec3], iblank: Option<&[i32]>) -> Split {
    let classify = |tets: &[[u32; 4]]| -> Vec<Shape> {
        tets.par_iter()
            .map(|&tet| {
                let shape = tet_shape(tet.map(|i| points[i as usize]));
                if shape.is_degenerate() {
                    Shape::Flat
                } else if shape.volume6 < 0.0 {
                    Shape::Inverted
                } else {
                    Shape::Positive
                }
            })
            .collect()
    };
    let count = |shapes: &[Shape], s: Shape| shapes.iter().filter(|&&x| x == s).count();
    let candidate = |diagonal_parity: usize| {
        let mut tets = structured_tets(dims, diagonal_parity);
        let blanked_hexahedra = iblank.map_or(0, |iblank| drop_blanked(&mut tets, iblank));
        let shapes = classify(&tets);
        (tets, shapes, diagonal_parity, blanked_hexahedra)
    };
    let score = |c: &(Vec<[u32; 4]>, Vec<Shape>, usize, usize)| {
        (count(&c.1, Shape::Inverted), count(&c.1, Shape::Flat))
    };
    let first = candidate(0);
    // A perfect first split cannot be beaten: skip the second.
    let (tets, shapes, diagonal_parity, blanked_hexahedra) = if score(&first) == (0, 0) {
        first
    } else {
        let second = candidate(1);
        if score(&second) < score(&first) {
            second
        } else {
            first
        }
    };
    let degenerate_dropped = count(&shapes, Shape::Flat);
    let reoriented = count(&shapes, Shape::Inverted);
    let tets = tets
        .into_iter()
        .zip(shapes)
        .filter_map(|(tet, shape)| match shape {
            Shape::Flat => None,
            Shape::Inverted => Some([tet[0], tet[1], tet[3], tet[2]]),
            Shape::Positive => Some(tet),
        })
        .collect();
    Split {
        tets,
        diagonal_parity,
        blanked_hexahedra,
        degenerate_dropped,
        reoriented,
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shape {
    Positive,
    Inverted,
    Flat,
}

/// Removes the 5 tetrahedra of every hexahedron with a blanked corner
/// (IBLANK 0: no valid data there); returns how many hexahedra. The tets of
/// one hexahedron are consecutive.
fn drop_blanked(tets: &mut Vec<[u32; 4]>, iblank: &[i32]) -> usize {
    let before = tets.len();
    let blanked = |hex: &[[u32; 4]]| hex.iter().flatten().any(|&p| iblank[p as usize] == 0);
    let kept: Vec<[u32; 4]> = tets
        .chunks_exact(5)
        .filter(|hex| !blanked(hex))
        .flatten()
        .copied()
        .collect();
    *tets = kept;
    (before - tets.len()) / 5
}
