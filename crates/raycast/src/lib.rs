//! The CPU reference ray caster that walks a tetrahedral mesh cell to cell
//! (its [`tetray_scene::Scene`]: topology, boundary BVH, walk records).
//!
//! - [`render_cpu`]: one ray per pixel; each enters the mesh through the
//!   boundary face the BVH finds, walks tet to tet through exit faces chosen
//!   by the shared watertight predicate, and composites the integrated
//!   segments front to back;
//! - [`render_fragments`]: the same rays, the light of each interval inside
//!   the mesh kept apart as a [`Fragment`] (for compositing across pieces).

mod cpu;
mod entries;
mod exits;
mod face;
mod fragment;
mod holes;
mod segment;
mod walk;

pub use cpu::{
    RayTrace, RenderError, RenderOptions, RenderOutput, RenderStats, render_cpu,
    render_cpu_watched, render_cpu_with_progress, render_scalar, render_scalar_watched,
    render_scalar_with_progress, trace_pixel, wide_cpu,
};
pub use face::LEFT_OUT_SLOT;
pub use fragment::{Fragment, FragmentOutput, render_fragments, render_scalar_fragments};
pub use segment::SegmentIntegrator;
