//! Tetrahedral meshes for volume rendering: points, tetrahedra, point scalar
//! fields; the cell model every reader produces ([`cells`]: VTK cell types,
//! f64 points, point and cell arrays, pieces) and its splitting into
//! tetrahedra; the face-neighbour graph and boundary faces; validation.
//! The file readers and writers are in `tetray-io`; nothing here reads a
//! file.
//!
//! Conventions shared by every crate of the workspace:
//! - every tetrahedron is stored positively oriented:
//!   `(p1 - p0) . ((p2 - p0) x (p3 - p0)) > 0` (fixed on load);
//! - local face `f` of a tetrahedron is the face opposite its vertex `f`, with
//!   the vertex order [`FACE_VERTICES`]`[f]`, counter-clockwise seen from
//!   outside (its normal by the right-hand rule points out of the tetrahedron).
//!
//! Entry points: [`cells::assemble_with`] (a reader's cells to
//! tetrahedra), [`finish`] (a reader's output, [`MeshRead`]), [`prepare`]
//! (a mesh built in memory). [`finish`] and [`prepare`] leave out
//! the cells that cannot be walked (tangled, overlapping, flat; reported),
//! orient the tetrahedra, [`validate`] the mesh (a broken file is an
//! error, never rendered wrong; non-conforming faces are warnings: rays
//! cross them through the boundary) and build its [`Topology`]. File
//! readers store the points relative to an origin near the mesh
//! ([`centring_origin`], [`LoadReport::origin`]).

mod conform;
mod error;
mod exclude;
mod geometry;
mod info;
mod loaded;
mod scale;
mod seams;
mod search;
mod topology;
mod validate;

pub mod cells;
pub mod structured;
pub mod synthetic;

pub use error::MeshError;
pub use exclude::{ExcludedCells, KnownTopology};
pub use geometry::{
    DEGENERATE_HEIGHT_ULPS, TetShape, bounds_f64, centring_origin, tet_shape, tet_volume6,
};
pub use info::{FieldRange, MeshSummary};
pub use loaded::{ElementBlock, LoadReport, LoadedMesh, MeshRead, finish, finish_reusing, prepare};
pub use scale::{
    default_field, default_field_of, mean_chord, mean_tet_chord, paraview_unit_distance,
    tet_chord_sum, value_range,
};
pub use search::{first_index, first_position};
pub use topology::{MAX_TETS, boundary_faces_of};
pub use validate::{ValidationReport, check_input, validate, validate_with_topology};

use glam::Vec3;

/// Local vertex indices of face `f` (opposite vertex `f`), ordered so the
/// right-hand normal points outwards for a positively oriented tetrahedron.
pub const FACE_VERTICES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// Marks a face with no neighbouring tetrahedron (a boundary face).
pub const NO_NEIGHBOR: u32 = u32::MAX;

/// A scalar value per mesh point.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalarField {
    pub name: String,
    pub values: Vec<f32>,
}

/// An unstructured tetrahedral mesh with point scalars.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TetMesh {
    pub points: Vec<Vec3>,
    /// Four point indices per tetrahedron, positively oriented.
    pub tets: Vec<[u32; 4]>,
    pub fields: Vec<ScalarField>,
}

/// A face of the mesh with a tetrahedron on one side only.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BoundaryFace {
    /// The tetrahedron this face belongs to.
    pub tet: u32,
    /// Its local face index in that tetrahedron (0..4).
    pub local_face: u8,
    /// Point indices, counter-clockwise seen from outside the mesh.
    pub vertices: [u32; 3],
}

/// Face adjacency of a [`TetMesh`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Topology {
    /// `neighbors[t][f]`: the tetrahedron across local face `f` of `t`, or
    /// [`NO_NEIGHBOR`].
    pub neighbors: Vec<[u32; 4]>,
    /// Every boundary face, outward oriented, listed by tetrahedron, then
    /// local face ([`Topology::boundary_face_index`] finds one).
    pub boundary_faces: Vec<BoundaryFace>,
}
