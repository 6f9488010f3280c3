//! From plain options to a rendered frame, shared by the `tetray` CLI and
//! the Python bindings so both make the same image of the same input:
//!
//! - [`mesh`]: which mesh ([`MeshOptions`]: a file or the embedded Blunt
//!   Fin) and loading it, or a raw grid built in memory through the same
//!   assembly as a `.vtu` ([`load_grid`]);
//! - [`setup`]: the field pick, scene, camera fit, transfer function
//!   defaults (the constant-field "solid" case included), unit distance and
//!   integrator ([`prepare`] -> [`Setup`]);
//! - [`engine`]: the renderer choice (cpu, gpu, project, shear-warp, auto)
//!   and one frame with its statistics;
//! - [`shear_warp`]: a uniform grid read as itself for shear-warp.
//!
//! Nothing here parses command lines or prints: progress and warnings go
//! to the caller's [`Log`].

mod error;
mod options;

pub mod engine;
pub mod mesh;
pub mod setup;
pub mod shear_warp;

pub use engine::{Engine, Frame, FrameStats, GpuEngine, ProjectEngine};
pub use error::FrameError;
pub use mesh::{load_grid, load_mesh, plural, MeshInput, MeshOptions, EMBEDDED_NAME};
pub use options::{
    bvh_preset_for, CameraOptions, IntegratorChoice, Log, RendererChoice, TfSource, WalkOptions,
    DEFAULT_VIEW,
};
pub use setup::{build_camera, prepare, FrameOptions, Setup, SOLID};
