//! Cell projection of tetrahedral meshes (Moreland 2004, chapter 4) on wgpu
//! render pipelines:
//!
//! - balanced projected tetrahedra: per corner the vertex stage finds where
//!   the view ray leaves through the opposite face, the fragment stage takes
//!   the nearest exit and integrates the segment with the ray caster's own
//!   WGSL (shaders/integrate.wgsl) — [`GpuProjector`];
//! - adaptive transfer-function sampling: cells drawn once per knot
//!   interval they span, clipped per fragment — [`draws`];
//! - visibility sorts: centroid depth (parallel radix sort), MPVO and
//!   MPVONC — [`sort`];
//! - the CPU twin of the pipeline, pixel centre by pixel centre — [`twin`].
//!
//! [`Projection::render`] runs a whole frame: sort, draws, render pass,
//! read-back, each timed.

pub mod draws;
mod error;
mod frame;
pub mod layout;
mod render;
mod scene;
pub mod shaders;
pub mod sort;
pub mod twin;
mod view;

pub use draws::{NO_CLIP, TetIntervals};
pub use error::ProjectError;
pub use frame::{
    Plan, ProjectFrame, ProjectOptions, ProjectStats, Projection, plan, samples_adaptively,
};
pub use render::{DrawStats, GpuProjectScene, GpuProjector};
pub use scene::{FACE_VERTS, ProjectScene};
pub use sort::{Order, SortKind, visibility_order};
pub use view::View;
