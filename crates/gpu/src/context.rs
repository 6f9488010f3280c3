//! The adapter and device: chosen by wgpu's environment variables
//! (`WGPU_BACKEND`, `WGPU_ADAPTER_NAME`, `WGPU_POWER_PREF`), with the
//! adapter's own limits requested so that large meshes fit.

use std::sync::{Arc, Mutex};

use crate::GpuError;

/// Whether Mesa's Vulkan device-selection layer could only fail noisily
/// here, so that a binary should turn it off (`NODEVICE_SELECT=1`) before
/// any thread starts.
///
/// `VK_LAYER_MESA_device_select` (an implicit layer installed with Mesa's
/// Vulkan drivers, lavapipe included) orders the physical devices by the
/// display's GPU: since wgpu enables `VK_KHR_wayland_surface` whenever the
/// driver has it, the layer calls `wl_display_connect(NULL)` from
/// `vkEnumeratePhysicalDevices`, and libwayland prints `error:
/// XDG_RUNTIME_DIR is invalid or not set in the environment.` on stderr
/// (once per enumeration, twice per adapter probe) when there is no runtime
/// directory, i.e. no Wayland display to ask. The layer's own switch,
/// `NODEVICE_SELECT=1`, is read by the Vulkan loader from the environment
/// when an instance is created; the order the layer would give matters
/// little here, as wgpu ranks adapters by type and `WGPU_POWER_PREF`
/// itself. False when the user chose (`NODEVICE_SELECT`,
/// `MESA_VK_DEVICE_SELECT`, `DRI_PRIME`) or when a Wayland connection could
/// succeed. This library never writes the environment: other threads (and
/// the Vulkan loader's C code) may be reading it.
pub fn device_select_would_be_noisy() -> bool {
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    if set("NODEVICE_SELECT") || set("MESA_VK_DEVICE_SELECT") || set("DRI_PRIME") {
        return false;
    }
    // libwayland's own test: XDG_RUNTIME_DIR must name a directory, unless
    // WAYLAND_DISPLAY is an absolute socket path.
    let runtime_dir_ok =
        std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|dir| std::path::Path::new(&dir).is_dir());
    let absolute_socket =
        std::env::var_os("WAYLAND_DISPLAY").is_some_and(|d| std::path::Path::new(&d).is_absolute());
    !(runtime_dir_ok || absolute_socket)
}

/// A device ready for the ray caster.
pub struct GpuContext {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    pub limits: wgpu::Limits,
    /// Whether passes can be timed with timestamp queries.
    pub timestamps: bool,
    /// Why the device was lost, once it is (a driver reset, a removed
    /// GPU, a destroyed device): every operation then fails with
    /// [`GpuError::DeviceLost`] instead of reaching the device.
    lost: Arc<Mutex<Option<String>>>,
}

impl GpuContext {
    /// The adapter named by the environment, or the default one.
    pub fn new() -> Result<GpuContext, GpuError> {
        pollster::block_on(Self::new_async())
    }

    async fn new_async() -> Result<GpuContext, GpuError> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        if std::env::var_os("WGPU_BACKEND").is_none() {
            // Compute needs no window system: skip the GL probe (and its
            // complaints about display variables) unless asked for.
            descriptor.backends = wgpu::Backends::PRIMARY;
        }
        let instance = wgpu::Instance::new(descriptor);
        let adapter = wgpu::util::initialize_adapter_from_env_or_default(&instance, None)
            .await
            .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        let limits = adapter.limits();
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        // Optional features, taken where the adapter has them: timestamps
        // for the ray caster, float blending and dual-source blending for
        // the cell projection's render targets (tetray_project).
        let required_features = adapter.features()
            & (wgpu::Features::TIMESTAMP_QUERY
                | wgpu::Features::FLOAT32_BLENDABLE
                | wgpu::Features::DUAL_SOURCE_BLENDING);
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("tetray"),
                required_features,
                required_limits: limits.clone(),
                experimental_features: wgpu::ExperimentalFeatures::disabled(),
                memory_hints: wgpu::MemoryHints::Performance,
                trace: wgpu::Trace::Off,
            })
            .await
            .map_err(|e| GpuError::Device {
                adapter: info.name.clone(),
                message: e.to_string(),
            })?;
        Ok(GpuContext::with_device(
            device, queue, info, limits, timestamps,
        ))
    }

    /// The context of `device`, watching for its loss.
    pub(crate) fn with_device(
        device: wgpu::Device,
        queue: wgpu::Queue,
        info: wgpu::AdapterInfo,
        limits: wgpu::Limits,
        timestamps: bool,
    ) -> GpuContext {
        let lost = Arc::new(Mutex::new(None));
        let record = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            let why = if message.is_empty() {
                format!("{reason:?}")
            } else {
                format!("{reason:?}: {message}")
            };
            *record
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner) = Some(why);
        });
        GpuContext {
            device,
            queue,
            info,
            limits,
            timestamps,
            lost,
        }
    }

    /// Fails with [`GpuError::DeviceLost`] once the device is lost (the
    /// loss is learnt from the device's callback, which a poll delivers).
    pub fn check(&self) -> Result<(), GpuError> {
        let polled = self.device.poll(wgpu::PollType::Poll);
        let lost = self
            .lost
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .clone();
        match (lost, polled) {
            (Some(why), _) => Err(GpuError::DeviceLost {
                adapter: self.info.name.clone(),
                why,
            }),
            (None, Err(e)) => Err(GpuError::DeviceLost {
                adapter: self.info.name.clone(),
                why: e.to_string(),
            }),
            (None, Ok(_)) => Ok(()),
        }
    }

    /// Submits `commands` and waits until the device has run them; the
    /// wall time from submission to completion.
    pub fn submit_and_wait(
        &self,
        commands: wgpu::CommandBuffer,
    ) -> Result<std::time::Duration, GpuError> {
        self.check()?;
        let start = std::time::Instant::now();
        let submission = self.queue.submit([commands]);
        let waited = self.device.poll(wgpu::PollType::Wait {
            submission_index: Some(submission),
            timeout: None,
        });
        // A loss during the work shows here first.
        self.check()?;
        waited.map_err(|e| GpuError::Driver(e.to_string()))?;
        Ok(start.elapsed())
    }

    /// "name (backend, device type)", for reports.
    pub fn adapter_name(&self) -> String {
        format!(
            "{} ({:?}, {:?})",
            self.info.name, self.info.backend, self.info.device_type
        )
    }

    /// Whether the adapter is a CPU implementation (lavapipe, WARP).
    pub fn is_cpu(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }
}

/// The descriptor of a 2-D texture of `width x height` texels, one mip
/// level, one sample.
pub fn texture_2d(
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::TextureDescriptor<'_> {
    wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    }
}
