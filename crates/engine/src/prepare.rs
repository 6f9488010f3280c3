//! The engine's entry: from a [`Source`] and options to a [`Setup`] holding
//! the representations the options ask for.

use crate::error::EngineError;
use crate::grid::prepare_grid;
use crate::options::{FrameOptions, Log, Representation, TfSource};
use crate::setup::{Setup, prepare_mesh};
use crate::source::{Source, load, load_image_data};

/// Loads `source` and makes everything a frame needs, reporting each step
/// through `log`: the representations `options` ask for, the camera (before
/// the integrator's tables, so a bad camera fails fast), the transfer
/// function and the integrator.
pub fn prepare(source: Source, options: &FrameOptions, log: Log<'_>) -> Result<Setup, EngineError> {
    if matches!(source, Source::Embedded) && options.representation != Representation::Grid {
        let options = embedded_defaults(options);
        if let TfSource::ParaView { label, .. } = &options.integrator.tf
            && label == EMBEDDED_PRESET_LABEL
        {
            (log.info)(format!("transfer function: {EMBEDDED_PRESET_LABEL}"));
        }
        return prepare_mesh(load(source)?, None, &options, log);
    }
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

/// The embedded Blunt Fin's default transfer function for its density: in
/// the field's own units, clear at the free stream, opaque on the shocks.
const EMBEDDED_PRESET: &str = include_str!("../../../data/presets/blunt-fin-density.json");
const EMBEDDED_PRESET_LABEL: &str =
    "the Blunt Fin's density preset (data/presets/blunt-fin-density.json)";

/// Azimuth and elevation (degrees) of the embedded Blunt Fin's default
/// view: the bow shock ahead of the fin and its wake along the plate.
pub const EMBEDDED_VIEW: (f32, f32) = (-30.0, 45.0);

/// `options` with the embedded Blunt Fin's own defaults where nothing else
/// is asked: its density preset, and its view.
fn embedded_defaults(options: &FrameOptions) -> FrameOptions {
    let mut options = options.clone();
    let density = options
        .integrator
        .scalar
        .as_deref()
        .is_none_or(|s| s == "density");
    if density && matches!(options.integrator.tf, TfSource::Default) {
        options.integrator.tf = TfSource::ParaView {
            text: EMBEDDED_PRESET.to_string(),
            name: None,
            rescale: false,
            label: EMBEDDED_PRESET_LABEL.to_string(),
        };
    }
    if !options.camera.is_given() {
        options.camera.azimuth = Some(EMBEDDED_VIEW.0);
        options.camera.elevation = Some(EMBEDDED_VIEW.1);
    }
    options
}
