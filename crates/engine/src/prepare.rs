//! The engine's entry: from a [`Source`] and options to a [`Setup`] holding
//! the representations the options ask for.

use crate::error::EngineError;
use crate::grid::prepare_grid;
use crate::options::{FrameOptions, Log, Representation};
use crate::setup::{prepare_mesh, Setup};
use crate::source::{load, load_image_data, Source};

/// Loads `source` and makes everything a frame needs, reporting each step
/// through `log`: the representations `options` ask for, the camera (before
/// the integrator's tables, so a bad camera fails fast), the transfer
/// function and the integrator.
pub fn prepare(source: Source, options: &FrameOptions, log: Log<'_>) -> Result<Setup, EngineError> {
    match options.representation {
        Representation::Grid => prepare_grid(source, options, log),
        Representation::Both if source.is_image_data()? => {
            let Source::File {
                path,
                options: load_options,
            } = source
            else {
                unreachable!("only files are image data");
            };
            let (input, image) = load_image_data(&path, &load_options)?;
            prepare_mesh(input, Some(image), options, log)
        }
        Representation::Both | Representation::Tetrahedra => {
            prepare_mesh(load(source)?, None, options, log)
        }
    }
}
