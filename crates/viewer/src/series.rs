//! The viewer's state for time steps and recordings, apart from the
//! application that holds it (`time.rs` and `record.rs` act on it).

use std::time::Instant;

use tetray_engine::{FrameOptions, TimeSteps};

/// The time steps the viewer plays.
pub struct TimeSeries {
    pub(crate) steps: TimeSteps,
    /// What the setup of a step that must be made anew is made with.
    pub(crate) options: FrameOptions,
    /// The stored time of each step.
    pub(crate) times: Vec<f64>,
    /// The step shown.
    pub step: usize,
    pub playing: bool,
    /// Steps per second while playing.
    pub fps: f32,
    pub(crate) last_step: Option<Instant>,
}

impl TimeSeries {
    /// The steps of `steps` (whose `times` are the stored times), with the
    /// setup on step `step` made from `options`.
    pub fn new(steps: TimeSteps, options: FrameOptions, times: Vec<f64>, step: usize) -> Self {
        TimeSeries {
            steps,
            options,
            times,
            step,
            playing: false,
            fps: 4.0,
            last_step: None,
        }
    }

    pub fn len(&self) -> usize {
        self.times.len()
    }

    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }
}

/// What to record.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Recording {
    /// Every time step, one frame each.
    TimeSteps,
    /// `frames` frames turning `degrees` about the view-up in all.
    Orbit { degrees: f32, frames: u32 },
}

/// The panel's recording controls and their state.
pub(crate) struct RecordPanel {
    pub path: String,
    pub fps: u32,
    pub degrees: f32,
    pub frames: u32,
    /// The last recording's message: (is an error, text).
    pub message: Option<(bool, String)>,
}

impl Default for RecordPanel {
    fn default() -> Self {
        RecordPanel {
            path: "tetray-view.gif".to_string(),
            fps: 10,
            degrees: 360.0,
            frames: 36,
            message: None,
        }
    }
}
