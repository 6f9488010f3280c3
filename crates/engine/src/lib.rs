//! The one door into the renderers: every front end (the CLI, the Python
//! package, the viewer, the distributed and in-situ renderers) makes its
//! frames here, from plain options, so the same options give the same image
//! everywhere.
//!
//! [`Source`] (a file, the embedded Blunt Fin, arrays in memory, a mesh
//! already made) -> [`prepare`] -> [`Setup`] (the [`Volume`]: tetrahedra,
//! a regular grid or both; the camera, the transfer function and the
//! integrator, with the defaults of the whole volume's [`Extent`]) ->
//! [`Engine`] (CPU or GPU ray caster, cell projection, shear-warp) ->
//! [`Frame`]; [`TimeSteps`] moves a setup through a file's time steps,
//! keeping what the steps share; [`measure`] times frames; [`segment`] integrates one ray
//! segment by any method.
//!
//! Nothing here parses command lines or prints: progress and warnings go
//! to the caller's [`Log`], and errors name what the user gave (a field, a
//! file, a renderer), not a flag.

mod camera;
mod error;
mod fields;
mod frame;
mod grid;
mod measure;
mod options;
mod prepare;
mod renderer;
mod segment;
mod setup;
mod source;
mod steps;
pub mod tf;

pub use camera::{build_camera, warn_if_inside};
pub use error::{EngineError, error_chain};
pub use fields::SOLID;
pub use frame::{Frame, FrameStats};
pub use measure::{Measured, Timing, measure, median};
pub use options::{
    CameraOptions, FrameOptions, IntegratorChoice, Log, RendererChoice, Representation, TfSource,
    WalkOptions, bvh_preset_for,
};
pub use prepare::{EMBEDDED_VIEW, prepare};
pub use renderer::{Engine, GpuEngine, ProjectEngine};
pub use segment::{SegmentOptions, segment};
pub use setup::{Extent, Setup, Volume, prepare_mesh, prepare_part};
pub use source::{EMBEDDED_NAME, MeshInput, Source, load, plural};
pub use steps::{StepCost, TimeSteps};
pub use tetray_core::defaults::DEFAULT_VIEW;
