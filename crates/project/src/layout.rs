//! Host twin of the pipeline's uniform struct (checked against naga's
//! layout of the WGSL in tests/layout.rs) and the codes shared with it.

use bytemuck::{Pod, Zeroable};
use tetray_gpu::IntegratorData;

use crate::view::View;

/// WGSL `Params` (shaders/project_common.wgsl): one per frame.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct Params {
    pub position: [f32; 3],
    pub orthographic: u32,
    pub right: [f32; 3],
    pub pixel: f32,
    pub up: [f32; 3],
    pub half_width: f32,
    pub direction: [f32; 3],
    pub half_height: f32,
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

/// Index of the integrated-segment counter (WGSL `STAT_SEGMENTS`).
pub const STAT_SEGMENTS: usize = 0;
/// Counter words (WGSL `STAT_COUNT`).
pub const STAT_COUNT: usize = 2;

impl Params {
    /// The frame's parameters. Segments are never cut at knots inside the
    /// integrator (`split = 0`): with adaptive sampling every draw is one
    /// knot interval already, and without it the transfer function is
    /// sampled at the segment ends only, which is what turning it off means.
    pub fn new(view: &View, integrator: &IntegratorData) -> Params {
        let preint = integrator.preint;
        Params {
            position: view.position.to_array(),
            orthographic: u32::from(view.orthographic),
            right: view.right.to_array(),
            pixel: view.pixel,
            up: view.up.to_array(),
            half_width: view.half_width(),
            direction: view.direction.to_array(),
            half_height: view.half_height(),
            method: integrator.method,
            grey: u32::from(integrator.grey),
            split: 0,
            knot_count: integrator.knot_count,
            psi_size: integrator.psi_size,
            inv_unit_distance: integrator.inv_unit_distance,
            riemann_step: integrator.riemann_step,
            preint_size: preint.map_or(0, |p| p.size),
            preint_offset: preint.map_or(0, |p| p.offset),
            preint_lo: preint.map_or(0.0, |p| p.lo),
            preint_scale: preint.map_or(0.0, |p| p.scale),
            preint_length: preint.map_or(1.0, |p| p.length),
        }
    }

    /// The ray caster's parameters with this frame's integrator members, so
    /// the CPU twin can call tetray_gpu's twin of integrate.wgsl.
    pub fn integrator_twin(&self) -> tetray_gpu::layout::Params {
        tetray_gpu::layout::Params {
            method: self.method,
            grey: self.grey,
            split: self.split,
            knot_count: self.knot_count,
            psi_size: self.psi_size,
            inv_unit_distance: self.inv_unit_distance,
            riemann_step: self.riemann_step,
            preint_size: self.preint_size,
            preint_offset: self.preint_offset,
            preint_lo: self.preint_lo,
            preint_scale: self.preint_scale,
            preint_length: self.preint_length,
            ..tetray_gpu::layout::Params::zeroed()
        }
    }
}

/// The knot scalars as the kernels read them (each interval's start).
pub fn knot_scalars(integrator: &IntegratorData) -> Vec<f32> {
    (0..integrator.knot_count as usize)
        .map(|k| integrator.tables[tetray_gpu::layout::INTERVAL_ENTRIES * (k + 1)][3])
        .collect()
}
