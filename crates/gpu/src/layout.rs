//! Host twins of the kernel's uniform structs (checked against naga's
//! layout of the WGSL in tests/layout.rs) and the codes shared with it (the
//! methods' codes are `tetray_core::Method::gpu_code`).

use bytemuck::{Pod, Zeroable};
use tetray_core::PixelRays;

/// WGSL `ViewParams` (shaders/params.wgsl): the camera of a frame, as the
/// ray caster and the cell projection read it.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct ViewParams {
    pub position: [f32; 3],
    pub orthographic: u32,
    pub right: [f32; 3],
    pub pixel: f32,
    pub up: [f32; 3],
    pub half_width: f32,
    pub direction: [f32; 3],
    pub half_height: f32,
}

impl ViewParams {
    /// The camera of `rays` as the kernels take it.
    pub fn new(rays: &PixelRays) -> ViewParams {
        let basis = rays.basis();
        let (half_width, half_height) = rays.half_size();
        ViewParams {
            position: rays.position().to_array(),
            orthographic: u32::from(rays.is_orthographic()),
            right: basis.right.to_array(),
            pixel: rays.pixel_size(),
            up: basis.up.to_array(),
            half_width,
            direction: basis.direction.to_array(),
            half_height,
        }
    }
}

/// WGSL `IntegratorParams` (shaders/params.wgsl): what integrate.wgsl
/// reads of the integrator, in both pipelines.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct IntegratorParams {
    /// [`tetray_core::Method::gpu_code`].
    pub method: u32,
    pub grey: u32,
    pub split: u32,
    pub knot_count: u32,
    pub psi_size: u32,
    pub inv_unit_distance: f32,
    pub riemann_step: f32,
    pub preint_size: u32,
    pub preint_offset: u32,
    pub preint_lo: f32,
    pub preint_scale: f32,
    pub preint_length: f32,
}

/// WGSL `Params` (shaders/common.wgsl): one per frame of the ray caster.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct Params {
    pub view: ViewParams,
    pub bounds_min: [f32; 3],
    pub eye_inside: u32,
    pub bounds_max: [f32; 3],
    pub scene_abs_max: f32,
    pub width: u32,
    pub height: u32,
    pub max_steps: u32,
    pub stop_below_sum: f32,
    pub integrator: IntegratorParams,
    pub tet_chunk: u32,
    pub point_chunk: u32,
    pub prim_offset: u32,
    pub face_offset: u32,
    /// Offset (in entries of the BVH array) of the left-out cells: their
    /// bounds (two entries), then one entry of point indices per
    /// tetrahedron.
    pub overlap_offset: u32,
    pub overlap_count: u32,
    pub _pad: [u32; 2],
}

/// What the frame parameters need to know of a mesh and its buffers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneLayout {
    pub bounds: (glam::Vec3, glam::Vec3),
    pub scene_abs_max: f32,
    pub tet_count: usize,
    pub tet_chunk: u32,
    pub point_chunk: u32,
    pub prim_offset: u32,
    pub face_offset: u32,
    pub overlap_offset: u32,
    pub overlap_count: u32,
}

/// WGSL `Tile`: the pixels of one dispatch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
#[repr(C)]
pub struct Tile {
    pub x0: u32,
    pub y0: u32,
    pub width: u32,
    pub height: u32,
}

/// Indices into the kernel's counter array (WGSL `STAT_*`).
pub const STAT_RAYS_HIT: usize = 0;
pub const STAT_SEGMENTS_LO: usize = 1;
pub const STAT_SEGMENTS_HI: usize = 2;
pub const STAT_STEPS_LO: usize = 3;
pub const STAT_STEPS_HI: usize = 4;
pub const STAT_ENTRIES: usize = 5;
pub const STAT_BOUND_HITS: usize = 6;
pub const STAT_WALK_FAILURES: usize = 7;
pub const STAT_OVERLAP_SEGMENTS: usize = 8;
pub const STAT_OVERLAP_OVERFLOWS: usize = 9;
pub const STAT_COUNT: usize = 10;

/// `vec4<f32>` entries per transfer-function interval in the tables buffer.
pub const INTERVAL_ENTRIES: usize = 4;
/// `vec4<f32>` entries per (front, back) pair of the pre-integration table.
pub const PREINT_ENTRIES: usize = 2;
