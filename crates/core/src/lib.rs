//! The vocabulary every tetray renderer shares, below all of them: no
//! renderer, no mesh, no GPU.
//!
//! - [`camera`]: VTK-style cameras and the rays of their pixels;
//! - [`watertight`]: a ray's frame and the exact edge predicate that decides
//!   which triangle it crosses (shared by the boundary BVH, the CPU walk and
//!   the GPU kernel's twin);
//! - [`image`]: premultiplied float RGBA images, EXR / PNG / NumPy output;
//! - [`counters`]: what a walk counts, one struct for every renderer;
//! - [`method`]: the ray-integration methods and which renderers run them;
//! - [`defaults`]: the defaults every front end shares.

pub mod camera;
pub mod counters;
pub mod defaults;
pub mod image;
pub mod method;
pub mod movie;
pub mod watertight;

pub use camera::{Camera, CameraError, PixelRays, ViewBasis, relative_to_origin};
pub use counters::WalkCounters;
pub use image::{Image, ImageError, composite_over};
pub use method::{Method, Model, UnknownMethod};
pub use movie::{Movie, MovieError};
