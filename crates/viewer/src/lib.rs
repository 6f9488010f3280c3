//! `tetray view`: the GPU ray caster in an eframe/egui window on wgpu.
//!
//! The ray caster renders on eframe's own device ([`wgpu_setup`] asks the
//! adapter for what the kernel needs) into float buffers that stay on the
//! GPU; a display pass (shaders/present.wgsl) turns them into the texture
//! egui draws. Frames are progressive: a preview sized to the frame budget
//! while the view changes, then the full frame a few rows per display frame.
//!
//! - [`ViewerApp`]: the application (also driven by the egui_kittest tests);
//! - [`run`]: opens the window.

mod app;
pub mod camera_ui;
pub mod cpu;
pub mod engine;
pub mod gpu_io;
pub mod methods;
mod overlay;
pub mod pacing;
mod panel;
pub mod present;
pub mod projection;
mod record;
mod screenshot;
mod series;
pub mod tf_editor;
mod time;
mod window;

use std::sync::Arc;

pub use app::{ViewerApp, ViewerOptions};
pub use series::{Recording, TimeSeries};

/// Default window size (points).
pub const WINDOW_SIZE: [f32; 2] = [1280.0, 800.0];

/// How eframe makes its device: the adapter wgpu's environment variables
/// name (`WGPU_ADAPTER_NAME`, `WGPU_BACKEND`, `WGPU_POWER_PREF`), as the CLI
/// picks it, asked for its own limits and the renderers' optional features
/// ([`tetray_gpu::GpuContext::device_request`]).
pub fn wgpu_setup() -> egui_wgpu::WgpuSetup {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    if std::env::var_os("WGPU_BACKEND").is_none() {
        // The ray caster is compute: Vulkan / Metal / DX12 only.
        setup.instance_descriptor.backends = wgpu::Backends::PRIMARY;
    }
    if let Ok(wanted) = std::env::var("WGPU_ADAPTER_NAME") {
        let wanted = wanted.to_lowercase();
        setup.native_adapter_selector = Some(Arc::new(move |adapters, _surface| {
            adapters
                .iter()
                .find(|a| a.get_info().name.to_lowercase().contains(&wanted))
                .cloned()
                .ok_or_else(|| format!("no adapter named like {wanted:?} (WGPU_ADAPTER_NAME)"))
        }));
    }
    setup.device_descriptor = Arc::new(|adapter| {
        let (required_features, required_limits) = tetray_gpu::GpuContext::device_request(adapter);
        wgpu::DeviceDescriptor {
            label: Some("tetray view"),
            required_features,
            required_limits,
            ..Default::default()
        }
    });
    egui_wgpu::WgpuSetup::CreateNew(setup)
}

/// Opens the viewer window on `setup` (made by the engine, with the
/// regular grid of image data for shear-warp: `Representation::Both`) and
/// returns when it is closed; `series`, the data's time steps, gives it a
/// time slider.
pub fn run(
    setup: tetray_engine::Setup,
    options: ViewerOptions,
    series: Option<TimeSeries>,
) -> anyhow::Result<()> {
    let title = format!("tetray view - {}", setup.name());
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(&title)
            .with_inner_size(WINDOW_SIZE),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: wgpu_setup(),
            ..Default::default()
        },
        ..Default::default()
    };
    eframe::run_native(
        &title,
        native,
        Box::new(move |cc| {
            let mut app = ViewerApp::new(cc, setup, options)?;
            if let Some(series) = series {
                app.set_time_series(series);
            }
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("the viewer window: {e}"))
}
