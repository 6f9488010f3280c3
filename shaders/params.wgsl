// The parameter blocks shared by the ray-casting kernel and the cell
// projection (host: tetray_gpu::layout::{ViewParams, IntegratorParams},
// checked against naga's layout of these structs). Every module that
// integrates starts with the method codes (generated from
// tetray_core::Method), then this file.

// The camera of a frame: perspective rays start at `position` and run
// along `direction + offset`, orthographic rays start at
// `position + offset` and run along `direction`; offset = right * x + up * y,
// with x = (px + 0.5 - half_width) pixel, y = (half_height - py - 0.5) pixel.
struct ViewParams {
    position: vec3<f32>,
    orthographic: u32,
    right: vec3<f32>,
    pixel: f32,
    up: vec3<f32>,
    half_width: f32,
    direction: vec3<f32>,
    half_height: f32,
}

// What integrate.wgsl reads of the integrator (the tables are bindings).
struct IntegratorParams {
    // A METHOD_* code.
    method: u32,
    // 1: every knot's attenuation and opacity is the same in all channels.
    grey: u32,
    // 1: segments are cut at the transfer function's knots.
    split: u32,
    knot_count: u32,
    psi_size: u32,
    inv_unit_distance: f32,
    riemann_step: f32,
    preint_size: u32,
    preint_offset: u32,
    preint_lo: f32,
    preint_scale: f32,
    preint_length: f32,
}
