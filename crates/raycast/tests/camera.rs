//! Camera conventions against values computed by hand from VTK's
//! definitions (vtkRenderer::ResetCamera, vtkCamera::Azimuth / Elevation).
//! Tolerance 1e-5: f32 positions of magnitude < 20, rotations done in f64.

use glam::Vec3;
use tetray_core::{Camera, CameraError};

const TOL: f32 = 1e-5;

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() <= TOL * b.abs().max_element().max(1.0)
}

#[test]
fn reset_to_bounds_matches_vtk() {
    // Bounds 2 x 4 x 4: centre (1, 2, 2), radius = sqrt(36) / 2 = 3,
    // distance = 3 / sin(15 deg) along +z (the default view plane normal).
    let c = Camera::reset_to_bounds(Vec3::ZERO, Vec3::new(2.0, 4.0, 4.0)).unwrap();
    let distance = 3.0 / 15f32.to_radians().sin();
    assert!((distance - 11.591_109).abs() < 1e-4);
    assert!(close(c.focal_point, Vec3::new(1.0, 2.0, 2.0)));
    assert!(close(c.position, Vec3::new(1.0, 2.0, 2.0 + distance)));
    assert_eq!(c.view_up, Vec3::Y);
    assert_eq!(c.view_angle, 30.0);
    assert_eq!(c.parallel_scale, None);

    // Orthographic: the parallel scale becomes the radius.
    let mut ortho = Camera {
        parallel_scale: Some(1.0),
        ..Camera::default()
    };
    ortho
        .reset(Vec3::ZERO, Vec3::new(2.0, 4.0, 4.0), 1.0)
        .unwrap();
    assert!((ortho.parallel_scale.unwrap() - 3.0).abs() < TOL);
    // A tall window (aspect 1/2) fits the sphere horizontally, as VTK does:
    // half angle atan(tan(15 deg) / 2), scale radius / aspect.
    ortho
        .reset(Vec3::ZERO, Vec3::new(2.0, 4.0, 4.0), 0.5)
        .unwrap();
    assert!((ortho.parallel_scale.unwrap() - 6.0).abs() < TOL);
    let half = (15f64.to_radians().tan() * 0.5).atan();
    let d = (3.0 / half.sin()) as f32;
    assert!(close(ortho.position, Vec3::new(1.0, 2.0, 2.0 + d)));
    // A view-up parallel to the view direction is rotated, as VTK does.
    let mut up_z = Camera {
        view_up: Vec3::Z,
        ..Camera::default()
    };
    up_z.reset(Vec3::ZERO, Vec3::ONE, 1.0).unwrap();
    assert_eq!(up_z.view_up, Vec3::NEG_X); // (-up.z, up.x, up.y)
    // Degenerate bounds (a point): radius 1, as VTK.
    let p = Camera::reset_to_bounds(Vec3::ONE, Vec3::ONE).unwrap();
    assert!(close(
        p.position,
        Vec3::new(1.0, 1.0, 1.0 + 1.0 / 15f32.to_radians().sin())
    ));
}

#[test]
fn azimuth_and_elevation_match_hand_computed_positions() {
    let mut c = Camera::default();
    c.azimuth(90.0).unwrap();
    // About +y, right-handed: (0, 0, 1) -> (1, 0, 0): the camera moves right.
    assert!(close(c.position, Vec3::X), "{:?}", c.position);

    let mut c = Camera::default();
    c.elevation(90.0).unwrap();
    assert!(close(c.position, Vec3::Y), "{:?}", c.position);
    // VTK leaves the view-up alone in Elevation.
    assert_eq!(c.view_up, Vec3::Y);

    // Azimuth 30 then elevation 20 (the Blunt Fin view): the position
    // (sin 30, 0, cos 30) tilts up by 20 degrees towards +y.
    let mut c = Camera::default();
    c.azimuth(30.0).unwrap();
    c.elevation(20.0).unwrap();
    let (s30, c30) = 30f32.to_radians().sin_cos();
    let (s20, c20) = 20f32.to_radians().sin_cos();
    let want = Vec3::new(s30 * c20, s20, c30 * c20);
    assert!(close(c.position, want), "{:?} vs {want:?}", c.position);
    c.orthogonalize_view_up().unwrap();
    // Orthogonalised up: perpendicular to the view direction, in the plane
    // of the old up and the direction: (-s30 s20, c20, -c30 s20).
    let up = Vec3::new(-s30 * s20, c20, -c30 * s20);
    assert!(close(c.view_up, up), "{:?} vs {up:?}", c.view_up);

    // Rotations about an off-origin focal point keep the distance.
    let mut c = Camera {
        position: Vec3::new(1.0, 2.0, 8.0),
        focal_point: Vec3::new(1.0, 2.0, 3.0),
        ..Camera::default()
    };
    c.azimuth(-90.0).unwrap();
    assert!(
        close(c.position, Vec3::new(-4.0, 2.0, 3.0)),
        "{:?}",
        c.position
    );
}

#[test]
fn row_zero_is_the_top_and_pixels_are_sampled_at_centres() {
    let c = Camera::default();
    let (w, h) = (4, 2);
    let top_left = c.ray(0, 0, w, h).unwrap();
    let bottom_right = c.ray(w - 1, h - 1, w, h).unwrap();
    assert!(top_left.dir.y > 0.0 && top_left.dir.x < 0.0);
    assert!(bottom_right.dir.y < 0.0 && bottom_right.dir.x > 0.0);
    // Pixel (0, 0) of a 4 x 2 image: centre at (-1.5, +0.5) pixels from the
    // image centre, a pixel being tan(15 deg) world units at unit distance.
    let t = 15f32.to_radians().tan();
    let want = Vec3::new(-1.5 * t, 0.5 * t, -1.0).normalize();
    assert!(close(top_left.dir, want), "{:?} vs {want:?}", top_left.dir);
    assert_eq!(top_left.origin, c.position);

    // Orthographic: parallel rays from the view plane, half height = scale.
    let o = Camera {
        parallel_scale: Some(2.0),
        ..Camera::default()
    };
    let r = o.ray(0, 0, w, h).unwrap();
    assert!(close(r.dir, Vec3::NEG_Z));
    // Pixels are 2 * 2 / 2 = 2 units: centre (-3, 1) from the axis.
    assert!(close(r.origin, Vec3::new(-3.0, 1.0, 1.0)), "{:?}", r.origin);
}

#[test]
fn invalid_cameras_are_rejected() {
    let at_focus = Camera {
        position: Vec3::ZERO,
        ..Camera::default()
    };
    assert!(matches!(
        at_focus.basis(),
        Err(CameraError::PositionAtFocalPoint { .. })
    ));
    let parallel_up = Camera {
        view_up: Vec3::new(0.0, 0.0, 2.0),
        ..Camera::default()
    };
    assert!(matches!(
        parallel_up.ray(0, 0, 2, 2),
        Err(CameraError::ViewUpParallel { .. })
    ));
    let nan = Camera {
        focal_point: Vec3::new(f32::NAN, 0.0, 0.0),
        ..Camera::default()
    };
    assert!(matches!(nan.basis(), Err(CameraError::NonFinite { .. })));
    let wide = Camera {
        view_angle: 180.0,
        ..Camera::default()
    };
    assert!(matches!(wide.basis(), Err(CameraError::BadViewAngle(_))));
    let flat = Camera {
        parallel_scale: Some(0.0),
        ..Camera::default()
    };
    assert!(matches!(
        flat.basis(),
        Err(CameraError::BadParallelScale(_))
    ));
    assert!(matches!(
        Camera::default().ray(2, 0, 2, 2),
        Err(CameraError::PixelOutOfRange { .. })
    ));
    assert!(matches!(
        Camera::default().pixel_rays(0, 3),
        Err(CameraError::BadImageSize { .. })
    ));
    assert!(matches!(
        Camera::reset_to_bounds(Vec3::ONE, Vec3::ZERO),
        Err(CameraError::BadBounds { .. })
    ));
}

#[test]
fn inside_bounds_is_reported() {
    let c = Camera::reset_to_bounds(Vec3::ZERO, Vec3::ONE).unwrap();
    assert!(!c.is_inside_bounds(Vec3::ZERO, Vec3::ONE));
    let inside = Camera {
        position: Vec3::splat(0.5),
        focal_point: Vec3::new(0.5, 0.5, 0.0),
        ..Camera::default()
    };
    assert!(inside.is_inside_bounds(Vec3::ZERO, Vec3::ONE));
}
