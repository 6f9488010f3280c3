//! Recording what the viewer shows to an animation, with the writer of
//! `tetray animate` ([`tetray_core::Movie`]: a GIF, an MP4 through ffmpeg,
//! or a folder of PNG frames): the time steps, or an orbit of the current
//! view about its view-up. Frames are rendered by the engine's GPU ray
//! caster with the viewer's transfer function, first method, unit
//! distance, opacity mode, early termination and background, at the size
//! of the view's image, from the current camera.

use std::path::Path;

use anyhow::Context;
use glam::Vec3;
use tetray_core::Movie;
use tetray_engine::{Engine, RendererChoice, WalkOptions};
use tetray_integrate::{Method, ScalarIntegrator};

use crate::app::ViewerApp;
use crate::series::Recording;

impl ViewerApp {
    /// Records `what` to `path` at `fps` frames per second; returns the
    /// number of frames. The viewer's state (its step, integrators,
    /// camera) is as before afterwards.
    pub fn record(&mut self, path: &Path, what: Recording, fps: u32) -> anyhow::Result<usize> {
        let key = self.key.clone().context("nothing rendered yet")?;
        let camera = self.camera.context("nothing rendered yet")?;
        let tf = self.tf_editor.transfer_function()?;
        let method = self.settings.methods[0];
        let integrator = self.setup.integrator_with(
            method,
            &tf,
            self.settings.unit_distance,
            self.settings.opacity_mode,
        )?;
        let walk = WalkOptions {
            early_termination: self.settings.early_termination,
            ..WalkOptions::default()
        };
        let background = Vec3::from(self.settings.background);
        let mut movie = Movie::create(path, key.size, fps, background)?;
        let shown = self.time_step();
        let saved = self.use_integrator(integrator.clone(), method);
        let result = (|| -> anyhow::Result<()> {
            let quiet = |_: String| {};
            let mut engine = Engine::new(RendererChoice::Gpu, &self.setup, &quiet)?;
            match what {
                Recording::Orbit { degrees, frames } => {
                    for i in 0..frames.max(1) {
                        let mut turned = camera;
                        turned
                            .azimuth(degrees * i as f32 / frames.max(1) as f32)
                            .and_then(|()| turned.orthogonalize_view_up())
                            .context("turning the camera")?;
                        let frame = engine.render(&self.setup, &turned, walk, key.size, None)?;
                        movie.add(&frame.image)?;
                    }
                }
                Recording::TimeSteps => {
                    let steps = self.time.as_ref().map_or(0, |t| t.len());
                    anyhow::ensure!(steps > 0, "the data has no time steps to record");
                    for step in 0..steps {
                        if Some(step) != self.time_step() {
                            let kept = self.go_to_step(step)?;
                            // A step made anew has the setup's own integrator.
                            self.use_integrator(integrator.clone(), method);
                            if kept {
                                engine.take_fields(&self.setup, &quiet)?;
                            } else {
                                engine = Engine::new(RendererChoice::Gpu, &self.setup, &quiet)?;
                            }
                        }
                        let frame = engine.render(&self.setup, &camera, walk, key.size, None)?;
                        movie.add(&frame.image)?;
                    }
                }
            }
            Ok(())
        })();
        self.use_integrator(saved.0, saved.1);
        let back = match shown {
            Some(step) if Some(step) != self.time_step() => self.go_to_step(step).map(|_| ()),
            _ => Ok(()),
        };
        result?;
        back?;
        let frames = movie.frames();
        movie.finish()?;
        Ok(frames)
    }

    /// Puts `integrator` of `method` in the setup; returns what was there.
    fn use_integrator(
        &mut self,
        integrator: ScalarIntegrator,
        method: Method,
    ) -> (ScalarIntegrator, Method) {
        (
            std::mem::replace(&mut self.setup.integrator, integrator),
            std::mem::replace(&mut self.setup.method, method),
        )
    }
}

/// The panel's Record section: the file (.gif, .mp4 or a folder/), the
/// rate, the orbit, and a button per recording.
pub(crate) fn controls(app: &mut ViewerApp, ui: &mut egui::Ui) {
    let panel = &mut app.recorder;
    ui.horizontal(|ui| {
        ui.label("file");
        ui.text_edit_singleline(&mut panel.path);
    });
    ui.add(
        egui::DragValue::new(&mut panel.fps)
            .range(1..=240)
            .suffix(" frames/s"),
    );
    ui.horizontal(|ui| {
        ui.add(
            egui::DragValue::new(&mut panel.degrees)
                .range(-3600.0..=3600.0)
                .suffix(" deg"),
        );
        ui.add(
            egui::DragValue::new(&mut panel.frames)
                .range(1..=10_000)
                .suffix(" frames"),
        );
    });
    let mut asked = None;
    ui.horizontal(|ui| {
        if ui.button("Record orbit").clicked() {
            asked = Some(Recording::Orbit {
                degrees: panel.degrees,
                frames: panel.frames,
            });
        }
        if app.time.is_some() && ui.button("Record time steps").clicked() {
            asked = Some(Recording::TimeSteps);
        }
    });
    if let Some(what) = asked {
        let path = std::path::PathBuf::from(&app.recorder.path);
        let fps = app.recorder.fps;
        app.recorder.message = Some(match app.record(&path, what, fps) {
            Ok(frames) => (
                false,
                format!("wrote {frames} frames to {}", path.display()),
            ),
            Err(e) => (true, format!("{e:#}")),
        });
    }
    if let Some((error, text)) = &app.recorder.message {
        let color = if *error {
            ui.visuals().error_fg_color
        } else {
            ui.visuals().text_color()
        };
        ui.colored_label(color, text);
    }
}
