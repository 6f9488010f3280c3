//! Per-interval ray fragments, for compositing rays split over several
//! meshes (the pieces of a partitioned mesh on different processes).
//!
//! A ray crosses a mesh in one or more intervals, each from an entry
//! through a boundary face to the next exit through one. The light of each
//! interval, composited alone, is one [`Fragment`]. Intervals are never
//! merged across a gap, so the intervals of other meshes that fall in the
//! gap can be composited in between: sorted by entry depth and blended
//! front to back, the fragments of every piece give the ray's integral
//! (compositing is associative, and intervals of disjoint pieces never
//! overlap in depth).

use std::time::Instant;

use rayon::prelude::*;
use tetray_integrate::{KernelVisitor, ScalarIntegrator, SegmentKernel, Typed};

use crate::cpu::{BAND_ROWS, Frame, RenderError, RenderOptions, RenderStats, in_pool};
use crate::segment::SegmentIntegrator;
use crate::walk::{WalkLimits, Walker};
use tetray_core::camera::Camera;
use tetray_scene::Scene;

/// The light of one interval of one pixel's ray inside a mesh: 32 bytes,
/// sent as they are between processes.
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct Fragment {
    /// The pixel, `y * width + x` (row 0 at the top).
    pub pixel: u32,
    /// Distance along the ray where the interval starts (world units,
    /// clipped at the ray origin): the compositing order.
    pub depth: f32,
    /// Premultiplied colour the interval sends towards the eye.
    pub color: [f32; 3],
    /// Per-channel transmittance of the interval.
    pub transmittance: [f32; 3],
}

impl Fragment {
    /// A fragment that changes nothing: no light, full transmittance.
    pub fn is_clear(&self) -> bool {
        self.color == [0.0; 3] && self.transmittance == [1.0; 3]
    }
}

/// Every fragment of a frame, and what the rays did.
#[derive(Debug, Clone)]
pub struct FragmentOutput {
    /// Grouped by pixel (in the order the rays were cast), front to back
    /// within a pixel.
    pub fragments: Vec<Fragment>,
    pub stats: RenderStats,
}

/// Casts every pixel's ray through `scene` and keeps the light of each
/// interval apart: one [`Fragment`] per interval in which a segment was
/// integrated. Entries come from per-pixel lists where the frame gains from
/// them, as in [`crate::render_cpu`] (the same entries as the BVH's).
///
/// Early termination would cut a ray on what this mesh alone knows, so it
/// is not applied: `opts.early_termination` must be 1. A ray stops inside
/// an interval only once its transmittance is exactly zero there, which
/// nothing composited behind it can change.
pub fn render_fragments<I: SegmentIntegrator + ?Sized>(
    scene: &Scene,
    camera: &Camera,
    integrator: &I,
    opts: &RenderOptions,
) -> Result<FragmentOutput, RenderError> {
    fragments_with(scene, camera, integrator, opts, true)
}

/// [`render_fragments`], with entry lists allowed or not.
fn fragments_with<I: SegmentIntegrator + ?Sized>(
    scene: &Scene,
    camera: &Camera,
    integrator: &I,
    opts: &RenderOptions,
    entry_lists: bool,
) -> Result<FragmentOutput, RenderError> {
    if opts.early_termination != 1.0 {
        return Err(RenderError::BadEarlyTermination(opts.early_termination));
    }
    let rays = camera.pixel_rays(opts.width, opts.height)?;
    let mut frame = Frame::new(scene, camera, &rays, integrator, opts);
    frame.limits = WalkLimits {
        stop_below_sum: 0.0,
        ..frame.limits
    };
    let (width, height) = (frame.width, frame.height);
    let start = Instant::now();
    let bands = in_pool(opts.threads, || {
        if entry_lists {
            frame.bin_entries();
        }
        let frame = &frame;
        (0..height.div_ceil(BAND_ROWS))
            .into_par_iter()
            .map(|band| {
                let y0 = band * BAND_ROWS;
                let rows = BAND_ROWS.min(height - y0);
                let mut fragments = Vec::new();
                let stats = frame.band(y0, rows, Walker::split, |walker, index| {
                    walker.close_interval();
                    let pixel = (y0 * width + index) as u32;
                    fragments.extend(walker.intervals.iter().map(|i| Fragment {
                        pixel,
                        depth: i.depth,
                        color: i.light.color.to_array(),
                        transmittance: i.light.transmittance.to_array(),
                    }));
                });
                (fragments, stats)
            })
            .collect::<Vec<_>>()
    })?;
    let mut stats = RenderStats::default();
    let mut fragments = Vec::with_capacity(bands.iter().map(|b| b.0.len()).sum());
    for (band, band_stats) in bands {
        fragments.extend(band);
        stats = stats.merge(band_stats);
    }
    stats.elapsed = start.elapsed();
    let (lo, hi) = scene.bounds();
    stats.eye_inside_bounds = camera.is_inside_bounds(lo, hi);
    stats.entry_lists = frame.uses_entry_lists();
    Ok(FragmentOutput { fragments, stats })
}

/// [`render_fragments`] with a transfer-function integrator, the walk
/// compiled for its method.
pub fn render_scalar_fragments(
    scene: &Scene,
    camera: &Camera,
    integrator: &ScalarIntegrator,
    opts: &RenderOptions,
) -> Result<FragmentOutput, RenderError> {
    struct Render<'a> {
        scene: &'a Scene,
        camera: &'a Camera,
        opts: &'a RenderOptions,
    }
    impl KernelVisitor for Render<'_> {
        type Output = Result<FragmentOutput, RenderError>;
        fn visit<K: SegmentKernel>(self, integrator: Typed<'_, K>) -> Self::Output {
            render_fragments(self.scene, self.camera, &integrator, self.opts)
        }
    }
    integrator.dispatch(Render {
        scene,
        camera,
        opts,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::tests::{Glow, holed_box_views};

    /// The fragments with entries from per-pixel lists are those with BVH
    /// entries bit for bit, on a mesh with a hole (intervals that end and
    /// begin again) seen from outside, from inside and by orthographic
    /// rays starting inside it.
    #[test]
    fn entry_lists_give_the_same_fragments() {
        let (scene, [outside, inside, through]) = holed_box_views();
        let opts = RenderOptions {
            width: 45,
            height: 38,
            ..RenderOptions::default()
        };
        for camera in [outside, inside, through] {
            let with = fragments_with(&scene, &camera, &Glow, &opts, true).unwrap();
            let without = fragments_with(&scene, &camera, &Glow, &opts, false).unwrap();
            // A perspective eye inside the bounds keeps the BVH.
            assert_eq!(with.stats.entry_lists, camera != inside);
            assert!(!without.stats.entry_lists);
            let (a, b) = (&with.fragments, &without.fragments);
            assert!(
                with.stats.counters.entries > with.stats.counters.rays_hit,
                "rays re-enter"
            );
            assert!(a.len() >= with.stats.counters.rays_hit as usize);
            assert_eq!(
                bytemuck::cast_slice::<_, u32>(a),
                bytemuck::cast_slice::<_, u32>(b)
            );
            let counters =
                |s: &RenderStats| (s.counters.segments, s.counters.steps, s.counters.entries);
            assert_eq!(counters(&with.stats), counters(&without.stats));
        }
    }
}
