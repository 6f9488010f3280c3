//! A BVH (obvhs) over the boundary faces of a tetrahedral mesh, answering
//! "which boundary face does this ray enter the mesh through first, after t".
//!
//! Every query decides crossings with the shared `watertight` predicate, so
//! the BVH, the brute-force scan and the GPU layout's CPU twin agree bit for
//! bit, and agree with the ray caster about which faces a ray crosses.
//!
//! - [`BoundaryBvh::build`] builds over `Topology::boundary_faces` with one of
//!   the obvhs presets ([`BuildPreset`]);
//! - [`BoundaryBvh::first_entry`] / [`brute_force_first_entry`]: the nearest
//!   face the ray enters through in `[t_min, t_max]` (the first through the
//!   tree collapsed to four children per node);
//! - [`BoundaryBvh::flatten`]: a `#[repr(C)]` node array for the GPU kernel,
//!   with [`FlatBvh::first_entry`] as its CPU twin.

mod brute;
mod build;
mod bvh4;
mod flat;
mod hull;
mod preset;
mod slab;
mod traverse;

pub use brute::brute_force_first_entry;
pub use build::{BoundaryBvh, BvhStats};
pub use flat::{FLAT_STACK_SIZE, FlatBvh, FlatNode, FlatPrim};
pub use preset::BuildPreset;

/// The boundary face a ray enters the mesh through.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntryHit {
    /// Index into `Topology::boundary_faces`.
    pub face: u32,
    /// Distance along the ray (its unit direction) to the crossing.
    pub t: f32,
}

impl EntryHit {
    /// Whether this hit comes before `other` in every query's order:
    /// nearer, or as near with a lower face index.
    #[inline(always)]
    pub fn precedes(self, other: EntryHit) -> bool {
        self.t < other.t || (self.t == other.t && self.face < other.face)
    }
}

/// Why a BVH could not be built or flattened.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BvhError {
    #[error("the mesh has no boundary faces to build a BVH over")]
    NoBoundaryFaces,
    #[error("boundary face {face} refers to point {point}, but the mesh has {points} points")]
    PointOutOfRange {
        face: u32,
        point: u32,
        points: usize,
    },
    #[error("point {point} (on boundary face {face}) has a non-finite coordinate {coords:?}")]
    NonFinitePoint {
        face: u32,
        point: u32,
        coords: [f32; 3],
    },
    #[error("{faces} boundary faces exceed the u32 index range of the BVH")]
    TooManyFaces { faces: usize },
    #[error(
        "BVH depth {depth} exceeds the GPU traversal stack of {limit} entries; \
         use the CPU traversal or a different build preset"
    )]
    TooDeepForGpu { depth: u32, limit: u32 },
    #[error("a BVH leaf holds {prims} faces, more than the wide tree's 65535")]
    LeafTooLarge { prims: u32 },
    #[error("unknown BVH build preset {0:?} (expected one of: {names})", names = BuildPreset::names())]
    UnknownPreset(String),
}

/// Relative slack of a re-entry query: a ray that leaves the mesh at
/// distance `t` asks for entries from `t - REENTRY_REL * (S + |origin|)`
/// on (`S`: the largest boundary coordinate magnitude). The exit distance
/// (from the walk's weights) and the entry distance of a coincident face
/// (from the face's own weights) are rounded differently; without the
/// slack a seam crossed at a rounding-unlucky distance would be missed. No
/// other face can enter that close before an exit in a mesh whose parts
/// do not overlap, and the walk never integrates backwards.
pub const REENTRY_REL: f32 = 1.0 / 1_048_576.0;

/// The distance a re-entry query starts from after leaving at `t_exit`.
#[inline]
pub fn reentry_start(
    ray: &tetray_core::watertight::RayFrame,
    t_exit: f32,
    scene_abs_max: f32,
) -> f32 {
    t_exit - REENTRY_REL * (scene_abs_max + ray.origin.abs().max_element())
}

/// A ray with a non-finite origin or direction, or a NaN range, crosses
/// nothing by contract (its distances would be meaningless).
#[inline(always)]
pub(crate) fn query_is_valid(
    ray: &tetray_core::watertight::RayFrame,
    t_min: f32,
    t_max: f32,
) -> bool {
    ray.origin.is_finite() && ray.dir.is_finite() && !t_min.is_nan() && !t_max.is_nan()
}

/// Whether `(t, face)` beats the best hit so far: nearer, or as near with a
/// lower face index, so every traversal order returns the same hit.
#[inline(always)]
pub(crate) fn is_better(t: f32, face: u32, best: Option<EntryHit>) -> bool {
    best.is_none_or(|b| EntryHit { face, t }.precedes(b))
}
