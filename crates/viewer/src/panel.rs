//! The control panel: renderer, methods, comparison, options, the
//! transfer-function editor, the camera readout and screenshots.

use egui::Ui;
use tetray_integrate::{Method, OpacityMode};

use crate::app::ViewerApp;
use crate::camera_ui::vtk_flags;
use crate::methods::RendererChoice;
use crate::present::Display;

/// Draws the panel; returns whether the transfer function changed.
pub fn controls(app: &mut ViewerApp, ui: &mut Ui) -> bool {
    ui.heading("tetray view");
    ui.label(format!(
        "{} · {} tetrahedra",
        app.setup.name(),
        app.setup.tet_count()
    ));
    if let Some(error) = &app.error {
        ui.colored_label(ui.visuals().error_fg_color, format!("error: {error}"));
    }
    if app.time.is_some() {
        egui::CollapsingHeader::new("Time")
            .default_open(true)
            .show(ui, |ui| crate::time::controls(app, ui));
    }
    egui::CollapsingHeader::new("Rendering")
        .default_open(true)
        .show(ui, |ui| rendering(app, ui));
    let mut tf_changed = false;
    egui::CollapsingHeader::new("Transfer function")
        .default_open(true)
        .show(ui, |ui| {
            tf_changed = app.tf_editor.ui(ui);
            for note in &app.tf_notes {
                ui.label(egui::RichText::new(note).small());
            }
        });
    egui::CollapsingHeader::new("Camera")
        .default_open(true)
        .show(ui, |ui| camera(app, ui));
    egui::CollapsingHeader::new("Screenshot")
        .default_open(false)
        .show(ui, |ui| screenshot(app, ui));
    egui::CollapsingHeader::new("Record")
        .default_open(false)
        .show(ui, |ui| crate::record::controls(app, ui));
    tf_changed
}

fn method_picker(ui: &mut Ui, label: &str, method: &mut Method, renderer: RendererChoice) {
    egui::ComboBox::from_label(label)
        .selected_text(method.name())
        .show_ui(ui, |ui| {
            for m in Method::ALL {
                let supported = renderer.supports(m);
                ui.add_enabled_ui(supported, |ui| {
                    ui.selectable_value(method, m, m.name())
                        .on_disabled_hover_text("f64 reference: CPU renderer only");
                });
            }
        });
}

fn rendering(app: &mut ViewerApp, ui: &mut Ui) {
    let fields = app.field_names();
    let paraview_unit_distance = app.setup.extent.paraview_unit_distance;
    let s = &mut app.settings;
    egui::ComboBox::from_label("Renderer")
        .selected_text(s.renderer.label())
        .show_ui(ui, |ui| {
            for r in RendererChoice::ALL {
                let available = r != RendererChoice::ShearWarp || app.setup.image().is_some();
                ui.add_enabled_ui(available, |ui| {
                    ui.selectable_value(&mut s.renderer, r, r.label())
                        .on_disabled_hover_text(
                            "shear-warp renders image data (.vti, legacy STRUCTURED_POINTS)",
                        );
                });
            }
        });
    // A method the renderer cannot run falls back to its closed form.
    for m in &mut s.methods {
        if !s.renderer.supports(*m) {
            *m = m.gpu_stand_in();
        }
    }
    method_picker(ui, "Integrator", &mut s.methods[0], s.renderer);
    ui.checkbox(&mut s.compare, "Compare with a second method");
    if s.compare {
        method_picker(ui, "Integrator B", &mut s.methods[1], s.renderer);
        ui.horizontal(|ui| {
            ui.radio_value(&mut s.display, Display::Divider, "Divider");
            ui.radio_value(&mut s.display, Display::Difference, "Difference");
        });
        if s.display == Display::Divider {
            ui.add(egui::Slider::new(&mut s.divider, 0.0..=1.0).text("divider"));
        } else {
            ui.add(
                egui::Slider::new(&mut s.diff_scale, 1e-4..=1.0)
                    .logarithmic(true)
                    .text("difference scale"),
            );
        }
    }
    egui::ComboBox::from_label("Scalar field")
        .selected_text(s.field.clone())
        .show_ui(ui, |ui| {
            for f in fields {
                ui.selectable_value(&mut s.field, f.clone(), f);
            }
        });
    ui.horizontal(|ui| {
        let speed = s.unit_distance * 0.01;
        let label = ui.label("unit distance");
        ui.add(
            egui::DragValue::new(&mut s.unit_distance)
                .speed(speed)
                .range(1e-6..=f32::MAX),
        )
        .labelled_by(label.id);
        if ui.small_button("ParaView's").clicked() {
            s.unit_distance = paraview_unit_distance;
        }
    });
    ui.horizontal(|ui| {
        ui.label("opacity mode");
        ui.radio_value(&mut s.opacity_mode, OpacityMode::Exact, "exact");
        ui.radio_value(&mut s.opacity_mode, OpacityMode::Vtk, "vtk");
    });
    ui.add(
        egui::Slider::new(&mut s.early_termination, 0.5..=1.0).text("early termination (1: off)"),
    );
    ui.add(
        egui::Slider::new(&mut s.image_scale, 0.05..=1.0)
            .logarithmic(true)
            .text("image scale"),
    );
    ui.horizontal(|ui| {
        ui.label("background");
        egui::color_picker::color_edit_button_rgb(ui, &mut s.background);
        ui.checkbox(&mut s.show_stats, "stats");
    });
}

fn camera(app: &mut ViewerApp, ui: &mut Ui) {
    let Some(camera) = app.camera else {
        ui.label("(no view yet)");
        return;
    };
    let mut flags = vtk_flags(&camera);
    let label = ui.label("render flags");
    ui.add(
        egui::TextEdit::multiline(&mut flags)
            .desired_rows(3)
            .desired_width(f32::INFINITY)
            .font(egui::TextStyle::Monospace),
    )
    .labelled_by(label.id);
    ui.horizontal(|ui| {
        if ui.button("Copy flags").clicked() {
            ui.ctx().copy_text(flags.clone());
        }
        if ui
            .button("Reset")
            .on_hover_text("fit the mesh, keep the direction")
            .clicked()
        {
            app.reset_camera = true;
        }
        if ui
            .button("Front")
            .on_hover_text("fit the mesh, looking down -z")
            .clicked()
        {
            app.camera = Some(tetray_core::Camera {
                parallel_scale: camera.parallel_scale,
                view_angle: camera.view_angle,
                ..tetray_core::Camera::default()
            });
            app.reset_camera = true;
        }
        let mut ortho = camera.parallel_scale.is_some();
        if ui.checkbox(&mut ortho, "orthographic").changed() {
            let mut next = camera;
            next.parallel_scale = ortho.then_some(1.0);
            app.camera = Some(next);
            app.reset_camera = true;
        }
    });
    ui.label(
        egui::RichText::new("left drag: orbit · right/middle or shift drag: pan · wheel: dolly")
            .small()
            .weak(),
    );
}

fn screenshot(app: &mut ViewerApp, ui: &mut Ui) {
    ui.horizontal(|ui| {
        let label = ui.label("file");
        ui.add(egui::TextEdit::singleline(&mut app.screenshot_path).desired_width(150.0))
            .labelled_by(label.id);
        if ui.button("Save").clicked() {
            let path = std::path::PathBuf::from(&app.screenshot_path);
            app.screenshot_message = Some(match app.save_screenshot(&path) {
                Ok(paths) => (
                    false,
                    format!(
                        "saved {}",
                        paths
                            .iter()
                            .map(|p| p.display().to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ),
                Err(e) => (true, format!("error: {e:#}")),
            });
        }
    });
    ui.label(
        egui::RichText::new(".png: as displayed · .exr: float RGBA of each view")
            .small()
            .weak(),
    );
    if let Some((error, text)) = &app.screenshot_message {
        let color = if *error {
            ui.visuals().error_fg_color
        } else {
            ui.visuals().weak_text_color()
        };
        ui.colored_label(color, text);
    }
}
