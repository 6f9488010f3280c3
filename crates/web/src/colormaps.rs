//! The colour maps a page offers: the exported transfer function's own
//! colours, and a fixed set of others, each with the exported opacity
//! points (the page switches among their tables; it does not rebuild them).

use tetray_integrate::TransferFunction;

use crate::WebError;

/// The other colour maps, as a ParaView preset file (viridis sampled at
/// nine points, from matplotlib's table).
const PRESETS: &str = include_str!("../colormaps.json");
const PRESET_NAMES: [&str; 3] = ["Viridis", "Grayscale", "Rainbow"];

/// The name of the exported transfer function's own colours.
pub const EXPORTED: &str = "exported";

/// `(name, transfer function)` for every colour map of a page: the
/// exported function first, then the cool-to-warm ramp and the presets
/// rescaled to `range`, each with the exported opacity.
pub fn colormaps(
    exported: &TransferFunction,
    range: (f32, f32),
) -> Result<Vec<(String, TransferFunction)>, WebError> {
    let (lo, hi) = range;
    let mut maps = vec![(EXPORTED.to_string(), exported.clone())];
    if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
        // A constant field: colour does not vary; one map is all there is.
        return Ok(maps);
    }
    let opacity = exported.opacity_points().to_vec();
    let with_opacity = |colors: &TransferFunction| {
        TransferFunction::new(colors.color_points().to_vec(), opacity.clone())
            .map_err(|e| WebError::Colormap(e.to_string()))
    };
    maps.push((
        "Cool to Warm".to_string(),
        with_opacity(&TransferFunction::default_for_range(lo, hi))?,
    ));
    for name in PRESET_NAMES {
        let preset = TransferFunction::from_paraview_json(PRESETS, Some(name), Some((lo, hi)))
            .map_err(|e| WebError::Colormap(format!("{name}: {e}")))?;
        maps.push((name.to_string(), with_opacity(&preset)?));
    }
    Ok(maps)
}
