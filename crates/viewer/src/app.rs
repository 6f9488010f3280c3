//! The viewer application: state, the frame loop and the image view.
//! The control panel is in `panel.rs`, the overlays in `overlay.rs`.

use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::Context;
use glam::Vec3;
use tetray_core::Camera;
use tetray_engine::{Log, Setup};
use tetray_integrate::{Method, TransferFunction};
use tetray_scene::Scene;
use tetray_shearwarp::ShearWarp;

use crate::cpu::{CpuJob, CpuWork, CpuWorker};
use crate::engine::{FrameKey, GpuRenderer, Look, Phase, Progressive};
use crate::methods::{RendererChoice, Settings, ViewIntegrator};
use crate::present::{Display, DisplayTexture, read_texture};
use crate::projection::ProjectRenderer;
use crate::tf_editor::TfEditor;

/// Histogram bins under the opacity curve.
pub(crate) const HISTOGRAM_BINS: usize = 128;

/// How the viewer starts (the field, transfer function, integrator, unit
/// distance and opacity mode are the [`Setup`]'s).
#[derive(Debug, Clone)]
pub struct ViewerOptions {
    /// Render pixels per display pixel (default: 1 on a GPU, 0.25 on a
    /// CPU implementation such as lavapipe).
    pub image_scale: Option<f32>,
    /// Ray-casting time one display frame may take.
    pub budget: Duration,
    pub early_termination: f32,
}

impl Default for ViewerOptions {
    fn default() -> Self {
        ViewerOptions {
            image_scale: None,
            budget: Duration::from_millis(40),
            early_termination: 1.0,
        }
    }
}

/// The viewer.
pub struct ViewerApp {
    /// The engine's setup: the scene of the active field (and the regular
    /// grid of image data), the defaults, what integrators are made from.
    pub(crate) setup: Setup,
    pub(crate) gpu: GpuRenderer,
    render_state: egui_wgpu::RenderState,
    pub(crate) progressive: Progressive,
    pub(crate) display: Option<(DisplayTexture, egui::TextureId)>,
    pub settings: Settings,
    /// The settings the integrators were made for.
    applied: Settings,
    pub(crate) tf_editor: TfEditor,
    pub(crate) views: Vec<ViewIntegrator>,
    /// What the last transfer-function change cost, per view.
    pub(crate) tf_notes: Vec<String>,
    pub(crate) generation: u64,
    pub(crate) camera: Option<Camera>,
    pub(crate) reset_camera: bool,
    pub(crate) cpu: CpuWorker,
    /// The cell projection, prepared when first picked.
    projection: Option<ProjectRenderer>,
    /// Shear-warp's classified grids, one per view, and the generation of
    /// the settings they were made for.
    shear_warp: Option<(u64, Vec<Arc<ShearWarp>>)>,
    /// The key of the frame a CPU or projection frame was shown for.
    external_shown: Option<FrameKey>,
    pub(crate) key: Option<FrameKey>,
    pub error: Option<String>,
    pub(crate) screenshot_path: String,
    pub(crate) screenshot_message: Option<(bool, String)>,
    /// Display frame interval while frames are being made (ms, smoothed).
    pub(crate) ui_ms: Option<f64>,
    last_frame: Option<Instant>,
    /// The data's time steps, when it has several.
    pub(crate) time: Option<crate::series::TimeSeries>,
    pub(crate) recorder: crate::series::RecordPanel,
}

impl ViewerApp {
    /// The viewer on eframe's wgpu device (the ray caster shares it).
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        setup: Setup,
        options: ViewerOptions,
    ) -> anyhow::Result<ViewerApp> {
        let render_state = cc
            .wgpu_render_state
            .clone()
            .context("the viewer needs eframe's wgpu renderer")?;
        let ctx = tetray_gpu::GpuContext::from_device(
            render_state.device.clone(),
            render_state.queue.clone(),
            render_state.adapter.get_info(),
        );
        let scene = Arc::clone(setup.scene_arc().context("the viewer needs tetrahedra")?);
        let tf_editor = tf_editor(&setup, &scene.scalar);
        let image_scale = options
            .image_scale
            .unwrap_or(if ctx.is_cpu() { 0.25 } else { 1.0 });
        let settings = Settings {
            renderer: RendererChoice::GpuRaycast,
            methods: [setup.method, Method::Exact],
            compare: false,
            display: Display::Divider,
            divider: 0.5,
            diff_scale: 0.05,
            unit_distance: setup.unit_distance,
            opacity_mode: setup.integrator_options.opacity_mode,
            early_termination: options.early_termination,
            image_scale,
            field: setup.extent.field.clone(),
            background: [0.0; 3],
            show_stats: true,
        };
        let gpu = GpuRenderer::new(ctx, &scene)?;
        let mut app = ViewerApp {
            setup,
            gpu,
            render_state,
            progressive: Progressive::new(options.budget),
            display: None,
            applied: settings.clone(),
            settings,
            tf_editor,
            views: Vec::new(),
            tf_notes: Vec::new(),
            generation: 0,
            camera: None,
            reset_camera: false,
            cpu: CpuWorker::default(),
            projection: None,
            shear_warp: None,
            external_shown: None,
            key: None,
            error: None,
            screenshot_path: "tetray-view.png".to_string(),
            screenshot_message: None,
            ui_ms: None,
            last_frame: None,
            time: None,
            recorder: crate::series::RecordPanel::default(),
        };
        app.rebuild_integrators()?;
        Ok(app)
    }

    /// The active field's scene.
    pub(crate) fn scene(&self) -> &Arc<Scene> {
        self.setup
            .scene_arc()
            .expect("the viewer's setup has tetrahedra")
    }

    /// The point fields the viewer can show.
    pub(crate) fn field_names(&self) -> Vec<String> {
        self.scene()
            .mesh
            .fields
            .iter()
            .map(|f| f.name.clone())
            .collect()
    }

    /// The adapter the views render on.
    pub fn adapter_name(&self) -> String {
        self.gpu.ctx.adapter_name()
    }

    /// Whether the current frame is finished (nothing left to render).
    pub fn is_idle(&self) -> bool {
        self.key.is_some()
            && self.progressive.phase() == Phase::Done
            && !self.cpu.busy()
            && (self.settings.renderer == RendererChoice::GpuRaycast
                || self.external_shown == self.key)
    }

    /// The statistics of the last finished frame.
    pub fn frame_report(&self) -> Option<crate::engine::FrameReport> {
        self.progressive.report
    }

    /// Size of the last preview shown while the view changed.
    pub fn preview_size(&self) -> Option<(u32, u32)> {
        self.progressive.preview_size()
    }

    /// The camera of the view (once the first frame has sized it).
    pub fn camera(&self) -> Option<Camera> {
        self.camera
    }

    /// What is on screen: the display texture read back (width, height,
    /// RGBA8 row-major, row 0 at the top). For tests and checks; the
    /// display itself never leaves the GPU.
    pub fn displayed_image(&self) -> anyhow::Result<(u32, u32, Vec<[u8; 4]>)> {
        let (texture, _) = self.display.as_ref().context("nothing displayed yet")?;
        let (w, h) = texture.size();
        Ok((w, h, read_texture(&self.gpu.ctx, texture)?))
    }

    /// The transfer function being edited.
    pub fn transfer_function(&self) -> anyhow::Result<TransferFunction> {
        self.tf_editor.transfer_function()
    }

    /// Makes the integrators of the views for the current settings and
    /// transfer function; on failure the previous ones stay.
    pub(crate) fn rebuild_integrators(&mut self) -> anyhow::Result<()> {
        let tf = self.tf_editor.transfer_function()?;
        let count = if self.settings.compare { 2 } else { 1 };
        let views = self.settings.methods[..count]
            .iter()
            .map(|&m| ViewIntegrator::new(&self.gpu.ctx, &self.setup, m, &tf, &self.settings))
            .collect::<anyhow::Result<Vec<_>>>()?;
        self.tf_notes = views.iter().map(ViewIntegrator::update_note).collect();
        self.views = views;
        self.applied = self.settings.clone();
        self.generation += 1;
        Ok(())
    }

    /// A new active field: the engine's scene and transfer function for
    /// it, the upload and the editor over its range and histogram.
    pub(crate) fn change_field(&mut self, field: &str) -> anyhow::Result<()> {
        self.setup.set_field(field, Log::quiet())?;
        let scene = Arc::clone(self.scene());
        self.gpu.set_scene(&scene)?;
        self.projection = None;
        let mut editor = tf_editor(&self.setup, &scene.scalar);
        editor.preset_path = std::mem::take(&mut self.tf_editor.preset_path);
        editor.rescale = self.tf_editor.rescale;
        self.tf_editor = editor;
        self.rebuild_integrators()
    }

    /// Drops what was made from the scene's values besides the ray
    /// caster's upload (the projection's upload, shear-warp's grids).
    pub(crate) fn drop_derived(&mut self) {
        self.projection = None;
        self.shear_warp = None;
    }

    /// Applies settings changed in the panel since the integrators were made.
    pub(crate) fn apply_settings(&mut self, tf_changed: bool) {
        let (s, a) = (&self.settings, &self.applied);
        let renderer_changed = s.renderer != a.renderer;
        let field_changed = s.field != a.field;
        let rebuild = tf_changed
            || s.methods != a.methods
            || s.compare != a.compare
            || s.unit_distance != a.unit_distance
            || s.opacity_mode != a.opacity_mode;
        let changed = *s != *a;
        if renderer_changed {
            // The other renderer's frame: start over.
            self.generation += 1;
        }
        let result = if field_changed {
            let field = self.settings.field.clone();
            self.change_field(&field)
        } else if rebuild {
            self.rebuild_integrators()
        } else {
            self.applied = self.settings.clone();
            Ok(())
        };
        match result {
            Err(e) => {
                self.error = Some(format!("{e:#}"));
                // Keep what renders: the settings the integrators were made for.
                self.settings = self.applied.clone();
            }
            Ok(()) if tf_changed || changed => self.error = None,
            Ok(()) => {}
        }
    }

    pub(crate) fn look(&self) -> Look {
        Look {
            display: self.settings.display,
            divider: self.settings.divider,
            background: Vec3::from(self.settings.background),
            diff_scale: self.settings.diff_scale,
        }
    }

    /// Does this display frame's rendering; returns whether more is left.
    pub(crate) fn advance_frame(&mut self, key: &FrameKey, still: bool) -> anyhow::Result<bool> {
        self.ensure_display(key.size);
        let look = self.look();
        let (output, _) = self.display.as_ref().context("no display texture")?;
        let integrators: Vec<_> = self.views.iter().map(|v| &v.gpu).collect();
        let renderer = self.settings.renderer;
        let shown = self.external_shown.as_ref() == Some(key);
        let gpu = &self.gpu;
        let mut more = match renderer {
            RendererChoice::GpuRaycast => {
                self.progressive
                    .advance(gpu, key, &integrators, &look, output, true)?
            }
            // A CPU or projection frame is shown: only the display pass
            // may run again.
            _ if shown => {
                self.progressive
                    .advance(gpu, key, &integrators, &look, output, false)?;
                false
            }
            RendererChoice::Projection(sort) => {
                if self.projection.is_none() {
                    let scene = self.setup.scene_arc().context("no tetrahedra")?;
                    self.projection = Some(ProjectRenderer::new(&gpu.ctx, scene)?);
                }
                let projection = self.projection.as_mut().context("no projection")?;
                // Follow the camera when a frame fits the budget; else
                // ray-cast previews until it stops.
                let fast = projection
                    .last_frame
                    .is_some_and(|t| t <= self.progressive.pacer.budget);
                if still || fast {
                    let (images, report) = projection.render(&gpu.ctx, key, sort, &integrators)?;
                    self.progressive
                        .show_frames(gpu, key, &images, report, &look, output)?;
                    self.external_shown = Some(key.clone());
                    false
                } else {
                    self.progressive
                        .advance(gpu, key, &integrators, &look, output, false)?;
                    true
                }
            }
            RendererChoice::CpuReference | RendererChoice::ShearWarp => {
                self.progressive
                    .advance(gpu, key, &integrators, &look, output, false)?
            }
        };
        let cpu_mode = renderer.on_cpu();
        if let Some(result) = self.cpu.poll() {
            let frame = result.context("the CPU reference render")?;
            if &frame.key == key && cpu_mode {
                self.progressive.show_frames(
                    gpu,
                    key,
                    &frame.images,
                    frame.report,
                    &look,
                    output,
                )?;
                self.external_shown = Some(key.clone());
            }
        }
        if cpu_mode && self.external_shown.as_ref() != Some(key) {
            if still && !self.cpu.is_working_on(key) {
                let work = if renderer == RendererChoice::ShearWarp {
                    CpuWork::ShearWarp(self.shear_warp_views()?)
                } else {
                    CpuWork::Raycast {
                        scene: Arc::clone(self.scene()),
                        integrators: self.views.iter().map(|v| Arc::clone(&v.cpu)).collect(),
                    }
                };
                self.cpu.request(CpuJob {
                    key: key.clone(),
                    work,
                });
            }
            more = true;
        }
        self.tick(more);
        Ok(more || self.cpu.busy())
    }

    /// Shear-warp's grid classified for each view's method with the
    /// current transfer function and options (made once per generation;
    /// the run-length encodings are built by the first frame, on the
    /// worker).
    fn shear_warp_views(&mut self) -> anyhow::Result<Vec<Arc<ShearWarp>>> {
        if let Some((generation, views)) = &self.shear_warp
            && *generation == self.generation
        {
            return Ok(views.clone());
        }
        let tf = self.tf_editor.transfer_function()?;
        let views = self
            .views
            .iter()
            .map(|view| {
                self.setup
                    .shear_warp(
                        view.method,
                        &tf,
                        self.settings.unit_distance,
                        self.settings.opacity_mode,
                    )
                    .map(Arc::new)
            })
            .collect::<Result<Vec<_>, _>>()?;
        self.shear_warp = Some((self.generation, views.clone()));
        Ok(views)
    }

    /// Times display frames while frames are being made.
    fn tick(&mut self, busy: bool) {
        let now = Instant::now();
        if let (Some(last), true) = (self.last_frame, busy) {
            let ms = now.duration_since(last).as_secs_f64() * 1e3;
            self.ui_ms = Some(self.ui_ms.map_or(ms, |old| 0.8 * old + 0.2 * ms));
        }
        self.last_frame = busy.then_some(now);
    }

    /// A display texture of `size`, registered with egui.
    fn ensure_display(&mut self, size: (u32, u32)) {
        if self.display.as_ref().map(|(t, _)| t.size()) == Some(size) {
            return;
        }
        let texture = DisplayTexture::new(&self.gpu.ctx, size.0, size.1);
        let mut renderer = self.render_state.renderer.write();
        let id = match &self.display {
            Some((_, id)) => {
                renderer.update_egui_texture_from_wgpu_texture(
                    &self.render_state.device,
                    &texture.view,
                    wgpu::FilterMode::Linear,
                    *id,
                );
                *id
            }
            None => renderer.register_native_texture(
                &self.render_state.device,
                &texture.view,
                wgpu::FilterMode::Linear,
            ),
        };
        self.display = Some((texture, id));
    }

    /// Saves the current frame (finished first): PNG as displayed, EXR as
    /// the float image of each view (B's beside A's, `-b` before the
    /// extension).
    pub fn save_screenshot(
        &mut self,
        path: &std::path::Path,
    ) -> anyhow::Result<Vec<std::path::PathBuf>> {
        let key = self.key.clone().context("nothing rendered yet")?;
        // A finished frame (the CPU's, when shown) is read as it is.
        let integrators: Vec<_> = self.views.iter().map(|v| &v.gpu).collect();
        let images = self
            .progressive
            .finished_images(&self.gpu, &key, &integrators)?;
        crate::screenshot::save(path, &images, &key, &self.look())
    }
}

/// The editor of the setup's transfer function over its field's range and
/// the histogram of `values`.
fn tf_editor(setup: &Setup, values: &[f32]) -> TfEditor {
    let range = setup.extent.range;
    TfEditor::new(&setup.tf, range, histogram(values, range, HISTOGRAM_BINS))
}

/// Counts of `values` in `bins` equal bins over `[lo, hi]`.
pub(crate) fn histogram(values: &[f32], (lo, hi): (f32, f32), bins: usize) -> Vec<u32> {
    let mut counts = vec![0u32; bins.max(1)];
    let width = hi - lo;
    for &v in values {
        let t = if width > 0.0 { (v - lo) / width } else { 0.0 };
        let bin = ((t * bins as f32) as usize).min(bins.max(1) - 1);
        counts[bin] += 1;
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histogram_puts_the_ends_in_the_end_bins() {
        let counts = histogram(&[0.0, 0.5, 0.99, 1.0, 0.25], (0.0, 1.0), 4);
        assert_eq!(counts, vec![1, 1, 1, 2]);
        assert_eq!(histogram(&[3.0, 3.0], (3.0, 3.0), 2), vec![2, 0]);
    }
}
