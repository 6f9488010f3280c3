//! Conversions between Python values and the engine's: images to NumPy
//! arrays, camera dicts to `CameraOptions`, sizes checked.

use glam::DVec3;
use numpy::{IntoPyArray, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tetray_engine::CameraOptions;

use crate::value_error;

/// An image as a (height, width, 4) float32 array.
pub(crate) fn image_array<'py>(
    py: Python<'py>,
    image: &tetray_core::Image,
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let flat: Vec<f32> = image.rgba.iter().flatten().copied().collect();
    flat.into_pyarray(py)
        .reshape([image.height as usize, image.width as usize, 4])
}

/// Colour points (s, r, g, b) and opacity points (s, alpha) over [0, 1].
pub(crate) type TfPoints = (Vec<(f32, f32, f32, f32)>, Vec<(f32, f32)>);

pub(crate) fn check_size((w, h): (u32, u32)) -> PyResult<()> {
    if (1..=16384).contains(&w) && (1..=16384).contains(&h) {
        Ok(())
    } else {
        Err(value_error(format!(
            "size ({w}, {h}): each side must be a whole number in 1..=16384"
        )))
    }
}

/// CameraOptions from a dict with the keys position, focal_point, view_up
/// (3 numbers each), view_angle, parallel_scale, azimuth, elevation (None
/// or absent: not given).
pub(crate) fn camera_options(dict: Option<&Bound<'_, PyDict>>) -> PyResult<CameraOptions> {
    let mut options = CameraOptions::default();
    let Some(dict) = dict else {
        return Ok(options);
    };
    for key in dict.keys() {
        let key: String = key.extract()?;
        if ![
            "position",
            "focal_point",
            "view_up",
            "view_angle",
            "parallel_scale",
            "azimuth",
            "elevation",
        ]
        .contains(&key.as_str())
        {
            return Err(value_error(format!("camera: unknown key {key:?}")));
        }
    }
    let get = |key: &str| -> PyResult<Option<Bound<'_, PyAny>>> {
        Ok(dict.get_item(key)?.filter(|v| !v.is_none()))
    };
    let finite = |key: &str, v: f64| -> PyResult<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(value_error(format!("camera {key}: {v} is not finite")))
        }
    };
    let vec3 = |key: &str| -> PyResult<Option<DVec3>> {
        match get(key)? {
            None => Ok(None),
            Some(v) => {
                let [x, y, z]: [f64; 3] = v.extract().map_err(|_| {
                    value_error(format!("camera {key}: expected three numbers (x, y, z)"))
                })?;
                Ok(Some(DVec3::new(
                    finite(key, x)?,
                    finite(key, y)?,
                    finite(key, z)?,
                )))
            }
        }
    };
    let number = |key: &str| -> PyResult<Option<f32>> {
        match get(key)? {
            None => Ok(None),
            Some(v) => {
                let v: f64 = v
                    .extract()
                    .map_err(|_| value_error(format!("camera {key}: expected a number")))?;
                Ok(Some(finite(key, v)? as f32))
            }
        }
    };
    options.camera_position = vec3("position")?;
    options.focal_point = vec3("focal_point")?;
    options.view_up = vec3("view_up")?.map(|v| v.as_vec3());
    if let Some(angle) = number("view_angle")? {
        if !(angle > 0.0 && angle < 180.0) {
            return Err(value_error(format!(
                "camera view_angle: {angle} degrees is outside (0, 180)"
            )));
        }
        options.view_angle = angle;
    }
    options.parallel_scale = number("parallel_scale")?;
    if let Some(s) = options.parallel_scale.filter(|s| *s <= 0.0) {
        return Err(value_error(format!(
            "camera parallel_scale: {s} must be greater than 0"
        )));
    }
    options.azimuth = number("azimuth")?;
    options.elevation = number("elevation")?;
    Ok(options)
}
