//! A frame that outlives one submission: the image and counter buffers the
//! kernel writes, kept on the GPU so that a frame can be rendered a few rows
//! per submission and shown (or compared) without reading it back.

use tetray_core::CameraError;

use crate::layout::STAT_COUNT;
use crate::readback::readback_buffer;
use crate::{GpuContext, GpuError};

/// The kernel's output for one `width x height` frame: premultiplied RGBA
/// (`vec4<f32>` per pixel, row 0 at the top) and the counters.
pub struct GpuTarget {
    width: u32,
    height: u32,
    image: wgpu::Buffer,
    stats: wgpu::Buffer,
}

impl GpuTarget {
    /// Zeroed buffers for a frame (wgpu zero-initialises new buffers).
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Result<GpuTarget, GpuError> {
        if width == 0 || height == 0 {
            return Err(CameraError::BadImageSize { width, height }.into());
        }
        let image_bytes = u64::from(width) * u64::from(height) * 16;
        let limit = ctx
            .limits
            .max_storage_buffer_binding_size
            .min(ctx.limits.max_buffer_size);
        if image_bytes > limit {
            return Err(GpuError::ImageTooLarge {
                width,
                height,
                bytes: image_bytes,
                limit,
            });
        }
        let usage = wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST;
        let image = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("image"),
            size: image_bytes,
            usage,
            mapped_at_creation: false,
        });
        let stats = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stats"),
            size: (STAT_COUNT * 4) as u64,
            usage,
            mapped_at_creation: false,
        });
        Ok(GpuTarget {
            width,
            height,
            image,
            stats,
        })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The image buffer: `width * height` premultiplied `vec4<f32>`.
    pub fn image(&self) -> &wgpu::Buffer {
        &self.image
    }

    pub fn image_bytes(&self) -> u64 {
        self.image.size()
    }

    /// The kernel's counters (`u32` each, see [`crate::layout`]).
    pub fn stats(&self) -> &wgpu::Buffer {
        &self.stats
    }

    /// Zeroes the counters before a new frame is rendered into the target.
    pub fn clear_stats(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.clear_buffer(&self.stats, 0, None);
    }

    /// Encodes a copy of the counters into a new mappable buffer, to be
    /// read after the submission completes ([`crate::GpuStats::from_counters`]).
    pub fn encode_stats_readback(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
    ) -> wgpu::Buffer {
        let size = self.stats.size();
        let read = readback_buffer(ctx, "stats readback", size);
        encoder.copy_buffer_to_buffer(&self.stats, 0, &read, 0, size);
        read
    }
}
