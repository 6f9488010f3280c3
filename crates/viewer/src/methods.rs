//! The view settings (the pickers) and the integrators they make: each
//! view's method set up for the transfer function on the CPU (tables built
//! there) and uploaded for the GPU, with the time each took, so that the UI
//! can show that partial pre-integration rebuilds nothing when the transfer
//! function changes while full pre-integration rebuilds its table.

use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::Context;
use tetray_engine::Setup;
use tetray_gpu::{GpuContext, GpuIntegrator};
use tetray_integrate::{Method, OpacityMode, ScalarIntegrator, TransferFunction};
use tetray_project::SortKind;

use crate::present::Display;

/// The renderers the viewer can show.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RendererChoice {
    /// The wgpu compute ray caster, every display frame.
    GpuRaycast,
    /// Cell projection (crates/project) with a visibility sort: whole
    /// frames; the ray caster shows previews while the view changes when a
    /// frame is slower than the budget.
    Projection(SortKind),
    /// The CPU reference ray caster for still frames; the GPU shows
    /// previews while the view changes.
    CpuReference,
    /// Shear-warp (crates/shearwarp) on the file's regular grid, image data
    /// only, still frames on the CPU as the reference's; the Riemann sum
    /// post-classifies, every other method pre-integrates.
    ShearWarp,
}

impl RendererChoice {
    pub const ALL: [RendererChoice; 6] = [
        RendererChoice::GpuRaycast,
        RendererChoice::Projection(SortKind::Centroid),
        RendererChoice::Projection(SortKind::Mpvo),
        RendererChoice::Projection(SortKind::Mpvonc),
        RendererChoice::CpuReference,
        RendererChoice::ShearWarp,
    ];

    pub fn label(self) -> &'static str {
        match self {
            RendererChoice::GpuRaycast => "GPU ray caster",
            RendererChoice::Projection(SortKind::Centroid) => "cell projection, centroid sort",
            RendererChoice::Projection(SortKind::Mpvo) => "cell projection, MPVO sort",
            RendererChoice::Projection(SortKind::Mpvonc) => "cell projection, MPVONC sort",
            RendererChoice::CpuReference => "CPU reference (still frame)",
            RendererChoice::ShearWarp => "shear-warp (regular grids, still frame)",
        }
    }

    /// Whether it can integrate with `method` (the GPU renderers share the
    /// kernel's methods: every one but the f64 references).
    pub fn supports(self, method: Method) -> bool {
        match self {
            RendererChoice::GpuRaycast | RendererChoice::Projection(_) => method.has_gpu_kernel(),
            RendererChoice::CpuReference => true,
            // Only the classification depends on the method.
            RendererChoice::ShearWarp => true,
        }
    }

    /// Whether it renders on the CPU in a worker thread (the GPU ray
    /// caster shows previews meanwhile).
    pub fn on_cpu(self) -> bool {
        matches!(
            self,
            RendererChoice::CpuReference | RendererChoice::ShearWarp
        )
    }
}

/// Everything the pickers set.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    pub renderer: RendererChoice,
    pub methods: [Method; 2],
    pub compare: bool,
    pub display: Display,
    pub divider: f32,
    pub diff_scale: f32,
    pub unit_distance: f32,
    pub opacity_mode: OpacityMode,
    pub early_termination: f32,
    /// Render pixels per display pixel (per side).
    pub image_scale: f32,
    pub field: String,
    pub background: [f32; 3],
    pub show_stats: bool,
}

/// One view's integrator, on the CPU and the GPU.
pub struct ViewIntegrator {
    pub method: Method,
    pub cpu: Arc<ScalarIntegrator>,
    /// The GPU integrator: the method's own, or for the f64 references
    /// (no kernel) the closed form of the same model, used for previews.
    pub gpu: GpuIntegrator,
    pub gpu_method: Method,
    /// Table building in the integrator's setup (the pre-integration
    /// table; the Psi table is built once per process).
    pub setup: Duration,
    /// Packing and uploading for the GPU.
    pub upload: Duration,
}

impl ViewIntegrator {
    /// `method` with `tf` and the unit distance and opacity mode of
    /// `settings`, made by the engine as `tetray render` makes it.
    pub fn new(
        ctx: &GpuContext,
        setup: &Setup,
        method: Method,
        tf: &TransferFunction,
        settings: &Settings,
    ) -> anyhow::Result<ViewIntegrator> {
        let make =
            |m: Method| setup.integrator_with(m, tf, settings.unit_distance, settings.opacity_mode);
        let cpu = make(method)?;
        let setup_time = cpu.setup_time();
        let gpu_method = method.gpu_stand_in();
        let start = Instant::now();
        let gpu = if gpu_method == method {
            GpuIntegrator::new(ctx, &cpu)
        } else {
            GpuIntegrator::new(ctx, &make(gpu_method)?)
        }
        .with_context(|| format!("uploading the {gpu_method} integrator"))?;
        Ok(ViewIntegrator {
            method,
            cpu: Arc::new(cpu),
            gpu,
            gpu_method,
            setup: setup_time,
            upload: start.elapsed(),
        })
    }

    /// What a transfer-function change cost, in words.
    pub fn update_note(&self) -> String {
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        match self.method {
            Method::Preintegrated => format!(
                "{}: pre-integration table rebuilt in {:.1} ms, uploaded in {:.1} ms",
                self.method,
                ms(self.setup),
                ms(self.upload)
            ),
            Method::Ppi => format!(
                "ppi: no table rebuild (one Psi table per process): set up in {:.2} ms, \
                 uploaded in {:.2} ms",
                ms(self.setup),
                ms(self.upload)
            ),
            _ => format!(
                "{}: no table, knots set up in {:.2} ms, uploaded in {:.2} ms",
                self.method,
                ms(self.setup),
                ms(self.upload)
            ),
        }
    }
}
