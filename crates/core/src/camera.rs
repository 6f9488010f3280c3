//! A camera with VTK's conventions (vtkCamera / vtkRenderer::ResetCamera), so
//! that views can be matched one to one with VTK and ParaView renders.
//!
//! - the view angle is the full vertical angle in degrees;
//! - `parallel_scale`, when set, makes the projection orthographic with half
//!   the view height equal to it, in world units;
//! - image row 0 is the top row; pixel `(px, py)` is sampled at its centre.

use crate::watertight::RayFrame;
use glam::{DVec3, Vec3};

/// Why a camera cannot produce rays.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("camera {field} is not finite: {value:?}")]
    NonFinite {
        field: &'static str,
        value: [f32; 3],
    },
    #[error("camera position {position:?} equals its focal point: no view direction")]
    PositionAtFocalPoint { position: [f32; 3] },
    #[error("camera view-up {view_up:?} is zero or parallel to the view direction {direction:?}")]
    ViewUpParallel {
        view_up: [f32; 3],
        direction: [f32; 3],
    },
    #[error("camera view angle {0} degrees is outside (0, 180)")]
    BadViewAngle(f32),
    #[error("camera parallel scale {0} must be finite and positive")]
    BadParallelScale(f32),
    #[error("camera {what} factor {value} must be finite and positive")]
    BadFactor { what: &'static str, value: f32 },
    #[error("image size {width}x{height} must be at least 1x1")]
    BadImageSize { width: u32, height: u32 },
    #[error("pixel ({px}, {py}) is outside the {width}x{height} image")]
    PixelOutOfRange {
        px: u32,
        py: u32,
        width: u32,
        height: u32,
    },
    #[error("bounds min {min:?} max {max:?} are not finite or not ordered")]
    BadBounds { min: [f32; 3], max: [f32; 3] },
}

/// A VTK-style camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub focal_point: Vec3,
    /// Need not be orthogonal to the view direction (as in VTK); only its
    /// component perpendicular to the direction of projection is used.
    pub view_up: Vec3,
    /// Full vertical view angle, degrees (perspective only).
    pub view_angle: f32,
    /// `Some(s)`: orthographic projection, half the view height is `s`.
    pub parallel_scale: Option<f32>,
}

impl Default for Camera {
    /// VTK's default camera: at (0, 0, 1) looking at the origin, +y up, 30
    /// degree view angle, perspective.
    fn default() -> Self {
        Camera {
            position: Vec3::Z,
            focal_point: Vec3::ZERO,
            view_up: Vec3::Y,
            view_angle: 30.0,
            parallel_scale: None,
        }
    }
}

/// A point given in a file's coordinates (f64; a camera position or focal
/// point) in the coordinates of a mesh stored relative to `origin`
/// (`tetray_mesh::LoadReport::origin`): subtracted in f64, then rounded to
/// f32, so a camera at 7e6 m keeps the resolution of the mesh near it.
pub fn relative_to_origin(world: DVec3, origin: DVec3) -> Vec3 {
    (world - origin).as_vec3()
}

/// The orthonormal view basis of a validated camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewBasis {
    /// Unit direction of projection (position towards focal point).
    pub direction: Vec3,
    /// Unit screen right.
    pub right: Vec3,
    /// Unit screen up (view-up orthogonalised against the direction).
    pub up: Vec3,
}

impl Camera {
    /// VTK's default camera after `vtkRenderer::ResetCamera(bounds)` on a
    /// window at least as wide as tall.
    pub fn reset_to_bounds(min: Vec3, max: Vec3) -> Result<Camera, CameraError> {
        let mut camera = Camera::default();
        camera.reset(min, max, 1.0)?;
        Ok(camera)
    }

    /// `vtkRenderer::ResetCamera`: keeps the view direction and view angle,
    /// looks at the centre of the bounds from the distance at which the
    /// bounding sphere (radius = half the diagonal) fills the view angle, and
    /// sets the parallel scale (if orthographic) to that radius. `aspect` is
    /// width / height of the image; narrow windows (aspect < 1) fit the
    /// sphere horizontally, as VTK does.
    pub fn reset(&mut self, min: Vec3, max: Vec3, aspect: f32) -> Result<(), CameraError> {
        if !min.is_finite() || !max.is_finite() || min.cmpgt(max).any() {
            return Err(CameraError::BadBounds {
                min: min.to_array(),
                max: max.to_array(),
            });
        }
        let direction =
            (self.focal_point.as_dvec3() - self.position.as_dvec3()).normalize_or_zero();
        if direction == DVec3::ZERO || !direction.is_finite() {
            return Err(CameraError::PositionAtFocalPoint {
                position: self.position.to_array(),
            });
        }
        let (min, max) = (min.as_dvec3(), max.as_dvec3());
        let centre = (min + max) * 0.5;
        let extent = max - min;
        let r2 = extent.length_squared();
        let radius = if r2 == 0.0 { 1.0 } else { r2.sqrt() * 0.5 };
        let mut angle = f64::from(self.view_angle).to_radians();
        let mut parallel_scale = radius;
        if aspect.is_finite() && aspect > 0.0 && aspect < 1.0 {
            angle = 2.0 * ((angle * 0.5).tan() * f64::from(aspect)).atan();
            parallel_scale /= f64::from(aspect);
        }
        let distance = radius / (angle * 0.5).sin();
        // View plane normal: from the focal point towards the camera.
        let normal = -direction;
        if self
            .view_up
            .as_dvec3()
            .normalize_or_zero()
            .dot(normal)
            .abs()
            > 0.999
        {
            // VTK rotates the view-up components when it is parallel.
            self.view_up = Vec3::new(-self.view_up.z, self.view_up.x, self.view_up.y);
        }
        self.focal_point = centre.as_vec3();
        self.position = (centre + normal * distance).as_vec3();
        if self.parallel_scale.is_some() {
            self.parallel_scale = Some(parallel_scale as f32);
        }
        self.basis().map(|_| ())
    }

    /// Checks the camera and returns its orthonormal view basis.
    pub fn basis(&self) -> Result<ViewBasis, CameraError> {
        for (field, value) in [
            ("position", self.position),
            ("focal point", self.focal_point),
            ("view-up", self.view_up),
        ] {
            if !value.is_finite() {
                return Err(CameraError::NonFinite {
                    field,
                    value: value.to_array(),
                });
            }
        }
        if !(self.view_angle > 0.0 && self.view_angle < 180.0) {
            return Err(CameraError::BadViewAngle(self.view_angle));
        }
        if let Some(s) = self.parallel_scale
            && !(s.is_finite() && s > 0.0)
        {
            return Err(CameraError::BadParallelScale(s));
        }
        let direction =
            (self.focal_point.as_dvec3() - self.position.as_dvec3()).normalize_or_zero();
        if direction == DVec3::ZERO || !direction.is_finite() {
            return Err(CameraError::PositionAtFocalPoint {
                position: self.position.to_array(),
            });
        }
        let right = direction.cross(self.view_up.as_dvec3());
        // Relative test: a tiny but non-parallel view-up is still usable.
        let up_len = self.view_up.as_dvec3().length();
        if right.length() <= 1e-6 * up_len || !right.is_finite() {
            return Err(CameraError::ViewUpParallel {
                view_up: self.view_up.to_array(),
                direction: direction.as_vec3().to_array(),
            });
        }
        let right = right.normalize();
        let up = right.cross(direction);
        Ok(ViewBasis {
            direction: direction.as_vec3(),
            right: right.as_vec3(),
            up: up.as_vec3(),
        })
    }

    /// `vtkCamera::Azimuth`: rotates the position about the view-up vector
    /// centred at the focal point (positive: the camera moves to its right).
    pub fn azimuth(&mut self, degrees: f32) -> Result<(), CameraError> {
        self.basis()?;
        let axis = self.view_up.as_dvec3();
        self.position = rotate_about(self.position, self.focal_point, axis, degrees);
        Ok(())
    }

    /// `vtkCamera::Elevation`: rotates the position about the camera's
    /// negative right vector (`-(direction x view_up)`) centred at the focal
    /// point (positive: the camera moves up). The view-up is left unchanged,
    /// as VTK does; call [`Camera::orthogonalize_view_up`] afterwards.
    pub fn elevation(&mut self, degrees: f32) -> Result<(), CameraError> {
        let basis = self.basis()?;
        let axis = -basis.right.as_dvec3();
        self.position = rotate_about(self.position, self.focal_point, axis, degrees);
        Ok(())
    }

    /// `vtkCamera::OrthogonalizeViewUp`: replaces the view-up by the unit
    /// screen-up vector (perpendicular to the view direction).
    pub fn orthogonalize_view_up(&mut self) -> Result<(), CameraError> {
        self.view_up = self.basis()?.up;
        Ok(())
    }

    /// `vtkCamera::Zoom`: narrows the view angle (perspective) or divides the
    /// parallel scale (orthographic) by `factor`.
    pub fn zoom(&mut self, factor: f32) -> Result<(), CameraError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(CameraError::BadFactor {
                what: "zoom",
                value: factor,
            });
        }
        match self.parallel_scale.as_mut() {
            Some(s) => *s /= factor,
            None => self.view_angle /= factor,
        }
        self.basis().map(|_| ())
    }

    /// `vtkCamera::Dolly`: moves the position towards the focal point,
    /// dividing their distance by `factor`.
    pub fn dolly(&mut self, factor: f32) -> Result<(), CameraError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(CameraError::BadFactor {
                what: "dolly",
                value: factor,
            });
        }
        let focal = self.focal_point.as_dvec3();
        let offset = self.position.as_dvec3() - focal;
        self.position = (focal + offset / f64::from(factor)).as_vec3();
        self.basis().map(|_| ())
    }

    /// Whether the camera position lies inside (or on) the box `[min, max]`.
    /// Rays then start inside the mesh's bounds, possibly inside the mesh;
    /// the renderer handles that (it integrates from the eye), but a user
    /// usually did not mean it.
    pub fn is_inside_bounds(&self, min: Vec3, max: Vec3) -> bool {
        self.position.cmpge(min).all() && self.position.cmple(max).all()
    }

    /// The ray through the centre of pixel `(px, py)` of a `width x height`
    /// image (row 0 at the top).
    pub fn ray(&self, px: u32, py: u32, width: u32, height: u32) -> Result<RayFrame, CameraError> {
        if px >= width || py >= height {
            return Err(CameraError::PixelOutOfRange {
                px,
                py,
                width,
                height,
            });
        }
        Ok(self.pixel_rays(width, height)?.ray(px, py))
    }

    /// Validates once and returns a cheap per-pixel ray generator.
    pub fn pixel_rays(&self, width: u32, height: u32) -> Result<PixelRays, CameraError> {
        if width == 0 || height == 0 {
            return Err(CameraError::BadImageSize { width, height });
        }
        let basis = self.basis()?;
        // World size of one (square) pixel: at unit distance (perspective)
        // or on the view plane (orthographic). Offsets are computed as
        // `(px + 0.5 - width / 2) * pixel`, exact for dyadic pixel sizes, so
        // tests can aim pixel centres exactly at grid vertices.
        let half_height = match self.parallel_scale {
            Some(s) => f64::from(s),
            None => (f64::from(self.view_angle).to_radians() * 0.5).tan(),
        };
        let pixel = (2.0 * half_height / f64::from(height)) as f32;
        Ok(PixelRays {
            basis,
            position: self.position,
            pixel,
            half_width: width as f32 * 0.5,
            half_height: height as f32 * 0.5,
            orthographic: self.parallel_scale.is_some(),
        })
    }
}

/// Rays for every pixel of one image from one camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelRays {
    basis: ViewBasis,
    position: Vec3,
    pixel: f32,
    half_width: f32,
    half_height: f32,
    orthographic: bool,
}

impl PixelRays {
    /// The ray through the centre of pixel `(px, py)`. Perspective rays start
    /// at the camera position; orthographic rays start on the view plane
    /// through the position and run along the direction of projection.
    /// Distances along either are measured from that start.
    #[inline]
    pub fn ray(&self, px: u32, py: u32) -> RayFrame {
        let x = (px as f32 + 0.5 - self.half_width) * self.pixel;
        let y = (self.half_height - (py as f32 + 0.5)) * self.pixel;
        let offset = self.basis.right * x + self.basis.up * y;
        if self.orthographic {
            RayFrame::new(self.position + offset, self.basis.direction)
        } else {
            RayFrame::new(self.position, self.basis.direction + offset)
        }
    }

    pub fn basis(&self) -> ViewBasis {
        self.basis
    }

    /// Where perspective rays start; orthographic rays start on the view
    /// plane through it.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// World size of one pixel (at unit distance, or on the view plane).
    pub fn pixel_size(&self) -> f32 {
        self.pixel
    }

    /// Half the image width and height, in pixels.
    pub fn half_size(&self) -> (f32, f32) {
        (self.half_width, self.half_height)
    }

    pub fn is_orthographic(&self) -> bool {
        self.orthographic
    }
}

/// Rotates `point` by `degrees` (right-handed) about `axis` through `centre`.
fn rotate_about(point: Vec3, centre: Vec3, axis: DVec3, degrees: f32) -> Vec3 {
    let axis = axis.normalize();
    let (sin, cos) = f64::from(degrees).to_radians().sin_cos();
    let p = point.as_dvec3() - centre.as_dvec3();
    // Rodrigues' rotation formula.
    let rotated = p * cos + axis.cross(p) * sin + axis * axis.dot(p) * (1.0 - cos);
    (centre.as_dvec3() + rotated).as_vec3()
}
