//! A file's time steps in the viewer: a slider over the steps and
//! play/pause. A step moves the engine's setup through
//! [`tetray_engine::TimeSteps`]: a step of the same points and cells
//! brings only its fields (written over the uploaded points' scalars), a
//! moving mesh is uploaded anew. The transfer function, the camera and the
//! colour range (the field's over all the steps, as `tetray animate`'s)
//! stay, so a colour means the same value in every step.

use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::Context;
use egui::Ui;
use tetray_engine::Log;

use crate::app::{HISTOGRAM_BINS, ViewerApp, histogram};
use crate::series::TimeSeries;

impl ViewerApp {
    /// Plays `series` in this viewer (its setup must be on `series.step`).
    pub fn set_time_series(&mut self, series: TimeSeries) {
        self.time = Some(series);
    }

    /// Starts or stops playing the steps (as the panel's Play button).
    pub fn set_playing(&mut self, playing: bool) {
        if let Some(series) = self.time.as_mut() {
            series.playing = playing;
            series.last_step = None;
        }
    }

    /// The step shown, when the data has time steps.
    pub fn time_step(&self) -> Option<usize> {
        self.time.as_ref().map(|t| t.step)
    }

    /// Shows time step `step`: its fields over the held mesh, or the step
    /// made anew when its mesh differs (then `false`); the transfer
    /// function and camera stay.
    pub fn go_to_step(&mut self, step: usize) -> anyhow::Result<bool> {
        let series = self.time.as_mut().context("the data has no time steps")?;
        if step >= series.len() {
            anyhow::bail!(
                "time step {step} is out of range: the data stores {} steps",
                series.len()
            );
        }
        let cost = series
            .steps
            .advance(&mut self.setup, step, &series.options, Log::quiet())?;
        series.step = step;
        let scene = Arc::clone(self.scene());
        if cost.kept {
            self.gpu.write_points(&scene)?;
        } else {
            self.gpu.set_scene(&scene)?;
        }
        // Their uploads hold the old step's values: made again when picked.
        self.drop_derived();
        self.tf_editor.set_histogram(histogram(
            &scene.scalar,
            self.tf_editor.range(),
            HISTOGRAM_BINS,
        ));
        self.generation += 1;
        Ok(cost.kept)
    }

    /// While playing, moves to the next step once the frame is finished
    /// and its time is up; returns how long until the next step is due.
    pub(crate) fn play(&mut self, idle: bool) -> Option<Duration> {
        let series = self.time.as_mut()?;
        if !series.playing || series.len() < 2 {
            return None;
        }
        let period = Duration::from_secs_f32(1.0 / series.fps.clamp(0.1, 60.0));
        let due = series
            .last_step
            .map_or(Duration::ZERO, |at| period.saturating_sub(at.elapsed()));
        if !idle || !due.is_zero() {
            return Some(due.max(Duration::from_millis(5)));
        }
        let next = (series.step + 1) % series.len();
        series.last_step = Some(Instant::now());
        if let Err(e) = self.go_to_step(next) {
            self.error = Some(format!("{e:#}"));
            if let Some(series) = self.time.as_mut() {
                series.playing = false;
            }
        }
        Some(period)
    }
}

/// The panel's time controls: the step slider, play/pause and the rate.
pub(crate) fn controls(app: &mut ViewerApp, ui: &mut Ui) {
    let Some(series) = app.time.as_mut() else {
        return;
    };
    let last = series.len().saturating_sub(1);
    let mut step = series.step;
    let time = series.times.get(step).copied().unwrap_or(f64::NAN);
    ui.add(egui::Slider::new(&mut step, 0..=last).text(format!("step (time {time})")));
    ui.horizontal(|ui| {
        let label = if series.playing { "Pause" } else { "Play" };
        if ui.button(label).clicked() {
            series.playing = !series.playing;
            series.last_step = None;
        }
        ui.add(
            egui::DragValue::new(&mut series.fps)
                .range(0.1..=60.0)
                .speed(0.1)
                .suffix(" steps/s"),
        );
    });
    if step != series.step
        && let Err(e) = app.go_to_step(step)
    {
        app.error = Some(format!("{e:#}"));
    }
}
