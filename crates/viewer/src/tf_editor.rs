//! The transfer-function editor: the opacity curve with draggable control
//! points over the scalar's histogram, the colour ramp with draggable,
//! editable stops, and ParaView presets in and out. Every control point is
//! a widget with an accessible name ("opacity point 1", "colour stop 2").

use std::path::Path;

use anyhow::Context;
use egui::{Color32, Pos2, Rect, Sense, Shape, Stroke, Vec2};
use glam::Vec3;
use tetray_integrate::{ColorPoint, OpacityPoint, TransferFunction};

const PLOT_HEIGHT: f32 = 120.0;
const RAMP_HEIGHT: f32 = 18.0;
const STOP_HEIGHT: f32 = 12.0;
const HANDLE: f32 = 14.0;

/// The function being edited and the editor's own state.
pub struct TfEditor {
    pub color: Vec<ColorPoint>,
    pub opacity: Vec<OpacityPoint>,
    /// The data range: the editor's scalar axis (widened to the points).
    range: (f32, f32),
    histogram: Vec<u32>,
    selected_stop: Option<usize>,
    pub preset_path: String,
    /// Rescale loaded presets to the data range (ParaView's default).
    pub rescale: bool,
    /// The last preset message: (is an error, text).
    pub message: Option<(bool, String)>,
}

impl TfEditor {
    pub fn new(tf: &TransferFunction, range: (f32, f32), histogram: Vec<u32>) -> TfEditor {
        TfEditor {
            color: tf.color_points().to_vec(),
            opacity: tf.opacity_points().to_vec(),
            range,
            histogram,
            selected_stop: None,
            preset_path: "preset.json".to_string(),
            rescale: true,
            message: None,
        }
    }

    /// The data range the editor's axis spans.
    pub fn range(&self) -> (f32, f32) {
        self.range
    }

    /// The histogram under the opacity curve (another time step's field).
    pub fn set_histogram(&mut self, histogram: Vec<u32>) {
        self.histogram = histogram;
    }

    /// The edited function (the editor keeps it valid: points stay
    /// ordered, opacities in [0, 1], colours non-negative).
    pub fn transfer_function(&self) -> anyhow::Result<TransferFunction> {
        Ok(tetray_engine::tf::from_points(
            self.color.clone(),
            self.opacity.clone(),
        )?)
    }

    fn set(&mut self, tf: &TransferFunction) {
        self.color = tf.color_points().to_vec();
        self.opacity = tf.opacity_points().to_vec();
        self.selected_stop = None;
    }

    /// Reads a ParaView preset; on failure the function is unchanged and
    /// the error is shown in the editor.
    pub fn load_preset(&mut self, path: &Path) -> bool {
        let result = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))
            .and_then(|text| {
                let rescale = self.rescale.then_some(self.range);
                tetray_engine::tf::paraview_preset(&text, None, rescale)
                    .with_context(|| format!("{}", path.display()))
            });
        match result {
            Ok((tf, warnings)) => {
                self.set(&tf);
                let note = if warnings.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", warnings.join("; "))
                };
                self.message = Some((false, format!("loaded {}{note}", path.display())));
                true
            }
            Err(e) => {
                self.message = Some((true, format!("error: {e:#}")));
                false
            }
        }
    }

    /// Writes the function as a ParaView preset.
    pub fn save_preset(&mut self, path: &Path) {
        let result = self.transfer_function().and_then(|tf| {
            let name = path
                .file_stem()
                .map_or("tetray".into(), |s| s.to_string_lossy());
            std::fs::write(path, tf.to_paraview_json(&name))
                .with_context(|| format!("cannot write {}", path.display()))
        });
        self.message = Some(match result {
            Ok(()) => (false, format!("saved {}", path.display())),
            Err(e) => (true, format!("error: {e:#}")),
        });
    }

    /// Resets to the default function over the data range.
    pub fn reset(&mut self) {
        self.set(&tetray_engine::tf::default_ramp(self.range));
    }

    /// The scalar axis: the data range widened to every control point.
    fn axis(&self) -> (f32, f32) {
        let points = self
            .color
            .iter()
            .map(|p| p.scalar)
            .chain(self.opacity.iter().map(|p| p.scalar));
        let (lo, hi) = points.fold(self.range, |(lo, hi), s| (lo.min(s), hi.max(s)));
        if hi > lo { (lo, hi) } else { (lo, lo + 1.0) }
    }

    /// The editor; returns whether the function changed.
    pub fn ui(&mut self, ui: &mut egui::Ui) -> bool {
        let mut changed = self.opacity_plot(ui);
        changed |= self.color_ramp(ui);
        changed |= self.selected_stop_ui(ui);
        ui.label(
            egui::RichText::new(
                "drag points; double-click to add; right-click to remove; click a stop to edit",
            )
            .small()
            .weak(),
        );
        ui.horizontal(|ui| {
            if ui.button("Reset").clicked() {
                self.reset();
                changed = true;
            }
            ui.checkbox(&mut self.rescale, "rescale presets to data");
        });
        ui.horizontal(|ui| {
            let label = ui.label("preset file");
            ui.add(
                egui::TextEdit::singleline(&mut self.preset_path)
                    .desired_width(120.0)
                    .hint_text("preset.json"),
            )
            .labelled_by(label.id);
        });
        ui.horizontal(|ui| {
            if ui.button("Load preset").clicked() {
                let path = self.preset_path.clone();
                changed |= self.load_preset(Path::new(&path));
            }
            if ui.button("Save preset").clicked() {
                let path = self.preset_path.clone();
                self.save_preset(Path::new(&path));
            }
        });
        if let Some((error, text)) = &self.message {
            let color = if *error {
                ui.visuals().error_fg_color
            } else {
                ui.visuals().weak_text_color()
            };
            ui.colored_label(color, text);
        }
        changed
    }

    fn opacity_plot(&mut self, ui: &mut egui::Ui) -> bool {
        let width = ui.available_width().max(100.0);
        let (outer, background) =
            ui.allocate_exact_size(Vec2::new(width, PLOT_HEIGHT), Sense::click());
        // The data area is inset by a handle's size so that the end points
        // are whole and clear of the panel's edge (its scroll bar and resize
        // handle would take a drag there).
        let rect = outer.shrink2(Vec2::new(HANDLE, HANDLE / 2.0));
        let axis = self.axis();
        let to_x = |s: f32| rect.left() + (s - axis.0) / (axis.1 - axis.0) * rect.width();
        let to_y = |a: f32| rect.bottom() - a * rect.height();
        let painter = ui.painter_at(rect.expand(HANDLE / 2.0));
        painter.rect_filled(rect, 2.0, ui.visuals().extreme_bg_color);
        // The histogram, log scale, over the data range.
        let max = self.histogram.iter().copied().max().unwrap_or(0).max(1) as f32;
        let bins = self.histogram.len().max(1) as f32;
        let (lo, hi) = self.range;
        for (i, &count) in self.histogram.iter().enumerate() {
            let x0 = to_x(lo + (hi - lo) * i as f32 / bins);
            let x1 = to_x(lo + (hi - lo) * (i + 1) as f32 / bins);
            let h = (1.0 + count as f32).ln() / (1.0 + max).ln() * rect.height();
            painter.rect_filled(
                Rect::from_min_max(
                    Pos2::new(x0, rect.bottom() - h),
                    Pos2::new(x1, rect.bottom()),
                ),
                0.0,
                Color32::from_gray(70),
            );
        }
        // The curve, flat beyond the end points.
        let mut line = vec![Pos2::new(rect.left(), to_y(self.opacity[0].alpha))];
        line.extend(
            self.opacity
                .iter()
                .map(|p| Pos2::new(to_x(p.scalar), to_y(p.alpha))),
        );
        line.push(Pos2::new(
            rect.right(),
            to_y(self.opacity[self.opacity.len() - 1].alpha),
        ));
        painter.add(Shape::line(line, Stroke::new(1.5, Color32::WHITE)));

        let mut changed = false;
        let mut remove = None;
        for i in 0..self.opacity.len() {
            let p = self.opacity[i];
            let centre = Pos2::new(to_x(p.scalar), to_y(p.alpha));
            let id = ui.scope_id().with(("opacity point", i));
            let response = ui.interact(
                Rect::from_center_size(centre, Vec2::splat(HANDLE)),
                id,
                Sense::click_and_drag(),
            );
            response.widget_info(|| {
                egui::WidgetInfo::labeled(egui::Role::Slider, true, format!("opacity point {i}"))
            });
            if response.dragged()
                && let Some(pos) = response.interact_pointer_pos()
            {
                let scalar = axis.0 + (pos.x - rect.left()) / rect.width() * (axis.1 - axis.0);
                let alpha = (rect.bottom() - pos.y) / rect.height();
                changed |= move_opacity_point(&mut self.opacity, i, scalar, alpha);
            }
            if response.secondary_clicked() {
                remove = Some(i);
            }
            let active = response.hovered() || response.dragged();
            painter.circle(
                centre,
                if active { 6.0 } else { 4.5 },
                Color32::from_rgb(255, 200, 60),
                Stroke::new(1.0, Color32::BLACK),
            );
        }
        if let Some(i) = remove {
            changed |= remove_point(&mut self.opacity, i);
        }
        if background.double_clicked()
            && let Some(pos) = background.interact_pointer_pos()
        {
            let scalar = axis.0 + (pos.x - rect.left()) / rect.width() * (axis.1 - axis.0);
            let alpha = ((rect.bottom() - pos.y) / rect.height()).clamp(0.0, 1.0);
            insert_opacity_point(&mut self.opacity, scalar, alpha);
            changed = true;
        }
        changed
    }

    fn color_ramp(&mut self, ui: &mut egui::Ui) -> bool {
        let width = ui.available_width().max(100.0);
        let (outer, ramp) =
            ui.allocate_exact_size(Vec2::new(width, RAMP_HEIGHT + STOP_HEIGHT), Sense::click());
        // Inset as the opacity plot, so that both share the scalar axis.
        let rect = outer.shrink2(Vec2::new(HANDLE, 0.0));
        let strip = Rect::from_min_size(rect.min, Vec2::new(rect.width(), RAMP_HEIGHT));
        let axis = self.axis();
        let to_x = |s: f32| rect.left() + (s - axis.0) / (axis.1 - axis.0) * rect.width();
        let painter = ui.painter_at(rect.expand(HANDLE / 2.0));
        let tf = self.transfer_function().ok();
        let mut mesh = egui::Mesh::default();
        const SEGMENTS: usize = 96;
        for k in 0..=SEGMENTS {
            let t = k as f32 / SEGMENTS as f32;
            let s = axis.0 + t * (axis.1 - axis.0);
            let color = tf
                .as_ref()
                .map_or(Color32::BLACK, |tf| color32(tf.color_at(s)));
            let x = strip.left() + t * strip.width();
            mesh.colored_vertex(Pos2::new(x, strip.top()), color);
            mesh.colored_vertex(Pos2::new(x, strip.bottom()), color);
            if k > 0 {
                let i = 2 * k as u32;
                mesh.add_triangle(i - 2, i - 1, i);
                mesh.add_triangle(i - 1, i + 1, i);
            }
        }
        painter.add(Shape::mesh(mesh));

        let mut changed = false;
        let mut remove = None;
        for i in 0..self.color.len() {
            let p = self.color[i];
            let x = to_x(p.scalar);
            let tip = Pos2::new(x, strip.bottom());
            let id = ui.scope_id().with(("colour stop", i));
            let response = ui.interact(
                Rect::from_center_size(
                    Pos2::new(x, strip.bottom() + STOP_HEIGHT / 2.0),
                    Vec2::new(HANDLE, STOP_HEIGHT),
                ),
                id,
                Sense::click_and_drag(),
            );
            response.widget_info(|| {
                egui::WidgetInfo::labeled(egui::Role::Slider, true, format!("colour stop {i}"))
            });
            if response.dragged()
                && let Some(pos) = response.interact_pointer_pos()
            {
                let scalar = axis.0 + (pos.x - rect.left()) / rect.width() * (axis.1 - axis.0);
                changed |= move_color_stop(&mut self.color, i, scalar);
            }
            if response.clicked() {
                self.selected_stop = Some(i);
            }
            if response.secondary_clicked() {
                remove = Some(i);
            }
            let selected = self.selected_stop == Some(i);
            let outline = if selected || response.hovered() {
                Color32::WHITE
            } else {
                Color32::GRAY
            };
            painter.add(Shape::convex_polygon(
                vec![
                    tip,
                    Pos2::new(x + 5.0, tip.y + STOP_HEIGHT - 1.0),
                    Pos2::new(x - 5.0, tip.y + STOP_HEIGHT - 1.0),
                ],
                color32(p.rgb),
                Stroke::new(if selected { 2.0 } else { 1.0 }, outline),
            ));
        }
        if let Some(i) = remove
            && remove_point(&mut self.color, i)
        {
            self.selected_stop = None;
            changed = true;
        }
        if ramp.double_clicked()
            && let (Some(pos), Some(tf)) = (ramp.interact_pointer_pos(), tf)
        {
            let scalar = axis.0 + (pos.x - rect.left()) / rect.width() * (axis.1 - axis.0);
            self.selected_stop = Some(insert_color_stop(
                &mut self.color,
                scalar,
                tf.color_at(scalar),
            ));
            changed = true;
        }
        changed
    }

    fn selected_stop_ui(&mut self, ui: &mut egui::Ui) -> bool {
        let Some(i) = self.selected_stop.filter(|&i| i < self.color.len()) else {
            return false;
        };
        let mut changed = false;
        ui.horizontal(|ui| {
            ui.label(format!("stop {i} at {:.4}", self.color[i].scalar));
            let mut rgb = self.color[i].rgb.to_array();
            if egui::color_picker::color_edit_button_rgb(ui, &mut rgb).changed() {
                self.color[i].rgb = Vec3::from(rgb).max(Vec3::ZERO);
                changed = true;
            }
        });
        changed
    }
}

/// The colour a luminance is shown with: its value as the byte, no sRGB
/// transform, as the rendered image and `tetray render`'s PNG show it.
pub fn color32(rgb: Vec3) -> Color32 {
    let [r, g, b] = rgb
        .to_array()
        .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
    Color32::from_rgb(r, g, b)
}

/// Something with a scalar position on the axis.
pub trait Knot {
    fn scalar(&self) -> f32;
    fn set_scalar(&mut self, s: f32);
}

impl Knot for OpacityPoint {
    fn scalar(&self) -> f32 {
        self.scalar
    }
    fn set_scalar(&mut self, s: f32) {
        self.scalar = s;
    }
}

impl Knot for ColorPoint {
    fn scalar(&self) -> f32 {
        self.scalar
    }
    fn set_scalar(&mut self, s: f32) {
        self.scalar = s;
    }
}

/// Moves point `i` to `scalar`, kept between its neighbours so the order
/// holds. Returns whether it moved.
fn move_knot<K: Knot>(points: &mut [K], i: usize, scalar: f32) -> bool {
    let lo = if i > 0 {
        points[i - 1].scalar()
    } else {
        f32::MIN
    };
    let hi = points.get(i + 1).map_or(f32::MAX, |p| p.scalar());
    let s = if scalar.is_finite() {
        scalar.clamp(lo, hi)
    } else {
        points[i].scalar()
    };
    let moved = s != points[i].scalar();
    points[i].set_scalar(s);
    moved
}

/// Moves opacity point `i` to (`scalar`, `alpha`), the scalar kept between
/// the neighbours and the opacity in [0, 1].
pub fn move_opacity_point(points: &mut [OpacityPoint], i: usize, scalar: f32, alpha: f32) -> bool {
    let moved = move_knot(points, i, scalar);
    let a = if alpha.is_finite() {
        alpha.clamp(0.0, 1.0)
    } else {
        points[i].alpha
    };
    let raised = a != points[i].alpha;
    points[i].alpha = a;
    moved || raised
}

/// Moves colour stop `i` to `scalar`, kept between the neighbours.
pub fn move_color_stop(points: &mut [ColorPoint], i: usize, scalar: f32) -> bool {
    move_knot(points, i, scalar)
}

/// Adds an opacity point where it belongs in the order.
pub fn insert_opacity_point(points: &mut Vec<OpacityPoint>, scalar: f32, alpha: f32) -> usize {
    let at = points.partition_point(|p| p.scalar <= scalar);
    points.insert(at, OpacityPoint { scalar, alpha });
    at
}

/// Adds a colour stop where it belongs in the order.
pub fn insert_color_stop(points: &mut Vec<ColorPoint>, scalar: f32, rgb: Vec3) -> usize {
    let at = points.partition_point(|p| p.scalar <= scalar);
    points.insert(at, ColorPoint { scalar, rgb });
    at
}

/// Removes point `i` unless it is the last one (a function needs one).
pub fn remove_point<T>(points: &mut Vec<T>, i: usize) -> bool {
    if points.len() > 1 && i < points.len() {
        points.remove(i);
        true
    } else {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Vec<OpacityPoint> {
        [(0.0, 0.0), (0.5, 0.2), (1.0, 1.0)]
            .map(|(scalar, alpha)| OpacityPoint { scalar, alpha })
            .to_vec()
    }

    #[test]
    fn dragged_points_stay_ordered_and_in_range() {
        let mut points = ramp();
        assert!(move_opacity_point(&mut points, 1, 2.0, 1.5));
        assert_eq!((points[1].scalar, points[1].alpha), (1.0, 1.0));
        assert!(move_opacity_point(&mut points, 1, -3.0, -1.0));
        assert_eq!((points[1].scalar, points[1].alpha), (0.0, 0.0));
        assert!(!move_opacity_point(&mut points, 1, f32::NAN, f32::NAN));
        // Two points may share a scalar (a step), as TransferFunction allows.
        assert!(
            TransferFunction::new(
                vec![ColorPoint {
                    scalar: 0.0,
                    rgb: Vec3::ONE
                }],
                points.clone()
            )
            .is_ok()
        );
    }

    #[test]
    fn points_are_inserted_in_order_and_the_last_is_kept() {
        let mut points = ramp();
        assert_eq!(insert_opacity_point(&mut points, 0.75, 0.5), 2);
        assert!(points.windows(2).all(|w| w[0].scalar <= w[1].scalar));
        let mut one = vec![points[0]];
        assert!(!remove_point(&mut one, 0));
        assert!(remove_point(&mut points, 2));
        assert_eq!(points.len(), 3);
        let mut stops = vec![
            ColorPoint {
                scalar: 0.0,
                rgb: Vec3::ZERO,
            },
            ColorPoint {
                scalar: 1.0,
                rgb: Vec3::ONE,
            },
        ];
        assert_eq!(insert_color_stop(&mut stops, 0.5, Vec3::X), 1);
        assert!(move_color_stop(&mut stops, 1, 0.25));
        assert!(move_color_stop(&mut stops, 1, 2.0));
        assert_eq!(stops[1].scalar, 1.0, "clamped to the next stop");
        assert!(move_color_stop(&mut stops, 0, -1.0));
        assert_eq!(
            stops[0].scalar, -1.0,
            "the first stop may leave the data range"
        );
    }
}
