//! The wgpu compute ray caster: one invocation per pixel enters the mesh
//! through the boundary BVH, walks tetrahedron to tetrahedron with an exact
//! watertight exit rule, integrates every segment (partial pre-integration
//! with the Psi table by default) and re-enters after leaving the mesh.
//!
//! - [`GpuContext`]: adapter and device (wgpu's environment variables pick
//!   the adapter);
//! - [`GpuScene`], [`GpuIntegrator`]: a mesh and a transfer function with
//!   its method, uploaded;
//! - [`GpuRaycaster::render`]: a frame, read back, with counters and the
//!   GPU time from timestamp queries;
//! - [`GpuRaycaster::encode_rows`] into a [`GpuTarget`]: a frame rendered
//!   a few rows per submission and kept on the GPU (the viewer), on a
//!   device shared with a GUI ([`GpuContext::from_device`]).
//!
//! The kernel is WGSL in `shaders/` (see [`shaders`]).

mod context;
mod error;
pub mod layout;
pub mod readback;
mod render;
pub mod shaders;
mod shared;
mod target;
pub mod twin;
mod upload;

pub use context::{GpuContext, device_select_would_be_noisy, texture_2d};
pub use error::GpuError;
pub use layout::SceneLayout;
pub use render::{
    FrameJob, GpuFrame, GpuRaycaster, GpuRenderOptions, GpuStats, TILE, default_max_steps,
    frame_params, walk_counters,
};
pub use target::GpuTarget;
pub use upload::{
    GpuIntegrator, GpuScene, IntegratorData, PreintParams, SceneData, TET_WORDS, psi_texture,
};
