//! The CPU twin of the projection pipeline: the same draws in the same
//! order, the vertex stage's f32 arithmetic per corner, rasterization at
//! pixel centres (back faces culled, top-left rule on shared edges),
//! attributes interpolated linearly in screen space, the fragment stage's
//! exit choice, clip and integration (tetray_gpu's twin of
//! integrate.wgsl), and the blender's premultiplied "over". Where the GPU
//! and the twin differ it is the device's arithmetic (its rasterizer's
//! fixed-point edge tests and interpolation, fused multiply-adds), not the
//! algorithm.

mod raster;
mod stages;

use rayon::prelude::*;
use tetray_core::Image;
use tetray_gpu::IntegratorData;
use tetray_gpu::twin::integrate::IntegratorInputs;

use crate::ProjectError;
use crate::layout::Params;
use crate::scene::{FACE_VERTS, ProjectScene};
use crate::view::View;
use raster::{Screen, covered_pixels};
use stages::{Corner, Fragment, fragment, vertex};

/// Rows per band: bands are rendered in parallel, each over every draw.
const BAND_ROWS: u32 = 16;

/// What the twin draws: premultiplied image and the fragments integrated.
pub fn render(
    scene: &ProjectScene,
    integrator: &IntegratorData,
    view: &View,
    draws: &[[u32; 2]],
) -> Result<(Image, u64), ProjectError> {
    if !integrator.grey {
        return Err(ProjectError::ColouredAttenuation);
    }
    let params = Params::new(view, integrator);
    let inputs = IntegratorInputs::new(&params.integrator, integrator);
    let screen = Screen::new(view);
    // The vertex stage once per draw.
    let corners: Vec<[Corner; 4]> = draws
        .par_iter()
        .map(|&[tet, clip]| {
            let verts = scene.tets[tet as usize];
            let q = verts.map(|v| glam::Vec4::from_array(scene.points[v as usize]));
            std::array::from_fn(|i| vertex(&params, &q, i, clip))
        })
        .collect();
    let width = view.width as usize;
    let mut rgba = vec![[0.0f32; 4]; width * view.height as usize];
    let segments = rgba
        .par_chunks_mut(width * BAND_ROWS as usize)
        .enumerate()
        .map(|(band, pixels)| {
            let y0 = band as u32 * BAND_ROWS;
            let rows = (pixels.len() / width) as u32;
            let mut count = 0u64;
            for draw in &corners {
                for face in FACE_VERTS {
                    let tri = face.map(|i| &draw[i]);
                    covered_pixels(&screen, tri.map(|c| c.clip), y0, y0 + rows, |px, py, w| {
                        let f = Fragment::interpolate(&tri, w, px, py);
                        if let Some(light) = fragment(&params, &inputs, &f) {
                            let out = &mut pixels[(py - y0) as usize * width + px as usize];
                            let alpha = 1.0 - light.transmittance.x;
                            let keep = 1.0 - alpha;
                            let e = light.emitted;
                            *out = [
                                e.x + keep * out[0],
                                e.y + keep * out[1],
                                e.z + keep * out[2],
                                alpha + keep * out[3],
                            ];
                            count += 1;
                        }
                    });
                }
            }
            count
        })
        .sum();
    Ok((Image::from_pixels(view.width, view.height, rgba)?, segments))
}
