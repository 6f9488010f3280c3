//! Why the cell projection could not run.

use tetray_core::{CameraError, ImageError};
use tetray_gpu::GpuError;

#[derive(Debug, thiserror::Error)]
pub enum ProjectError {
    #[error("the mesh has no tetrahedra to project")]
    Empty,
    #[error(
        "the transfer function attenuates colours differently; the projection blends one \
         transmittance per pixel (every ParaView transfer function is grey)"
    )]
    ColouredAttenuation,
    #[error("the {0} integrator (f64 quadrature) has no GPU kernel; use --renderer cpu")]
    NoKernel(String),
    #[error(
        "{what} needs {bytes} bytes, more than the adapter's \
         max_storage_buffer_binding_size ({limit} bytes)"
    )]
    TooLarge {
        what: &'static str,
        bytes: u64,
        limit: u64,
    },
    #[error("image {width}x{height} exceeds the adapter's {limit} pixel texture side")]
    ImageTooLarge { width: u32, height: u32, limit: u32 },
    #[error("{0}")]
    Camera(#[from] CameraError),
    #[error("{0}")]
    Image(#[from] ImageError),
    #[error("{0}")]
    Gpu(#[from] GpuError),
    #[error("the GPU reported an error: {0}")]
    Driver(String),
}
