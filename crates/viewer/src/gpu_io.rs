//! Blocking reads of small GPU buffers: a frame's counters when it is
//! done, and images for screenshots. Never an image per display frame.

use tetray_core::Image;
use tetray_gpu::readback::{read_buffer, readback_buffer};
use tetray_gpu::{GpuContext, GpuTarget};

/// Waits for the queue, maps `buffer` and copies it out.
pub fn map_read(ctx: &GpuContext, buffer: &wgpu::Buffer) -> anyhow::Result<Vec<u8>> {
    Ok(read_buffer(ctx, buffer)?)
}

/// The float image of a target (premultiplied RGBA, row 0 at the top).
pub fn read_image(ctx: &GpuContext, target: &GpuTarget) -> anyhow::Result<Image> {
    let size = target.image_bytes();
    let read = readback_buffer(ctx, "image readback", size);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(target.image(), 0, &read, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let bytes = map_read(ctx, &read)?;
    let rgba: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
    Ok(Image::from_pixels(target.width(), target.height(), rgba)?)
}

/// Replaces a target's image with `image` (a CPU render shown through the
/// same display pass).
pub fn write_image(ctx: &GpuContext, target: &GpuTarget, image: &Image) {
    ctx.queue
        .write_buffer(target.image(), 0, bytemuck::cast_slice(&image.rgba));
}
