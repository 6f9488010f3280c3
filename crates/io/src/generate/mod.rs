//! Large test meshes for scaling measurements, at a requested tetrahedron
//! count:
//! - [`Refinement`], [`RefinementPlan`]: a PLOT3D grid with every hexahedron cut into `ri x rj x rk`
//!   (8 per level of doubling), coordinates and solution interpolated
//!   trilinearly, written as PLOT3D files the reader splits as usual;
//! - [`solid`]: a procedural nonconvex solid (a thick torus shell) with
//!   analytic point scalars, written as `.vtu`, or as a partitioned
//!   `.pvtu` of piece files ([`pieces`]).
//!
//! Both stream their output: a refinement is computed point by point as it
//! is written, the solid's tetrahedra chunk by chunk.

mod folded;
pub mod pieces;
mod plan;
mod refine;
pub mod solid;

pub use plan::{RefinementPlan, near_uniform_factors};
pub use refine::{Refinement, refine};

use crate::IoError;

/// The most tetrahedra a generated mesh may have: what the loader can
/// index (`4 * tet + face` in 32 bits).
pub const MAX_TETS: usize = tetray_mesh::MAX_TETS;

/// Why a mesh could not be generated.
#[derive(Debug, thiserror::Error)]
pub enum GenerateError {
    /// Reading the source grid or writing an output file failed.
    #[error(transparent)]
    Read(#[from] IoError),

    /// A requested size outside what can be generated.
    #[error("{requested} tetrahedra requested: {reason}")]
    TetCount { requested: usize, reason: String },

    /// A refinement factor of 0.
    #[error("refinement factors {factors:?}: each must be at least 1")]
    ZeroFactor { factors: [usize; 3] },

    /// A refinement that makes more points, or a larger mesh, than can be
    /// stored or loaded.
    #[error("refining the {dims:?} grid by {factors:?} gives {what}; at most {max} are supported")]
    TooLarge {
        dims: [usize; 3],
        factors: [usize; 3],
        what: String,
        max: usize,
    },

    /// Every refinement tried for a requested count would be rejected by
    /// validation (see [`RefinementPlan::defect`]).
    #[error(
        "no refinement of the {dims:?} grid with at least {requested} tetrahedra splits into \
         a valid mesh; tried {tried}"
    )]
    NoCleanRefinement {
        dims: [usize; 3],
        requested: usize,
        tried: String,
    },

    /// A torus shell whose cell counts cannot make a valid mesh.
    #[error("torus shell with {cells:?} cells: {reason}")]
    BadShell { cells: [usize; 3], reason: String },

    /// Writing a file failed.
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
}
