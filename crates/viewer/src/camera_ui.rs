//! Mouse control of the VTK camera (as vtkInteractorStyleTrackballCamera:
//! left drag orbits, right or middle or shift-drag pans, the wheel dollies)
//! and its readout as `tetray render` flags.

use egui::Vec2;
use glam::Vec3;
use tetray_core::{Camera, CameraError};

/// Degrees of orbit for a drag across the whole view (VTK: 20 degrees per
/// window times its motion factor of 10).
const ORBIT_DEGREES_PER_VIEW: f32 = 200.0;

/// Orbits about the focal point for a drag of `delta` points over a view
/// `size` points large: right moves the camera left around the object, up
/// moves it down (the object follows the mouse).
pub fn orbit(camera: &mut Camera, delta: Vec2, size: Vec2) -> Result<(), CameraError> {
    let mut next = *camera;
    next.azimuth(-delta.x / size.x.max(1.0) * ORBIT_DEGREES_PER_VIEW)?;
    next.elevation(delta.y / size.y.max(1.0) * ORBIT_DEGREES_PER_VIEW)?;
    next.orthogonalize_view_up()?;
    *camera = next;
    Ok(())
}

/// Moves the camera and focal point so that the point under the mouse
/// follows it (`delta` points over a view `size` points tall).
pub fn pan(camera: &mut Camera, delta: Vec2, size: Vec2) -> Result<(), CameraError> {
    let basis = camera.basis()?;
    let distance = (camera.focal_point - camera.position).length();
    // World height of the view at the focal plane.
    let view_height = match camera.parallel_scale {
        Some(s) => 2.0 * s,
        None => 2.0 * distance * (camera.view_angle.to_radians() * 0.5).tan(),
    };
    let per_point = view_height / size.y.max(1.0);
    let shift = (-basis.right * delta.x + basis.up * delta.y) * per_point;
    camera.position += shift;
    camera.focal_point += shift;
    Ok(())
}

/// Moves towards the focal point (`steps` > 0) or away, 10% per step;
/// orthographic cameras scale instead (the projection has no distance).
pub fn dolly(camera: &mut Camera, steps: f32) -> Result<(), CameraError> {
    let factor = 1.1f32.powf(steps);
    let mut next = *camera;
    if next.parallel_scale.is_some() {
        next.zoom(factor)?;
    } else {
        next.dolly(factor)?;
    }
    *camera = next;
    Ok(())
}

/// The camera as `tetray render` flags (shortest exact decimals, so they
/// reproduce this view).
pub fn vtk_flags(camera: &Camera) -> String {
    let v = |p: Vec3| format!("{},{},{}", p.x, p.y, p.z);
    let mut flags = format!(
        "--camera-position {} --focal-point {} --view-up {} --view-angle {}",
        v(camera.position),
        v(camera.focal_point),
        v(camera.view_up),
        camera.view_angle
    );
    if let Some(s) = camera.parallel_scale {
        flags.push_str(&format!(" --parallel-scale {s}"));
    }
    flags
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::reset_to_bounds(Vec3::ZERO, Vec3::ONE).expect("camera")
    }

    #[test]
    fn orbit_keeps_the_distance_and_the_focal_point() {
        let mut c = camera();
        let before = (c.position - c.focal_point).length();
        orbit(&mut c, Vec2::new(50.0, 20.0), Vec2::new(400.0, 300.0)).expect("orbit");
        assert!(((c.position - c.focal_point).length() - before).abs() < 1e-4 * before);
        assert_eq!(c.focal_point, camera().focal_point);
        assert!(
            c.position.x < camera().position.x,
            "dragging right moves the eye left"
        );
        assert!(c.view_up.dot(c.focal_point - c.position).abs() < 1e-4);
    }

    #[test]
    fn pan_moves_eye_and_focus_together_and_dolly_approaches() {
        let mut c = camera();
        let offset = c.position - c.focal_point;
        pan(&mut c, Vec2::new(10.0, 0.0), Vec2::new(400.0, 300.0)).expect("pan");
        assert!((c.position - c.focal_point - offset).length() < 1e-5);
        assert!(
            c.focal_point.x < 0.5,
            "the scene follows the mouse to the right"
        );
        let d = (c.position - c.focal_point).length();
        dolly(&mut c, 1.0).expect("dolly");
        assert!(((c.position - c.focal_point).length() - d / 1.1).abs() < 1e-4);
        let mut ortho = Camera {
            parallel_scale: Some(2.0),
            ..camera()
        };
        dolly(&mut ortho, -1.0).expect("zoom out");
        assert!((ortho.parallel_scale.unwrap() - 2.2).abs() < 1e-5);
    }

    #[test]
    fn flags_name_every_camera_value() {
        let c = Camera {
            parallel_scale: Some(1.5),
            ..camera()
        };
        let flags = vtk_flags(&c);
        assert!(flags.starts_with("--camera-position 0.5,0.5,"));
        assert!(flags.contains("--focal-point 0.5,0.5,0.5 --view-up 0,1,0 --view-angle 30"));
        assert!(flags.ends_with("--parallel-scale 1.5"));
    }
}
