//! The CPU reference renderer: one ray per pixel, tiles in parallel (rayon).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use glam::Vec3;
use rayon::prelude::*;
use tetray_core::watertight::RayFrame;
use tetray_integrate::{
    KernelVisitor, SampledSegment, ScalarIntegrator, SegmentKernel, SegmentLight, Typed,
};

use tetray_core::WalkCounters;
use tetray_core::camera::{Camera, CameraError, PixelRays};
use tetray_core::image::{Image, ImageError};

use crate::entries::EntryBins;
use crate::exits::Lanes;
use crate::segment::SegmentIntegrator;
use crate::walk::{Cells, RayCounters, WalkLimits, Walker};
use tetray_scene::Scene;

/// Tile edge in pixels: neighbouring rays in both directions walk the same
/// tetrahedra, so a square tile keeps them in cache.
const TILE: usize = 16;

/// What to render and how.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    /// Stop a ray once its opacity `1 - mean(T)` reaches this; `1` (or more)
    /// disables early termination.
    pub early_termination: f32,
    /// Bound on tetrahedra visited per ray; `None`: the tetrahedron count
    /// plus 1024 (a ray enters each convex cell at most once, plus cells it
    /// only touches where it runs through vertices or edges).
    pub max_steps_per_ray: Option<u32>,
    /// Worker threads; `None`: rayon's global pool.
    pub threads: Option<usize>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 512,
            height: 512,
            early_termination: 1.0,
            max_steps_per_ray: None,
            threads: None,
        }
    }
}

/// Counters of one frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RenderStats {
    /// What the walk counted (BVH queries that found a boundary face are
    /// its entries).
    pub counters: WalkCounters,
    /// Whether rays started inside the mesh's bounds (and were integrated
    /// from their origin, walking from the first entry behind it).
    pub eye_inside_bounds: bool,
    /// Whether rays took their boundary entries from per-pixel lists made
    /// for the frame instead of BVH queries (the same entries; see
    /// `crates/raycast/src/entries.rs` for when the lists are made).
    pub entry_lists: bool,
    pub elapsed: Duration,
}

impl RenderStats {
    fn add(&mut self, ray: &RayCounters) {
        let c = &mut self.counters;
        c.rays += 1;
        c.rays_hit += u64::from(ray.hit);
        c.segments += ray.segments;
        c.steps += ray.steps;
        c.entries += ray.entries;
        c.steps_bound_hits += u64::from(ray.step_bound_hit);
        c.walk_failures += u64::from(ray.walk_failure);
        c.overlap_segments += ray.overlap_segments;
        c.overlap_overflows += u64::from(ray.overlap_overflow);
    }

    pub(crate) fn merge(mut self, other: RenderStats) -> RenderStats {
        self.counters = self.counters.merge(other.counters);
        self
    }

    /// Integrated segments per second of wall time.
    pub fn segments_per_second(&self) -> f64 {
        self.counters
            .segments_per_second(self.elapsed.as_secs_f64())
    }
}

/// A rendered frame.
#[derive(Debug, Clone)]
pub struct RenderOutput {
    pub image: Image,
    pub stats: RenderStats,
}

/// Why a frame could not be rendered.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Camera(#[from] CameraError),
    #[error(transparent)]
    Image(#[from] ImageError),
    #[error("early termination threshold {0} must be in (0, 1] (1 disables it)")]
    BadEarlyTermination(f32),
    #[error("cannot start {threads} render threads: {message}")]
    Threads { threads: usize, message: String },
    /// The caller asked the frame to stop (see [`render_cpu_watched`]).
    #[error("the render was stopped before it finished")]
    Cancelled,
}

/// Renders `scene` seen by `camera`, integrating segments with `integrator`.
pub fn render_cpu<I: SegmentIntegrator + ?Sized>(
    scene: &Scene,
    camera: &Camera,
    integrator: &I,
    opts: &RenderOptions,
) -> Result<RenderOutput, RenderError> {
    render_cpu_with_progress(scene, camera, integrator, opts, None)
}

/// [`render_cpu`], calling `progress(rows_done, rows_total)` as bands of
/// rows finish (from worker threads, in no particular order of bands).
pub fn render_cpu_with_progress<I: SegmentIntegrator + ?Sized>(
    scene: &Scene,
    camera: &Camera,
    integrator: &I,
    opts: &RenderOptions,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<RenderOutput, RenderError> {
    render_cpu_watched(scene, camera, integrator, opts, progress, None)
}

/// [`render_cpu_with_progress`] that stops once `cancel` is set: bands of
/// rows not yet begun are skipped, and the frame is
/// [`RenderError::Cancelled`] (a band stops within one band's time).
pub fn render_cpu_watched<I: SegmentIntegrator + ?Sized>(
    scene: &Scene,
    camera: &Camera,
    integrator: &I,
    opts: &RenderOptions,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    cancel: Option<&AtomicBool>,
) -> Result<RenderOutput, RenderError> {
    if opts.early_termination.is_nan() || opts.early_termination <= 0.0 {
        return Err(RenderError::BadEarlyTermination(opts.early_termination));
    }
    let rays = camera.pixel_rays(opts.width, opts.height)?;
    let mut image = Image::new(opts.width, opts.height)?;
    let mut job = Frame::new(scene, camera, &rays, integrator, opts);
    job.progress = progress;
    job.cancel = cancel;
    let start = Instant::now();
    let mut stats = in_pool(opts.threads, || {
        job.bin_entries();
        job.run(&mut image.rgba)
    })?;
    if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
        return Err(RenderError::Cancelled);
    }
    stats.elapsed = start.elapsed();
    stats.eye_inside_bounds = job.eye_inside;
    stats.entry_lists = job.uses_entry_lists();
    Ok(RenderOutput { image, stats })
}

/// Runs `work` in rayon's global pool, or in a pool of `threads` threads.
pub(crate) fn in_pool<R: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> R + Send,
) -> Result<R, RenderError> {
    Ok(match threads {
        None => work(),
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| RenderError::Threads {
                threads,
                message: e.to_string(),
            })?
            .install(work),
    })
}

/// [`render_cpu`] with a transfer-function integrator: the frame is
/// rendered by a walk compiled for the integrator's method.
pub fn render_scalar(
    scene: &Scene,
    camera: &Camera,
    integrator: &ScalarIntegrator,
    opts: &RenderOptions,
) -> Result<RenderOutput, RenderError> {
    render_scalar_with_progress(scene, camera, integrator, opts, None)
}

/// [`render_scalar`] with progress, as [`render_cpu_with_progress`].
pub fn render_scalar_with_progress(
    scene: &Scene,
    camera: &Camera,
    integrator: &ScalarIntegrator,
    opts: &RenderOptions,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<RenderOutput, RenderError> {
    render_scalar_watched(scene, camera, integrator, opts, progress, None)
}

/// [`render_scalar_with_progress`] that stops once `cancel` is set, as
/// [`render_cpu_watched`].
pub fn render_scalar_watched(
    scene: &Scene,
    camera: &Camera,
    integrator: &ScalarIntegrator,
    opts: &RenderOptions,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    cancel: Option<&AtomicBool>,
) -> Result<RenderOutput, RenderError> {
    struct Render<'a> {
        scene: &'a Scene,
        camera: &'a Camera,
        opts: &'a RenderOptions,
        progress: Option<&'a (dyn Fn(usize, usize) + Sync)>,
        cancel: Option<&'a AtomicBool>,
    }
    impl KernelVisitor for Render<'_> {
        type Output = Result<RenderOutput, RenderError>;
        fn visit<K: SegmentKernel>(self, integrator: Typed<'_, K>) -> Self::Output {
            render_cpu_watched(
                self.scene,
                self.camera,
                &integrator,
                self.opts,
                self.progress,
                self.cancel,
            )
        }
    }
    integrator.dispatch(Render {
        scene,
        camera,
        opts,
        progress,
        cancel,
    })
}

/// What one ray did, from [`trace_pixel`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RayTrace {
    pub segments: u64,
    pub steps: u64,
    pub entries: u64,
    pub step_bound_hit: bool,
    pub walk_failure: bool,
}

/// The ray of one pixel of a `opts.width x opts.height` frame, traced
/// alone: its premultiplied RGBA and what it did (for inspecting a pixel).
pub fn trace_pixel<I: SegmentIntegrator + ?Sized>(
    scene: &Scene,
    camera: &Camera,
    integrator: &I,
    opts: &RenderOptions,
    x: u32,
    y: u32,
) -> Result<([f32; 4], RayTrace), RenderError> {
    let rays = camera.pixel_rays(opts.width, opts.height)?;
    let frame = Frame::new(scene, camera, &rays, integrator, opts);
    let mut walker = Walker::new();
    let mut lanes = Lanes::new();
    frame.start(&mut walker, x as usize, y as usize);
    while walker.advance::<false, _>(scene, integrator, frame.limits, &mut lanes) {}
    let (light, c) = (walker.light, walker.counters);
    let alpha = 1.0 - light.transmittance.element_sum() / 3.0;
    Ok((
        [light.color.x, light.color.y, light.color.z, alpha],
        RayTrace {
            segments: c.segments,
            steps: c.steps,
            entries: c.entries,
            step_bound_hit: c.step_bound_hit,
            walk_failure: c.walk_failure,
        },
    ))
}

/// Everything the workers share for one frame.
pub(crate) struct Frame<'a, I: ?Sized> {
    pub scene: &'a Scene,
    rays: &'a PixelRays,
    pub integrator: &'a I,
    pub limits: WalkLimits,
    orthographic: bool,
    /// Perspective eye inside the mesh bounds.
    eye_inside: bool,
    bounds: (Vec3, Vec3),
    progress: Option<&'a (dyn Fn(usize, usize) + Sync)>,
    /// Set by the caller to stop the frame: bands not begun are skipped.
    cancel: Option<&'a AtomicBool>,
    rows_done: AtomicUsize,
    /// Whether the mesh is large enough to prefetch (see
    /// [`LARGE_MESH_TETS`]).
    large: bool,
    /// Whether the walk runs as compiled for x86-64-v3 (see [`wide_cpu`]).
    wide: bool,
    /// The boundary faces binned by tile, where rays take their entries
    /// from per-pixel lists instead of the BVH ([`crate::entries`]).
    entries: Option<EntryBins>,
    pub width: usize,
    pub height: usize,
}

impl<'a, I: SegmentIntegrator + ?Sized> Frame<'a, I> {
    /// The frame of `opts` (no progress callback).
    pub fn new(
        scene: &'a Scene,
        camera: &Camera,
        rays: &'a PixelRays,
        integrator: &'a I,
        opts: &RenderOptions,
    ) -> Self {
        let (lo, hi) = scene.bounds();
        Frame {
            scene,
            rays,
            integrator,
            limits: WalkLimits {
                stop_below_sum: 3.0 * (1.0 - opts.early_termination),
                max_steps: opts
                    .max_steps_per_ray
                    .map_or(scene.tet_count() as u64 + 1024, u64::from),
            },
            orthographic: camera.parallel_scale.is_some(),
            eye_inside: camera.is_inside_bounds(lo, hi),
            bounds: (lo, hi),
            progress: None,
            cancel: None,
            rows_done: AtomicUsize::new(0),
            large: scene.tet_count() >= LARGE_MESH_TETS,
            wide: wide_cpu(),
            entries: None,
            width: opts.width as usize,
            height: opts.height as usize,
        }
    }

    /// Bins the boundary faces for per-pixel entry lists, where the frame
    /// gains from them ([`EntryBins::new`], parallel: call it in the
    /// frame's pool).
    pub fn bin_entries(&mut self) {
        let size = (self.width, self.height);
        self.entries = EntryBins::new(
            self.scene,
            self.rays,
            size,
            self.eye_inside,
            TILE,
            self.wide,
        );
    }

    /// Whether rays take their entries from per-pixel lists.
    pub fn uses_entry_lists(&self) -> bool {
        self.entries.is_some()
    }
}

/// Rays each worker keeps in flight, taken through each stage of a step
/// together (see [`Walker::begin`]). A step of one ray is a chain of about
/// 500 dependent instructions, more than the processor's reorder window,
/// so the rays' chains overlap only when their stages are interleaved.
/// Blunt Fin PPI, 512 x 512, alternating runs: 4 rays stepped one after
/// the other 157.3 / 175.1 ms (min / median of 8), 16 in stages 110.1 /
/// 138.2 (8 in stages 119.8 / 146.5, 32 130.7 / 150.6); the 10 M torus
/// shell 25.0 -> 32.6 M segments/s (median of 3; 8 in stages 28.4).
const IN_FLIGHT: usize = 16;
/// Meshes from this many tetrahedra on prefetch the records of the cells
/// each ray may enter next (alternating runs: 40 M shell 8.2-12.5 ->
/// 13.3-17.3 M segments/s, 10 M 15.6-17.0 -> 21.3-21.5, with rays stepped
/// one after the other). Since the walk carries its entry face and
/// prefetches without branching, the 1 M shell gains too (8 alternating
/// rounds: 17.0-24.5 -> 22.6-28.8 M segments/s, faster in 7); on the
/// Blunt Fin (187 k) the two are within noise (10 rounds, min / median
/// 159.5 / 182.0 against 156.3 / 175.4 ms), as they were 4-10% slower
/// there with the walk before. Such meshes also prefetch, one stage ahead,
/// the one point each ray's next step loads ([`Walker::prefetch_next_apex`]):
/// 512 x 512, two threads, two rounds, the 40 M shell 31.8-32.4 -> 39.5-41.6
/// M segments/s, 10 M 31.4-37.2 -> 39.2-41.4, for 13 more instructions
/// per segment on the 1 M shell (504.2 -> 517.2).
const LARGE_MESH_TETS: usize = 500_000;

/// Tile edge of the CPU ray caster (rows per parallel band).
pub(crate) const BAND_ROWS: usize = TILE;

/// Whether the CPU walk runs compiled for x86-64-v3 (AVX2, FMA, BMI):
/// on a CPU that has them, unless `TETRAY_CPU_BASELINE` is set (see
/// [`tetray_wide`]). The images are the same bit for bit.
pub fn wide_cpu() -> bool {
    tetray_wide::available()
}

impl<I: SegmentIntegrator + ?Sized> Frame<'_, I> {
    /// Starts `walker` on the ray of pixel `(x, y)`.
    pub(crate) fn start(&self, walker: &mut Walker<I::Sample>, x: usize, y: usize) {
        self.start_ray(walker, self.rays.ray(x as u32, y as u32));
    }

    /// Starts `walker` on `ray`, one of the frame's pixel rays.
    #[inline(always)]
    fn start_ray(&self, walker: &mut Walker<I::Sample>, ray: RayFrame) {
        // A ray whose origin may be inside the mesh walks from the first
        // entry of its whole line (behind the origin too) so it starts in
        // the cell holding the origin.
        let inside = if self.orthographic {
            let (lo, hi) = self.bounds;
            ray.origin.cmpge(lo).all() && ray.origin.cmple(hi).all()
        } else {
            self.eye_inside
        };
        walker.start(ray, if inside { f32::NEG_INFINITY } else { 0.0 });
    }

    fn run(&self, pixels: &mut [[f32; 4]]) -> RenderStats {
        pixels
            .par_chunks_mut(self.width * TILE)
            .enumerate()
            .map(|(band, rows)| {
                if self.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                    return RenderStats::default();
                }
                let band_rows = rows.len() / self.width;
                self.band(band * TILE, band_rows, Walker::new, |walker, index| {
                    let light = walker.light;
                    let alpha = 1.0 - light.transmittance.element_sum() / 3.0;
                    let c = light.color;
                    rows[index] = [c.x, c.y, c.z, alpha];
                })
            })
            .reduce(RenderStats::default, RenderStats::merge)
    }

    /// Rows `y0..y0 + band_rows` of the image, tile by tile, [`IN_FLIGHT`]
    /// rays at a time stepped together; `finish(walker, index)` takes each
    /// finished ray's light (`index`: the pixel's index within the band).
    pub(crate) fn band(
        &self,
        y0: usize,
        band_rows: usize,
        new_walker: fn() -> Walker<I::Sample>,
        finish: impl FnMut(&mut Walker<I::Sample>, usize),
    ) -> RenderStats {
        // The walk, inlined whole, compiled for x86-64-v3 where the CPU
        // has it (the same bits in fewer instructions).
        tetray_wide::run(
            self.wide,
            #[inline(always)]
            || {
                if self.large {
                    self.band_with::<IN_FLIGHT, true>(y0, band_rows, new_walker, finish)
                } else {
                    self.band_with::<IN_FLIGHT, false>(y0, band_rows, new_walker, finish)
                }
            },
        )
    }

    /// [`Frame::band`] with `N` rays in flight, prefetching the records
    /// they may enter next or not (see [`Walker::begin`]).
    #[inline(always)]
    fn band_with<const N: usize, const PREFETCH: bool>(
        &self,
        y0: usize,
        band_rows: usize,
        new_walker: fn() -> Walker<I::Sample>,
        mut finish: impl FnMut(&mut Walker<I::Sample>, usize),
    ) -> RenderStats {
        let mut stats = RenderStats::default();
        // Pixels of the band in tile order.
        let mut pixels = (0..self.width).step_by(TILE).flat_map(|x0| {
            (0..band_rows)
                .flat_map(move |dy| (x0..(x0 + TILE).min(self.width)).map(move |x| (x, dy)))
        });
        // The entry lists of the tile being started (see `crate::entries`).
        let (mut lists, mut frames, mut tile_x0) = (Vec::new(), Vec::new(), usize::MAX);
        let mut start = |walker: &mut Walker<I::Sample>, x: usize, dy: usize| {
            let Some(bins) = &self.entries else {
                self.start(walker, x, y0 + dy);
                return;
            };
            let x0 = x / TILE * TILE;
            let w = (x0 + TILE).min(self.width) - x0;
            if tile_x0 != x0 {
                let (origin, size) = ((x0, y0), (w, band_rows));
                bins.fill_tile(self.rays, origin, size, &mut lists, &mut frames);
                tile_x0 = x0;
            }
            let index = dy * w + x - x0;
            self.start_ray(walker, frames[index]);
            walker.use_entries(&lists[index]);
        };
        let mut slots: [(Walker<I::Sample>, usize); N] =
            std::array::from_fn(|_| (new_walker(), usize::MAX));
        let mut active = 0;
        for slot in &mut slots {
            if let Some((x, dy)) = pixels.next() {
                start(&mut slot.0, x, dy);
                slot.1 = dy * self.width + x;
                active += 1;
            }
        }
        // Each round takes every ray one step, stage by stage: the vertex
        // each ray leaves its cell against (or a BVH entry), the exits of
        // all rays at once, then classification, then the integration of
        // all the segments at once, then compositing. `live` has a bit per
        // ray. A ray's compositing and its next step's vertex are one pass
        // over the rays, as are its exit and classification (the same
        // order of stages for every ray, one loop fewer per round).
        const { assert!(N <= 32) };
        let mut batch = [SampledSegment::default(); N];
        let mut lights = [SegmentLight::CLEAR; N];
        // The frame's invariants, loaded once.
        let (scene, integrator, limits) = (self.scene, self.integrator, self.limits);
        let cells = Cells::of(scene);
        let mut lanes = Lanes::<N>::new();
        let wide = tetray_wide::token(self.wide);
        for (i, (walker, _)) in slots.iter_mut().enumerate() {
            walker.begin::<PREFETCH, N, _>(scene, cells, integrator, limits, &mut lanes, i);
        }
        while active > 0 {
            lanes.exits(wide);
            let mut live = 0;
            for (i, (walker, _)) in slots.iter_mut().enumerate() {
                let integrate = walker.leave(&mut lanes, i, integrator, &mut batch[i]);
                if PREFETCH {
                    walker.prefetch_next_apex(cells, &lanes, i);
                }
                live |= u32::from(integrate) << i;
            }
            integrator.segments(&batch, live, &mut lights, wide);
            for (i, (walker, index)) in slots.iter_mut().enumerate() {
                let light =
                    (live >> i & 1 != 0).then(|| (lights[i].emitted, lights[i].transmittance));
                if !walker.end(light, limits) && *index != usize::MAX {
                    stats.add(&walker.counters);
                    finish(walker, *index);
                    match pixels.next() {
                        Some((x, dy)) => {
                            start(walker, x, dy);
                            *index = dy * self.width + x;
                        }
                        None => {
                            *index = usize::MAX;
                            active -= 1;
                        }
                    }
                }
                walker.begin::<PREFETCH, N, _>(scene, cells, integrator, limits, &mut lanes, i);
            }
        }
        if let Some(progress) = self.progress {
            let done = self.rows_done.fetch_add(band_rows, Ordering::Relaxed) + band_rows;
            progress(done, self.height);
        }
        stats
    }
}

#[cfg(test)]
pub(crate) mod tests;
