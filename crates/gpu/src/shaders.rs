//! The WGSL sources, embedded, and how they are put together. WGSL has no
//! includes: a module is its pieces in dependency order, after the method
//! codes generated from [`tetray_core::Method::gpu_code`] and the parameter
//! blocks both pipelines share. Tests validate every module with naga.

/// The parameter blocks shared by the ray caster and the projection.
pub const PARAMS: &str = include_str!("../../../shaders/params.wgsl");
/// Declarations: parameters, bindings, buffer accessors.
pub const COMMON: &str = include_str!("../../../shaders/common.wgsl");
/// Ray frame and the exact watertight edge predicate.
pub const PREDICATE: &str = include_str!("../../../shaders/predicate.wgsl");
/// Boundary BVH traversal: where a ray enters the mesh.
pub const BVH: &str = include_str!("../../../shaders/bvh.wgsl");
/// Transfer-function sampling and every integration method.
pub const INTEGRATE: &str = include_str!("../../../shaders/integrate.wgsl");
/// The cells left out of the walk, composited in the gaps they leave.
pub const OVERLAPS: &str = include_str!("../../../shaders/overlaps.wgsl");
/// The same functions for a scene with no cells left out: no overlap lists.
pub const NO_OVERLAPS: &str = include_str!("../../../shaders/no_overlaps.wgsl");
/// The per-pixel kernel: entry, walk, compositing, counters.
pub const RAYCAST: &str = include_str!("../../../shaders/raycast.wgsl");

/// A module of `pieces` (in order) behind the method codes and
/// [`PARAMS`].
pub fn module(pieces: &[&str]) -> String {
    let mut source = tetray_core::method::wgsl_constants();
    for piece in [PARAMS].iter().chain(pieces) {
        source.push('\n');
        source.push_str(piece);
    }
    source
}

/// The ray-casting module: every piece, in order.
pub fn raycast_source() -> String {
    module(&[COMMON, PREDICATE, BVH, INTEGRATE, OVERLAPS, RAYCAST])
}

/// The ray-casting module for scenes with no cells left out of the walk
/// ([`NO_OVERLAPS`] in place of [`OVERLAPS`]): the same images, without
/// the per-invocation overlap lists (measured on lavapipe: the Blunt Fin's
/// frame 7-17% slower with them).
pub fn raycast_source_without_overlaps() -> String {
    module(&[COMMON, PREDICATE, BVH, INTEGRATE, NO_OVERLAPS, RAYCAST])
}
