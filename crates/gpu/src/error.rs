//! Why the GPU ray caster could not run.

use tetray_boundary_bvh::BvhError;
use tetray_core::{CameraError, ImageError};

#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter ({0}); install a Vulkan driver (mesa-vulkan-drivers gives the \
         lavapipe CPU adapter) or render with --renderer cpu"
    )]
    NoAdapter(String),
    #[error("adapter {adapter} refused a device: {message}")]
    Device { adapter: String, message: String },
    #[error(
        "{what} needs {bytes} bytes, more than {chunks} bindings of the adapter's \
         {limit_name} ({limit} bytes) hold"
    )]
    TooLarge {
        what: &'static str,
        bytes: u64,
        limit_name: &'static str,
        limit: u64,
        chunks: u64,
    },
    #[error("the boundary BVH cannot go to the GPU: {0}")]
    Bvh(#[from] BvhError),
    #[error("the Psi table has {0} gamma spacing; the GPU kernel reads the quadratic one")]
    PsiSpacing(&'static str),
    #[error("{0}")]
    Camera(#[from] CameraError),
    #[error("{0}")]
    Image(#[from] ImageError),
    #[error("early termination threshold {0} must be in (0, 1] (1 disables it)")]
    EarlyTermination(f32),
    #[error(
        "image {width}x{height} has too many pixels for one output buffer ({bytes} bytes, limit {limit})"
    )]
    ImageTooLarge {
        width: u32,
        height: u32,
        bytes: u64,
        limit: u64,
    },
    #[error("frame {frame:?} does not match its target's size {target:?}")]
    TargetSize {
        frame: (u32, u32),
        target: (u32, u32),
    },
    #[error("new point fields do not fit the uploaded mesh: {0}")]
    Mismatch(String),
    #[error("reading the frame back from the GPU failed: {0}")]
    Readback(String),
    #[error("the GPU reported an error: {0}")]
    Driver(String),
    /// The device stopped working (driver reset, GPU removed, device
    /// destroyed); a new context is needed.
    #[error(
        "the GPU device ({adapter}) was lost ({why}); start again, or render with \
         --renderer cpu"
    )]
    DeviceLost { adapter: String, why: String },
}
