//! Rasterization at pixel centres, as the GPU's: clip to framebuffer
//! coordinates (row 0 at the top), triangles facing away culled (counter-
//! clockwise in normalized device coordinates is front), a pixel covered
//! when its centre is inside, a centre exactly on an edge taken by the
//! top-left rule, so a pixel on an edge two faces share is covered once.
//! Edge functions in f64: the twin's coverage is exact for its f32 corners.

use glam::Vec4;

use crate::view::View;

pub struct Screen {
    width: f64,
    height: f64,
}

impl Screen {
    pub fn new(view: &View) -> Screen {
        Screen {
            width: f64::from(view.width),
            height: f64::from(view.height),
        }
    }

    /// Framebuffer position of a clip-space point (in front of the eye).
    fn place(&self, clip: Vec4) -> [f64; 2] {
        let w = f64::from(clip.w);
        let (x, y) = (f64::from(clip.x) / w, f64::from(clip.y) / w);
        [(x + 1.0) * 0.5 * self.width, (1.0 - y) * 0.5 * self.height]
    }
}

/// Calls `visit(px, py, weights)` for every pixel of rows `y0..y1` whose
/// centre the front-facing triangle covers, with the centre's screen-space
/// barycentric weights of the three corners.
pub fn covered_pixels(
    screen: &Screen,
    clip: [Vec4; 3],
    y0: u32,
    y1: u32,
    mut visit: impl FnMut(u32, u32, [f32; 3]),
) {
    // Corners behind the eye: the GPU clips them away; a cell reaching
    // behind the eye is left out here (the camera is outside the mesh in
    // every use of the twin).
    if clip.iter().any(|c| c.w <= 0.0) {
        return;
    }
    let p = clip.map(|c| screen.place(c));
    // Framebuffer y runs down: counter-clockwise in NDC is negative area.
    let area = edge(p[0], p[1], p[2]);
    if area >= 0.0 {
        return;
    }
    // Reverse to a positive area in framebuffer coordinates.
    let order = [0usize, 2, 1];
    let q = order.map(|i| p[i]);
    let area = -area;
    let lo_x = q.iter().map(|v| v[0]).fold(f64::INFINITY, f64::min);
    let hi_x = q.iter().map(|v| v[0]).fold(f64::NEG_INFINITY, f64::max);
    let lo_y = q.iter().map(|v| v[1]).fold(f64::INFINITY, f64::min);
    let hi_y = q.iter().map(|v| v[1]).fold(f64::NEG_INFINITY, f64::max);
    let first_x = (lo_x - 0.5).ceil().max(0.0) as u32;
    let last_x = ((hi_x - 0.5).floor()).min(screen.width - 1.0);
    let first_y = ((lo_y - 0.5).ceil().max(0.0) as u32).max(y0);
    let last_y = ((hi_y - 0.5).floor()).min(f64::from(y1) - 1.0);
    if last_x < 0.0 || last_y < 0.0 {
        return;
    }
    let (last_x, last_y) = (last_x as u32, last_y as u32);
    let edges = [(1usize, 2usize), (2, 0), (0, 1)];
    let top_left = edges.map(|(a, b)| {
        let (dx, dy) = (q[b][0] - q[a][0], q[b][1] - q[a][1]);
        (dy == 0.0 && dx > 0.0) || dy < 0.0
    });
    for py in first_y..=last_y {
        let cy = f64::from(py) + 0.5;
        for px in first_x..=last_x {
            let c = [f64::from(px) + 0.5, cy];
            let e = edges.map(|(a, b)| edge(q[a], q[b], c));
            let inside = (0..3).all(|i| e[i] > 0.0 || (e[i] == 0.0 && top_left[i]));
            if inside {
                // e[i] is the weight of corner i (of q); back to the
                // original corner order.
                let mut w = [0.0f32; 3];
                for (k, &i) in order.iter().enumerate() {
                    w[i] = (e[k] / area) as f32;
                }
                visit(px, py, w);
            }
        }
    }
}

/// Twice the signed area of (a, b, c) in framebuffer coordinates.
fn edge(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}
