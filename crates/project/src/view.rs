//! One frame's view: the camera's rays in the form the projection needs
//! (the ray casters' pixel-centre convention: pixel `(px, py)` is the ray
//! through `right * x + up * y`, `x = (px + 0.5 - width / 2) * pixel`,
//! `y = (height / 2 - py - 0.5) * pixel`, at unit depth or on the view plane).

use glam::Vec3;
use tetray_core::{Camera, CameraError};
use tetray_gpu::layout::ViewParams;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// The eye (perspective) or a point of the view plane (orthographic).
    pub position: Vec3,
    pub right: Vec3,
    pub up: Vec3,
    /// Unit direction of projection.
    pub direction: Vec3,
    /// World size of a pixel at unit depth (perspective) or on the view
    /// plane (orthographic).
    pub pixel: f32,
    pub width: u32,
    pub height: u32,
    pub orthographic: bool,
    /// The same camera as the kernels' parameter block.
    pub params: ViewParams,
}

impl View {
    pub fn new(camera: &Camera, width: u32, height: u32) -> Result<View, CameraError> {
        let rays = camera.pixel_rays(width, height)?;
        let basis = rays.basis();
        Ok(View {
            position: rays.position(),
            right: basis.right,
            up: basis.up,
            direction: basis.direction,
            pixel: rays.pixel_size(),
            width,
            height,
            orthographic: rays.is_orthographic(),
            params: ViewParams::new(&rays),
        })
    }

    pub fn half_width(&self) -> f32 {
        self.width as f32 * 0.5
    }

    pub fn half_height(&self) -> f32 {
        self.height as f32 * 0.5
    }

    /// Depth of `p` along the direction of projection from the eye (or the
    /// view plane): the key of the centroid sort, as vtkCellCenterDepthSort.
    pub fn depth(&self, p: Vec3) -> f32 {
        (p - self.position).dot(self.direction)
    }

    /// Which side of the plane `n . x = offset` the eye is on: positive on
    /// the side the normal points to (for orthographic views the eye is at
    /// infinity against the direction of projection). A plane and its exact
    /// negation give exactly negated values.
    pub fn eye_side(&self, plane: &[f32; 4]) -> f32 {
        let n = Vec3::new(plane[0], plane[1], plane[2]);
        if self.orthographic {
            -n.dot(self.direction)
        } else {
            n.dot(self.position) - plane[3]
        }
    }
}
