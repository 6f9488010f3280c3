//! Comparing renderers' images against a reference: per-pixel absolute
//! error and its summary ([`metrics`]), a FLIP-like perceptual error
//! ([`flip`]), heat maps with colour bars ([`heatmap`]), a labelled
//! side-by-side sheet ([`sheet`]) and the table of errors and speeds
//! ([`report`]), written as PNG, JSON and Markdown; and [`run`], which
//! renders the combinations to compare through the engine.

pub mod flip;
pub mod font;
pub mod heatmap;
pub mod metrics;
pub mod report;
mod run;
pub mod sheet;

use std::path::PathBuf;

pub use metrics::{ErrorStats, ONE_LEVEL, abs_error};
pub use report::{Method, Report, Row, Speed, compare};
pub use run::{RunOptions, Spec, parse_spec, run};

/// What can go wrong comparing images or writing the results.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    #[error("image sizes differ: {test:?} against the reference's {reference:?}")]
    SizeMismatch {
        test: (u32, u32),
        reference: (u32, u32),
    },
    #[error("nothing to compare: no method besides the reference")]
    NoMethods,
    #[error("writing {path}: {source}")]
    Image {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("writing {path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    Raster(#[from] tetray_core::ImageError),
    #[error("serializing the table: {0}")]
    Json(#[from] serde_json::Error),
    /// Boxed: the engine's error is large, and this one travels often.
    #[error(transparent)]
    Engine(Box<tetray_engine::EngineError>),
    #[error("{label}: rendering")]
    Render {
        label: String,
        #[source]
        source: Box<tetray_engine::EngineError>,
    },
}

impl From<tetray_engine::EngineError> for CompareError {
    fn from(e: tetray_engine::EngineError) -> Self {
        CompareError::Engine(Box::new(e))
    }
}
