//! A context on a device made by someone else: a GUI toolkit (the viewer's
//! eframe) owns the device its windows draw with, and the ray caster must
//! render on that same device for its images to be shown without a copy
//! through the CPU.

use crate::GpuContext;

impl GpuContext {
    /// The ray caster on an existing device and queue. The limits and the
    /// timestamp support are the device's (what it was created with, not
    /// what its adapter could give): create it with
    /// [`GpuContext::device_request`] to get everything the adapter has.
    pub fn from_device(
        device: wgpu::Device,
        queue: wgpu::Queue,
        info: wgpu::AdapterInfo,
    ) -> GpuContext {
        let limits = device.limits();
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        GpuContext::with_device(device, queue, info, limits, timestamps)
    }

    /// What to ask `adapter` for, as [`GpuContext::new`] does: its own
    /// limits (the most it has, so that large meshes fit) and the optional
    /// features the renderers use where it has them (timestamps for the
    /// ray caster; float and dual-source blending for the cell
    /// projection's targets).
    pub fn device_request(adapter: &wgpu::Adapter) -> (wgpu::Features, wgpu::Limits) {
        let features = adapter.features()
            & (wgpu::Features::TIMESTAMP_QUERY
                | wgpu::Features::FLOAT32_BLENDABLE
                | wgpu::Features::DUAL_SOURCE_BLENDING);
        (features, adapter.limits())
    }
}
