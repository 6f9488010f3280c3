//! The camera of a frame: VTK's ResetCamera fit of the volume's bounds, the
//! values given, then the turns (the oblique default when none is given).

use glam::{DVec3, Vec3};
use tetray_core::{Camera, relative_to_origin};

use crate::error::{Context, EngineError, bail};
use crate::options::{CameraOptions, Log};

/// The camera: VTK's ResetCamera fit of `bounds` for a `width x height`
/// image (looking down -z, or along the given position and focal point),
/// the given values, then azimuth, elevation (the oblique default when no
/// camera value is given) and OrthogonalizeViewUp. A given position and
/// focal point are in the file's coordinates: the mesh's `origin` is
/// subtracted (in f64).
pub fn build_camera(
    args: &CameraOptions,
    (lo, hi): (Vec3, Vec3),
    (width, height): (u32, u32),
    origin: DVec3,
) -> Result<Camera, EngineError> {
    if width == 0 || height == 0 {
        bail!("the image size must be at least 1x1, got {width}x{height}");
    }
    let position = args.camera_position.map(|p| relative_to_origin(p, origin));
    let focal_point = args.focal_point.map(|p| relative_to_origin(p, origin));
    let mut camera = Camera {
        view_angle: args.view_angle,
        parallel_scale: args.parallel_scale,
        ..Camera::default()
    };
    if let Some(up) = args.view_up {
        camera.view_up = up;
    }
    match (position, focal_point) {
        (Some(position), Some(focal_point)) => {
            camera.position = position;
            camera.focal_point = focal_point;
        }
        (position, focal_point) => {
            camera
                .reset(lo, hi, width as f32 / height as f32)
                .context("bad camera: cannot fit the mesh bounds")?;
            if let Some(s) = args.parallel_scale {
                camera.parallel_scale = Some(s);
            }
            if let Some(p) = position {
                camera.position = p;
            }
            if let Some(f) = focal_point {
                camera.focal_point = f;
            }
        }
    }
    camera.basis().context("bad camera")?;
    let (azimuth, elevation) = args.rotation();
    camera.azimuth(azimuth).context("bad camera")?;
    camera.elevation(elevation).context("bad camera")?;
    camera.orthogonalize_view_up().context("bad camera")?;
    Ok(camera)
}

/// Warns when rays start inside the mesh bounds (the renderer integrates
/// from the eye, which is rarely what was meant).
pub fn warn_if_inside(camera: &Camera, (lo, hi): (Vec3, Vec3), log: Log<'_>) {
    if camera.is_inside_bounds(lo, hi) {
        let p = camera.position;
        (log.warn)(format!(
            "the camera at {},{},{} is inside the mesh bounds; rendering from the eye",
            p.x, p.y, p.z
        ));
    }
}
