//! A tetrahedral mesh made ready to be walked by a ray, shared by every
//! renderer that walks or projects tetrahedra (the CPU ray caster, the GPU
//! kernel's uploads, the cell projection):
//!
//! - [`Scene`]: the mesh, its topology and boundary BVH, the active field,
//!   and per tetrahedron the 32-byte record a walk reads per step;
//! - [`order`]: the Morton renumbering that keeps neighbouring cells
//!   together in memory;
//! - [`overlaps`]: the cells left out of the walk, composited in the
//!   holes they leave.

pub mod order;
pub mod overlaps;
mod records;
mod scene;

pub use order::Reorder;
pub use overlaps::{
    MAX_OVERLAP_CROSSINGS, OverlapCrossing, Overlaps, collect_crossings, line_meets_box,
    window_segments,
};
pub use records::{FINAL_EXIT, WalkTet, vertex_rank};
pub use scene::{CellOrder, Scene, SceneError};
