//! Rendering a mesh split over processes, exactly, by compositing ray
//! fragments.
//!
//! Each process (rank) holds a part of the mesh. It casts every pixel's
//! ray through its part and keeps one fragment per interval the ray
//! spends inside it ([`tetray_raycast::render_fragments`]). Intervals of
//! different parts never overlap in depth and front-to-back compositing is
//! associative, so the fragments of all ranks, sorted by depth per pixel
//! and blended, give the whole mesh's image with no redistribution of
//! cells.
//!
//! - [`layout`]: which rank owns which pixels (interleaved tiles);
//! - [`composite`]: bucketing fragments per owner, the per-pixel depth
//!   sort, the blend, assembling the image (plain Rust, tested without
//!   MPI);
//! - [`summary`]: what ranks must agree on (bounds, ranges, cell counts);
//! - [`partition`]: which pieces or cells a rank renders;
//! - [`report`]: per-rank costs of a frame;
//! - with the feature `mpi`: `transport` (the exchange, gather and
//!   reductions over rsmpi), `frame` (agreeing and rendering one frame),
//!   `part` (a rank's part of a file made ready through the engine, as a
//!   single process would make the whole) and `in_situ` (a simulation's
//!   arrays on its own communicator).

pub mod composite;
pub mod layout;
pub mod partition;
pub mod report;
pub mod summary;

#[cfg(feature = "mpi")]
pub mod frame;
#[cfg(feature = "mpi")]
pub mod in_situ;
#[cfg(feature = "mpi")]
pub mod part;
#[cfg(feature = "mpi")]
pub mod transport;

pub use composite::{Buckets, OwnedPixels, assemble, blend, bucket_by_owner, composite_owned};
pub use layout::{DEFAULT_TILE, LayoutError, OwnedSlots, TileLayout};
pub use partition::{pieces_for_rank, spatial_split, subset};
pub use report::{FrameReport, Row};
pub use summary::{MeshSummary, Reduce};
pub use tetray_raycast::Fragment;

#[cfg(feature = "mpi")]
pub use frame::{Agreed, DistributedFrame, agree, render_distributed, render_setup};
#[cfg(feature = "mpi")]
pub use in_situ::{InSituView, RankMesh, render_in_situ, render_in_situ_cells};
#[cfg(feature = "mpi")]
pub use mpi;
#[cfg(feature = "mpi")]
pub use part::{Part, prepare_part};

/// Why a distributed frame could not be made.
#[derive(Debug, thiserror::Error)]
pub enum DistributedError {
    #[error(transparent)]
    Layout(#[from] LayoutError),
    #[error(transparent)]
    Render(#[from] tetray_raycast::RenderError),
    #[error(transparent)]
    Image(#[from] tetray_core::ImageError),
    #[error(transparent)]
    Scene(#[from] tetray_scene::SceneError),
    #[error(transparent)]
    Camera(#[from] tetray_core::CameraError),
    #[error(transparent)]
    Mesh(#[from] tetray_mesh::MeshError),
    #[error(transparent)]
    Cells(#[from] tetray_mesh::cells::CellError),
    #[error(transparent)]
    Integrator(#[from] tetray_integrate::IntegrateError),
    #[error(transparent)]
    Engine(#[from] tetray_engine::EngineError),
    #[error(transparent)]
    Io(#[from] tetray_io::IoError),
    #[error("{0} values are too many for one MPI message (counts are 32-bit)")]
    TooLarge(usize),
    #[error("no rank has any point: nothing to render")]
    NoMesh,
    #[error("{scalars} scalars for {points} points: one scalar per point")]
    ScalarCount { scalars: usize, points: usize },
    #[error("the field {name:?} is not on every rank (fields every rank has: {available})")]
    UnknownField { name: String, available: String },
}
