//! Reading GPU results back: mappable buffers, a blocking map-and-copy, and
//! two timestamp queries around a pass. Shared by the ray caster, the cell
//! projection (`tetray-project`) and the viewer.

use std::time::Duration;

use crate::{GpuContext, GpuError};

/// A buffer of `size` bytes the GPU copies into and the CPU maps.
pub fn readback_buffer(ctx: &GpuContext, label: &str, size: u64) -> wgpu::Buffer {
    ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Waits for the queue, maps `buffer` and copies it out as `T`s.
pub fn read_buffer<T: bytemuck::Pod>(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
) -> Result<Vec<T>, GpuError> {
    let slice = buffer.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| GpuError::Readback(e.to_string()))?
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let data = {
        let view = slice
            .get_mapped_range()
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        // A copy, not a cast: the mapped bytes need not be aligned for T.
        bytemuck::pod_collect_to_vec(&view)
    };
    buffer.unmap();
    Ok(data)
}

/// Two timestamps around one pass: index 0 at its start, 1 at its end.
pub struct PassTimestamps {
    pub set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    period_ns: f32,
}

impl PassTimestamps {
    pub fn new(ctx: &GpuContext, label: &str) -> PassTimestamps {
        PassTimestamps {
            set: ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some(label),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            read: readback_buffer(ctx, label, 16),
            period_ns: ctx.queue.get_timestamp_period(),
        }
    }

    /// Encodes the resolve and the copy to the mappable buffer (after the
    /// pass).
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.set, 0..2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 16);
    }

    /// The pass's time once the submission is done (`None` when the
    /// timestamps did not advance).
    pub fn read(&self, ctx: &GpuContext) -> Result<Option<Duration>, GpuError> {
        let ticks: Vec<u64> = read_buffer(ctx, &self.read)?;
        let ns = ticks[1].saturating_sub(ticks[0]) as f64 * f64::from(self.period_ns);
        Ok((ns > 0.0).then(|| Duration::from_secs_f64(ns * 1e-9)))
    }
}
