//! Rendering a mesh split over processes, exactly, by compositing ray
//! fragments (issue 13).
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
//! - `transport` and `in_situ` (feature `mpi`): the exchange over MPI
//!   (rsmpi) and the entry point for a simulation's own communicator.

pub mod composite;
pub mod layout;
pub mod partition;
pub mod summary;

pub use composite::{assemble, blend, bucket_by_owner, composite_owned, Buckets, OwnedPixels};
pub use layout::{LayoutError, TileLayout, DEFAULT_TILE};
pub use partition::{pieces_for_rank, spatial_split, subset};
pub use summary::{MeshSummary, Reduce};
pub use tetray_raycast::Fragment;
