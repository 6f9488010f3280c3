//! Host twin of the pipeline's uniform struct (checked against naga's
//! layout of the WGSL in tests/layout.rs) and the codes shared with it.

use bytemuck::{Pod, Zeroable};
use tetray_gpu::IntegratorData;
use tetray_gpu::layout::{IntegratorParams, ViewParams};

use crate::view::View;

/// WGSL `Params` (shaders/project_common.wgsl): one per frame, the
/// camera and the integrator blocks the ray caster has too.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct Params {
    pub view: ViewParams,
    pub integrator: IntegratorParams,
}

/// Index of the integrated-segment counter (WGSL `STAT_SEGMENTS`).
pub const STAT_SEGMENTS: usize = 0;
/// Counter words (WGSL `STAT_COUNT`).
pub const STAT_COUNT: usize = 2;

impl Params {
    /// The frame's parameters. Segments are never cut at knots inside the
    /// integrator: with adaptive sampling every draw is one knot interval
    /// already, and without it the transfer function is sampled at the
    /// segment ends only, which is what turning it off means.
    pub fn new(view: &View, integrator: &IntegratorData) -> Params {
        Params {
            view: view.params,
            integrator: integrator.params(false),
        }
    }
}

/// The knot scalars as the kernels read them (each interval's start).
pub fn knot_scalars(integrator: &IntegratorData) -> Vec<f32> {
    (0..integrator.knot_count as usize)
        .map(|k| integrator.tables[tetray_gpu::layout::INTERVAL_ENTRIES * (k + 1)][3])
        .collect()
}
