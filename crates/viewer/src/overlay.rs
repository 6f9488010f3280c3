//! What is drawn over the image: the statistics, the progress of the
//! frame, the divider between two methods and the difference colour bar.

use egui::{Align2, Color32, FontId, Pos2, Rect, Sense, Shape, Stroke, Vec2};

use crate::app::ViewerApp;
use crate::present::{Display, heat};

pub fn draw(app: &mut ViewerApp, ui: &mut egui::Ui, rect: Rect) {
    let comparing = app.views.len() > 1;
    if comparing && app.settings.display == Display::Divider {
        divider(app, ui, rect);
    }
    if comparing && app.settings.display == Display::Difference {
        colour_bar(ui, rect, app.settings.diff_scale);
    }
    progress(app, ui, rect);
    if app.settings.show_stats {
        stats(app, ui, rect);
    }
}

/// The divider line, draggable (its own widget, on top of the image).
fn divider(app: &mut ViewerApp, ui: &mut egui::Ui, rect: Rect) {
    let x = rect.left() + app.settings.divider.clamp(0.0, 1.0) * rect.width();
    let handle = Rect::from_min_max(
        Pos2::new(x - 5.0, rect.top()),
        Pos2::new(x + 5.0, rect.bottom()),
    );
    let response = ui.interact(handle, ui.scope_id().with("divider"), Sense::drag());
    response
        .widget_info(|| egui::WidgetInfo::slider(true, f64::from(app.settings.divider), "divider"));
    if response.dragged()
        && let Some(pos) = response.interact_pointer_pos()
    {
        app.settings.divider = ((pos.x - rect.left()) / rect.width()).clamp(0.0, 1.0);
    }
    let painter = ui.painter_at(rect);
    let width = if response.hovered() || response.dragged() {
        3.0
    } else {
        1.5
    };
    painter.line_segment(
        [Pos2::new(x, rect.top()), Pos2::new(x, rect.bottom())],
        Stroke::new(width, Color32::WHITE),
    );
    let names = [
        app.settings.methods[0].name(),
        app.settings.methods[1].name(),
    ];
    let font = FontId::proportional(13.0);
    painter.text(
        Pos2::new(x - 6.0, rect.bottom() - 8.0),
        Align2::RIGHT_BOTTOM,
        names[0],
        font.clone(),
        Color32::WHITE,
    );
    painter.text(
        Pos2::new(x + 6.0, rect.bottom() - 8.0),
        Align2::LEFT_BOTTOM,
        names[1],
        font,
        Color32::WHITE,
    );
}

/// The colour map of the difference view from 0 to `scale`.
fn colour_bar(ui: &egui::Ui, rect: Rect, scale: f32) {
    let bar = Rect::from_min_size(
        Pos2::new(rect.right() - 34.0, rect.top() + 40.0),
        Vec2::new(14.0, (rect.height() - 80.0).max(20.0)),
    );
    let painter = ui.painter_at(rect);
    let mut mesh = egui::Mesh::default();
    const STEPS: u32 = 64;
    for k in 0..=STEPS {
        let t = k as f32 / STEPS as f32;
        let y = bar.bottom() - t * bar.height();
        let color = crate::tf_editor::color32(heat(t));
        mesh.colored_vertex(Pos2::new(bar.left(), y), color);
        mesh.colored_vertex(Pos2::new(bar.right(), y), color);
        if k > 0 {
            let i = 2 * k;
            mesh.add_triangle(i - 2, i - 1, i);
            mesh.add_triangle(i - 1, i + 1, i);
        }
    }
    painter.add(Shape::mesh(mesh));
    painter.rect_stroke(
        bar,
        0.0,
        Stroke::new(1.0, Color32::GRAY),
        egui::StrokeKind::Outside,
    );
    let font = FontId::monospace(11.0);
    for (t, label) in [
        (0.0, "0".to_string()),
        (0.5, format!("{:.3e}", scale / 2.0)),
        (1.0, format!("{scale:.3e}")),
    ] {
        painter.text(
            Pos2::new(bar.left() - 4.0, bar.bottom() - t * bar.height()),
            Align2::RIGHT_CENTER,
            label,
            font.clone(),
            Color32::WHITE,
        );
    }
    painter.text(
        Pos2::new(bar.right(), bar.top() - 6.0),
        Align2::RIGHT_BOTTOM,
        "max |A - B|",
        font,
        Color32::WHITE,
    );
}

/// A thin bar along the bottom while the frame is refined or the CPU
/// renders.
fn progress(app: &ViewerApp, ui: &egui::Ui, rect: Rect) {
    let cpu = app
        .settings
        .renderer
        .on_cpu()
        .then(|| app.cpu.progress())
        .flatten();
    let fraction = cpu.unwrap_or_else(|| app.progressive.progress());
    if fraction >= 1.0 {
        return;
    }
    let bar = Rect::from_min_size(
        Pos2::new(rect.left(), rect.bottom() - 3.0),
        Vec2::new(rect.width() * fraction, 3.0),
    );
    let color = if cpu.is_some() {
        Color32::from_rgb(120, 200, 255)
    } else {
        Color32::from_rgb(255, 200, 60)
    };
    ui.painter_at(rect).rect_filled(bar, 0.0, color);
}

fn stats(app: &ViewerApp, ui: &egui::Ui, rect: Rect) {
    let mut lines = Vec::new();
    let methods: Vec<&str> = app.views.iter().map(|v| v.method.name()).collect();
    lines.push(format!(
        "{} · {}",
        app.settings.renderer.label(),
        methods.join(" | ")
    ));
    match &app.progressive.report {
        Some(r) => {
            let s = r.elapsed.as_secs_f64().max(1e-9);
            lines.push(format!(
                "{}: {}x{}{} in {:.1} ms/frame ({} batch{})",
                r.renderer,
                r.size.0,
                r.size.1,
                if r.views > 1 { " x2" } else { "" },
                s * 1e3,
                r.batches,
                if r.batches == 1 { "" } else { "es" }
            ));
            lines.push(format!(
                "{:.3} M rays/s · {:.2} M segments/s",
                r.rays() as f64 / s / 1e6,
                r.segments() as f64 / s / 1e6
            ));
        }
        None => lines.push("rendering the first frame...".to_string()),
    }
    lines.push(format!(
        "{} tets · {}",
        app.gpu.tet_count(),
        app.adapter_name()
    ));
    let mut state = match app.progressive.phase() {
        crate::engine::Phase::Done => "done".to_string(),
        crate::engine::Phase::Refining { .. } => {
            format!("refining {:.0}%", 100.0 * app.progressive.progress())
        }
        crate::engine::Phase::Start => "starting".to_string(),
    };
    if let Some(p) = app.cpu.progress() {
        state = format!("CPU reference {:.0}%", 100.0 * p);
    }
    match app.ui_ms {
        Some(ms) => lines.push(format!(
            "display: {ms:.1} ms/frame while rendering · {state}"
        )),
        None => lines.push(state),
    }
    let text = lines.join("\n");
    let painter = ui.painter_at(rect);
    let galley = painter.layout_no_wrap(text, FontId::monospace(12.0), Color32::WHITE);
    let at = rect.left_top() + Vec2::new(8.0, 8.0);
    painter.rect_filled(
        Rect::from_min_size(at, galley.size()).expand(4.0),
        3.0,
        Color32::from_black_alpha(160),
    );
    painter.galley(at, galley, Color32::WHITE);
}
