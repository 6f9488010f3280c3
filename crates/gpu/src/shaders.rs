//! The WGSL sources, embedded. WGSL has no includes: the kernel is the
//! concatenation of its pieces, in dependency order.

/// Declarations: parameters, bindings, buffer accessors.
pub const COMMON: &str = include_str!("../../../shaders/common.wgsl");
/// Ray frame and the exact watertight edge predicate.
pub const PREDICATE: &str = include_str!("../../../shaders/predicate.wgsl");
/// Boundary BVH traversal: where a ray enters the mesh.
pub const BVH: &str = include_str!("../../../shaders/bvh.wgsl");
/// Transfer-function sampling and every integration method.
pub const INTEGRATE: &str = include_str!("../../../shaders/integrate.wgsl");
/// The per-pixel kernel: entry, walk, compositing, counters.
pub const RAYCAST: &str = include_str!("../../../shaders/raycast.wgsl");

/// The ray-casting module: every piece, in order.
pub fn raycast_source() -> String {
    [COMMON, PREDICATE, BVH, INTEGRATE, RAYCAST].join("\n")
}
