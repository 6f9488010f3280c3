//! The window: the control panel, the image view with its overlays, and the
//! camera's mouse handling; the application's state and frame loop are in
//! `app.rs`, which knows nothing of these.

use std::time::Duration;

use egui::{PointerButton, Rect, Sense};

use crate::app::ViewerApp;
use crate::camera_ui;
use crate::engine::FrameKey;

impl ViewerApp {
    /// The image view: sizes the frame, handles the camera, advances the
    /// frame and draws it with its overlays.
    pub(crate) fn view(&mut self, ui: &mut egui::Ui) {
        let rect = ui.available_rect_before_wrap();
        if rect.width() < 1.0 || rect.height() < 1.0 {
            return;
        }
        let ppp = ui.ctx().pixels_per_point();
        let scale = self.settings.image_scale.clamp(0.05, 2.0);
        let size = (
            ((rect.width() * ppp * scale).round() as u32).max(1),
            ((rect.height() * ppp * scale).round() as u32).max(1),
        );
        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        self.handle_camera(ui, &response, rect, size);
        let Some(camera) = self.camera else {
            return;
        };
        let views = self.views.len() as u32;
        let key = FrameKey {
            camera,
            size,
            early_termination: self.settings.early_termination,
            generation: self.generation,
            views,
        };
        let still = self.key.as_ref() == Some(&key);
        self.key = Some(key.clone());
        let more = match self.advance_frame(&key, still) {
            Ok(more) => more,
            Err(e) => {
                self.error = Some(format!("{e:#}"));
                false
            }
        };
        if let Some((_, id)) = &self.display {
            ui.painter().image(
                *id,
                rect,
                Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                egui::Color32::WHITE,
            );
        }
        crate::overlay::draw(self, ui, rect);
        if more {
            if self.cpu.busy() {
                ui.ctx().request_repaint_after(Duration::from_millis(50));
            } else {
                ui.ctx().request_repaint();
            }
        }
    }

    fn handle_camera(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        rect: Rect,
        size: (u32, u32),
    ) {
        let (lo, hi) = self.setup.extent.bounds;
        let aspect = size.0 as f32 / size.1 as f32;
        if self.camera.is_none() || self.reset_camera {
            let mut camera = self.camera.unwrap_or_default();
            match camera.reset(lo, hi, aspect) {
                Ok(()) => self.camera = Some(camera),
                Err(e) => self.error = Some(format!("cannot fit the camera to the mesh: {e}")),
            }
            self.reset_camera = false;
        }
        let Some(camera) = self.camera.as_mut() else {
            return;
        };
        let delta = response.drag_delta();
        let view = rect.size();
        let shift = ui.input(|i| i.modifiers.shift);
        let result = if response.dragged_by(PointerButton::Primary) && !shift {
            camera_ui::orbit(camera, delta, view)
        } else if response.dragged_by(PointerButton::Secondary)
            || response.dragged_by(PointerButton::Middle)
            || (response.dragged_by(PointerButton::Primary) && shift)
        {
            camera_ui::pan(camera, delta, view)
        } else {
            Ok(())
        };
        let scroll = if response.hovered() {
            ui.input(|i| i.smooth_scroll_delta().y)
        } else {
            0.0
        };
        let result = result.and_then(|()| {
            if scroll != 0.0 {
                camera_ui::dolly(camera, scroll / 50.0)
            } else {
                Ok(())
            }
        });
        if let Err(e) = result {
            self.error = Some(format!("camera: {e}"));
        }
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        egui::Panel::left("controls")
            .resizable(true)
            .default_size(320.0)
            .show(ui, |ui| {
                // Scrolled by the wheel and the bar only: a drag in the panel
                // belongs to the transfer-function handles under it.
                egui::ScrollArea::vertical()
                    .scroll_source(egui::scroll_area::ScrollSource {
                        scroll_bar: true,
                        mouse_wheel: true,
                        ..egui::scroll_area::ScrollSource::NONE
                    })
                    .show(ui, |ui| {
                        let tf_changed = crate::panel::controls(self, ui);
                        self.apply_settings(tf_changed);
                    });
            });
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.view(ui));
        // Playing: the next step once this one's frame is finished.
        if let Some(due) = self.play(self.is_idle()) {
            ui.ctx().request_repaint_after(due);
        }
    }
}
