//! Per-pixel entry lists: the boundary faces each pixel's ray enters the
//! mesh through, found once per frame by projecting the boundary faces onto
//! the screen (as Bunyk, Kaufman and Silva's ray caster, and VTK's after
//! it, find their rays' entries) instead of one BVH query per entry.
//!
//! The lists give the BVH's answers exactly: each candidate face is tested
//! against the pixel's own ray with the shared watertight predicate
//! ([`entry_distance`]), and a face is a candidate of every pixel whose
//! ray the predicate could see cross it (its screen box, widened by a
//! bound on the predicate's rounding). A query then takes the first face
//! of the pixel's list sorted by distance and face index that passes the
//! query's range and skip list: [`tetray_boundary_bvh::BoundaryBvh::first_entry`]'s
//! contract. Where that bound cannot be given (a perspective eye inside
//! the mesh's bounds, a face behind the eye), the frame keeps the BVH; so
//! does a pixel whose ray enters more than [`LIST_LEN`] faces.

use std::cmp::Ordering;

use glam::{DVec3, Vec3};
use rayon::prelude::*;
use tetray_boundary_bvh::EntryHit;
use tetray_core::watertight::{RayFrame, entry_distance};

use tetray_core::camera::PixelRays;
use tetray_scene::Scene;

/// Entries kept per pixel.
pub(crate) const LIST_LEN: usize = 8;

/// Candidate tests (one face against one pixel's ray, about 60
/// instructions; counted by the faces' widened boxes, an upper bound) per
/// pixel above which the lists may cost more than the BVH queries they
/// replace (about 1200 instructions each, 1.6 per pixel on the Blunt Fin):
/// such a frame keeps the BVH.
const MAX_TESTS_PER_PIXEL: usize = 24;

/// Pixels per boundary face below which a frame keeps the BVH: projecting
/// every face costs more than the queries save. How much a query costs
/// depends on whether the BVH stays in the caches, so there are two bounds,
/// by the bytes the queries read ([`BoundaryBvh::query_bytes`]) against
/// [`CACHED_BVH_BYTES`]. PPI, BVH against lists (alternating runs; frames'
/// minimum in ms, or M segments/s):
///
/// - A cached tree, one thread, best of 7 frames: the Blunt Fin (13 514
///   faces, 0.7 MB) at 64 x 64 (0.30 pixels per face) 2.6-2.8 against
///   2.8-2.9 ms; 72 x 72 (0.38) 3.4-3.7 against 3.4; 80 x 80 (0.47)
///   4.1-4.2 against 4.0; 96 x 96 (0.68) 5.7-6.2 against 5.4-5.5. The
///   200 k torus shell (26 784 faces, under 2 MiB) at 128 x 128 (0.61)
///   13.0-13.6 against 10.1-10.6 ms.
/// - Larger trees, two threads: the 1 M torus shell (88 944 faces) 128 x
///   128 (0.18) 36.2-38.3 against 38.2-41.5 M segments/s, 192 x 192
///   (0.41) 36.3-41.3 against 45.1-51.5; the 10 M shell (400 000 faces)
///   256 x 256 (0.16) 42.7-43.3 against 43.1-43.2, 512 x 512 (0.66)
///   50.6-53.7 against 58.9-64.6; the 40 M shell (1 000 224 faces) 256 x
///   256 (0.066) 34.3 against 33.9, 384 x 384 (0.15) 43.7-44.0 against
///   45.4-45.8, 512 x 512 (0.26) 50.0-50.3 against 53.4-53.9.
///
/// [`BoundaryBvh::query_bytes`]: tetray_boundary_bvh::BoundaryBvh::query_bytes
const MIN_PIXELS_PER_FACE: f64 = 0.4;
/// [`MIN_PIXELS_PER_FACE`] for a BVH of more than [`CACHED_BVH_BYTES`].
const MIN_PIXELS_PER_FACE_UNCACHED: f64 = 0.1;

/// Query bytes above which a BVH is taken not to stay in the caches
/// between one pixel's queries and the next's: a core's second-level cache
/// (1 to 2 MiB on current x86-64 processors).
const CACHED_BVH_BYTES: usize = 2 << 20;

/// Boundary faces projected per parallel job (fewer are not worth a
/// thread's start).
const FACES_PER_JOB: usize = 16_384;

/// Relative rounding of a point projected into a ray's frame (a few f32
/// operations on coordinates of the size of the scene), generously.
const PROJECTION_ROUNDING: f64 = 4e-7;

/// The boundary faces one pixel's ray enters, nearest first.
#[derive(Clone, Copy)]
pub(crate) struct EntryList {
    hits: [EntryHit; LIST_LEN],
    len: u8,
    /// More entries than fit, or a ray the lists do not answer for: the
    /// pixel asks the BVH.
    overflow: bool,
}

impl EntryList {
    pub const EMPTY: EntryList = EntryList {
        hits: [EntryHit { face: 0, t: 0.0 }; LIST_LEN],
        len: 0,
        overflow: false,
    };

    /// Whether the list holds every entry of its ray.
    pub fn is_complete(&self) -> bool {
        !self.overflow
    }

    fn insert(&mut self, hit: EntryHit) {
        let len = usize::from(self.len);
        if len == LIST_LEN {
            self.overflow = true;
            return;
        }
        let mut i = len;
        while i > 0 && hit.precedes(self.hits[i - 1]) {
            self.hits[i] = self.hits[i - 1];
            i -= 1;
        }
        self.hits[i] = hit;
        self.len += 1;
    }

    /// `BoundaryBvh::first_entry` for this list's ray: the nearest entry
    /// with `t_min <= t <= t_max` not in `skip`, ties to the lowest face.
    #[inline(always)]
    pub fn first_entry(&self, t_min: f32, t_max: f32, skip: &[u32]) -> Option<EntryHit> {
        if t_min.is_nan() || t_max.is_nan() {
            return None;
        }
        self.hits[..usize::from(self.len)]
            .iter()
            .find(|h| h.t >= t_min && h.t <= t_max && !skip.contains(&h.face))
            .copied()
    }
}

/// A boundary face that may be entered, with the pixels it may cover.
#[derive(Clone, Copy)]
struct ScreenFace {
    face: u32,
    tri: [Vec3; 3],
    /// Columns and rows (inclusive) of the pixels whose centres its
    /// widened screen box holds.
    x: [u32; 2],
    y: [u32; 2],
    /// The widened triangle's edges (see [`ScreenTri::edges`]).
    edges: Option<[[f64; 3]; 3]>,
}

impl ScreenFace {
    /// The columns of row `y` within `xs` whose pixel centres lie in the
    /// widened triangle.
    #[inline(always)]
    fn span(&self, y: usize, [x0, x1]: [usize; 2]) -> std::ops::Range<usize> {
        let (mut lo, mut hi) = (x0 as f64, x1 as f64);
        if let Some(edges) = &self.edges {
            let y = y as f64;
            for [a, b, c] in edges {
                // a x + b y + c >= 0.
                let rest = b * y + c;
                if *a > 0.0 {
                    lo = lo.max((-rest / a).ceil());
                } else if *a < 0.0 {
                    hi = hi.min((-rest / a).floor());
                } else if rest < 0.0 {
                    return 0..0;
                }
            }
        }
        if lo > hi {
            return 0..0;
        }
        lo as usize..hi as usize + 1
    }
}

/// A face's place on the screen, widened by the predicate's rounding.
struct ScreenTri {
    /// `[x0, x1, y0, y1]`: the pixel centres of the widened box.
    bounds: [f64; 4],
    /// The triangle's edge lines `a x + b y + c = 0`, moved outwards by
    /// the widening, inside positive; `None` for a triangle too thin to
    /// orient, which keeps its box.
    edges: Option<[[f64; 3]; 3]>,
}

/// A frame's enterable boundary faces, binned by square screen tile.
pub(crate) struct EntryBins {
    tile: usize,
    tiles_x: usize,
    /// Per tile, its range of `refs`.
    starts: Vec<u32>,
    /// Indices into `faces`, tile by tile.
    refs: Vec<u32>,
    faces: Vec<ScreenFace>,
    /// Whether [`EntryBins::fill_tile`] runs the x86-64-v3 build.
    wide: bool,
}

impl EntryBins {
    /// The bins of a `width x height` frame of `rays` in `tile x tile`
    /// tiles, projected and filled in the x86-64-v3 build where `wide`
    /// (see [`tetray_wide::run`]), or `None` where the frame keeps the
    /// BVH: a perspective eye inside the mesh's bounds (`eye_inside`) or
    /// not in front of every boundary face, or more candidate tests than
    /// the queries would cost.
    pub fn new(
        scene: &Scene,
        rays: &PixelRays,
        (width, height): (usize, usize),
        eye_inside: bool,
        tile: usize,
        wide: bool,
    ) -> Option<EntryBins> {
        let ortho = rays.is_orthographic();
        let bvh = &scene.bvh;
        let face_count = bvh.face_count();
        let min_pixels_per_face = if bvh.query_bytes() > CACHED_BVH_BYTES {
            MIN_PIXELS_PER_FACE_UNCACHED
        } else {
            MIN_PIXELS_PER_FACE
        };
        if (eye_inside && !ortho)
            || ((width * height) as f64) < min_pixels_per_face * face_count as f64
        {
            return None;
        }
        let screen = Screen::new(rays);
        let (w, h) = (width as f64 - 1.0, height as f64 - 1.0);
        // Only the faces that may cover a pixel centre are kept (at less
        // than a pixel per face, most cover none), read in the BVH's leaf
        // order (one array, faces near in space near in memory) and
        // projected a job at a time in the wide build; a face the frame
        // cannot bound ends the collection.
        let jobs: Option<Vec<Vec<ScreenFace>>> = (0..face_count.div_ceil(FACES_PER_JOB))
            .into_par_iter()
            .map(|job| {
                let start = job * FACES_PER_JOB;
                let end = (start + FACES_PER_JOB).min(face_count);
                tetray_wide::run(
                    wide,
                    #[inline(always)]
                    || {
                        // Room for every face of the job: the pages of the
                        // part left unused are never touched.
                        let mut kept = Vec::with_capacity(end - start);
                        for i in start..end {
                            let (face, tri) = bvh.face_in_leaf_order(i);
                            match screen.face(face, tri, (w, h)) {
                                Some(Some(face)) => kept.push(face),
                                Some(None) => {}
                                None => return None,
                            }
                        }
                        Some(kept)
                    },
                )
            })
            .collect();
        let mut jobs = jobs?;
        let faces = if jobs.len() == 1 {
            jobs.pop().unwrap_or_default()
        } else {
            jobs.concat()
        };
        let tests: usize = (faces.iter())
            .map(|f| (f.x[1] - f.x[0] + 1) as usize * (f.y[1] - f.y[0] + 1) as usize)
            .sum();
        if tests > MAX_TESTS_PER_PIXEL * width * height {
            return None;
        }
        Some(EntryBins::bin(faces, width, height, tile, wide))
    }

    /// Sorts the faces into the tiles their pixel ranges meet.
    fn bin(
        faces: Vec<ScreenFace>,
        width: usize,
        height: usize,
        tile: usize,
        wide: bool,
    ) -> EntryBins {
        let tiles_x = width.div_ceil(tile);
        let tiles = tiles_x * height.div_ceil(tile);
        let tiles_of = |f: &ScreenFace| {
            let (tx, ty) = (
                f.x.map(|v| v as usize / tile),
                f.y.map(|v| v as usize / tile),
            );
            (ty[0]..=ty[1]).flat_map(move |ty| (tx[0]..=tx[1]).map(move |tx| ty * tiles_x + tx))
        };
        let mut counts = vec![0u32; tiles + 1];
        for f in &faces {
            for t in tiles_of(f) {
                counts[t + 1] += 1;
            }
        }
        for t in 0..tiles {
            counts[t + 1] += counts[t];
        }
        let mut fill = counts.clone();
        let mut refs = vec![0u32; counts[tiles] as usize];
        for (i, f) in (0u32..).zip(&faces) {
            for t in tiles_of(f) {
                refs[fill[t] as usize] = i;
                fill[t] += 1;
            }
        }
        EntryBins {
            tile,
            tiles_x,
            starts: counts,
            refs,
            faces,
            wide,
        }
    }

    /// The lists of the pixels `x0..x0 + w` by `y0..y0 + h` of one tile
    /// (`x0`, `y0` multiples of the tile size), row by row into `lists`.
    /// `frames` receives the pixels' rays, in the same order.
    #[inline(never)]
    pub fn fill_tile(
        &self,
        rays: &PixelRays,
        (x0, y0): (usize, usize),
        (w, h): (usize, usize),
        lists: &mut Vec<EntryList>,
        frames: &mut Vec<RayFrame>,
    ) {
        // The body as a closure inlined into the build `run` picks.
        tetray_wide::run(
            self.wide,
            #[inline(always)]
            || {
                lists.clear();
                lists.resize(w * h, EntryList::EMPTY);
                frames.clear();
                for y in y0..y0 + h {
                    for x in x0..x0 + w {
                        let ray = rays.ray(x as u32, y as u32);
                        if !(ray.origin.is_finite() && ray.dir.is_finite()) {
                            lists[frames.len()].overflow = true;
                        }
                        frames.push(ray);
                    }
                }
                let tile = (y0 / self.tile) * self.tiles_x + x0 / self.tile;
                let refs = &self.refs[self.starts[tile] as usize..self.starts[tile + 1] as usize];
                for &i in refs {
                    let f = &self.faces[i as usize];
                    let xs = [(f.x[0] as usize).max(x0), (f.x[1] as usize).min(x0 + w - 1)];
                    for y in (f.y[0] as usize).max(y0)..=(f.y[1] as usize).min(y0 + h - 1) {
                        for x in f.span(y, xs) {
                            let index = (y - y0) * w + (x - x0);
                            let ray = &frames[index];
                            let [a, b, c] = f.tri.map(|p| ray.project(p));
                            if let Some(t) = entry_distance(a, b, c) {
                                lists[index].insert(EntryHit { face: f.face, t });
                            }
                        }
                    }
                }
            },
        );
    }
}

/// The frame's projection onto pixel coordinates (the centre of pixel
/// `(px, py)` at `(px, py)`), and bounds on the watertight predicate's
/// rounding in those coordinates.
struct Screen {
    ortho: bool,
    eye: DVec3,
    right: DVec3,
    up: DVec3,
    direction: DVec3,
    pixel: f64,
    half: (f64, f64),
    /// Size of the coordinates the rays' origins are made from.
    eye_scale: f64,
}

impl Screen {
    fn new(rays: &PixelRays) -> Screen {
        let basis = rays.basis();
        let (hw, hh) = rays.half_size();
        let pixel = f64::from(rays.pixel_size());
        let eye = rays.position().as_dvec3();
        let ortho = rays.is_orthographic();
        // Orthographic rays start off the position by up to half the view.
        let offset = if ortho {
            (f64::from(hw) + f64::from(hh)) * pixel
        } else {
            0.0
        };
        Screen {
            ortho,
            eye,
            right: basis.right.as_dvec3(),
            up: basis.up.as_dvec3(),
            direction: basis.direction.as_dvec3(),
            pixel,
            half: (f64::from(hw), f64::from(hh)),
            eye_scale: eye.abs().max_element() + offset,
        }
    }

    /// Boundary face `face` with points `tri` on the screen, as
    /// [`Screen::face_box`] answers for it: `None` where the frame cannot
    /// bound the face, `Some(None)` where no pixel's ray enters it.
    #[inline(always)]
    fn face(&self, face: u32, tri: [Vec3; 3], (w, h): (f64, f64)) -> Option<Option<ScreenFace>> {
        let screen_tri = self.face_box(tri.map(|p| p.as_dvec3()), (w, h))?;
        Some(screen_tri.map(|ScreenTri { bounds, edges }| {
            let [x0, x1, y0, y1] = bounds;
            ScreenFace {
                face,
                tri,
                x: [x0, x1].map(|v| v.clamp(0.0, w) as u32),
                y: [y0, y1].map(|v| v.clamp(0.0, h) as u32),
                edges,
            }
        }))
    }

    /// The widened box `[x0, x1, y0, y1]` (pixel coordinates, rounded
    /// inwards to pixel centres) of a face that may be entered by the ray
    /// of a pixel centre `(0..=w, 0..=h)`; `Some(None)` for a face no such
    /// ray can enter; `None` when the frame cannot bound the face (a vertex
    /// not in front of a perspective eye).
    #[inline(always)]
    fn face_box(&self, [a, b, c]: [DVec3; 3], (w, h): (f64, f64)) -> Option<Option<ScreenTri>> {
        let rel = [a, b, c].map(|p| p - self.eye);
        let depth = rel.map(|d| d.dot(self.direction));
        if !self.ortho
            && depth
                .iter()
                .any(|&z| z.partial_cmp(&0.0) != Some(Ordering::Greater))
        {
            return None;
        }
        // A projected coordinate is off by at most `delta` (world units)
        // in the ray's frame, which moves an edge's sign by at most
        // `delta` times the edge's length.
        let scale = [a, b, c]
            .map(|p| p.abs().max_element())
            .into_iter()
            .fold(0.0, f64::max);
        let delta = PROJECTION_ROUNDING * (scale + self.eye_scale);
        // Bounds from above (cheaper than the lengths): the margins only
        // grow with them.
        let norm1 = |v: DVec3| v.abs().element_sum();
        let perimeter = norm1(b - a) + norm1(c - b) + norm1(a - c);
        // Entered only against its outward normal: a face seen from behind
        // by every ray, by more than rounding can turn, is dropped. For a
        // perspective eye `n . (p - eye)` is the same at every point of the
        // face's plane, and a ray's cosine to the normal is that over the
        // point's distance.
        let n = (b - a).cross(c - a);
        let facing = if self.ortho {
            n.dot(self.direction)
        } else {
            n.dot(rel[0]) / rel.map(norm1).into_iter().fold(0.0, f64::max)
        };
        if facing > 64.0 * delta * perimeter {
            return Some(None);
        }
        let (hw, hh) = self.half;
        let (mut sx, mut sy) = ([0.0; 3], [0.0; 3]);
        for (i, d) in rel.iter().enumerate() {
            let (x, y) = if self.ortho {
                (d.dot(self.right), d.dot(self.up))
            } else {
                (d.dot(self.right) / depth[i], d.dot(self.up) / depth[i])
            };
            sx[i] = x / self.pixel + hw - 0.5;
            sy[i] = hh - 0.5 - y / self.pixel;
        }
        // The predicate's edge can sit `delta` off the true one, seen from
        // the nearest vertex's depth, and a pixel's ray direction is
        // rounded by a few units in the last place of its size.
        let angle = if self.ortho {
            8.0 * delta
        } else {
            let near = depth.into_iter().fold(f64::INFINITY, f64::min);
            8.0 * delta / near + 1e-6 * (1.0 + (hw + hh) * self.pixel)
        };
        let pad = 0.01 + angle / self.pixel;
        let min = |v: [f64; 3]| v.into_iter().fold(f64::INFINITY, f64::min);
        let max = |v: [f64; 3]| v.into_iter().fold(f64::NEG_INFINITY, f64::max);
        let bounds = [
            (min(sx) - pad).ceil(),
            (max(sx) + pad).floor(),
            (min(sy) - pad).ceil(),
            (max(sy) + pad).floor(),
        ];
        let [x0, x1, y0, y1] = bounds;
        if x0 > x1 || y0 > y1 || x1 < 0.0 || y1 < 0.0 || x0 > w || y0 > h {
            return Some(None);
        }
        Some(Some(ScreenTri {
            bounds,
            edges: widened_edges(sx, sy, pad),
        }))
    }
}

/// The edge lines of the screen triangle `(sx, sy)`, each moved `pad`
/// outwards, as `a x + b y + c >= 0` inside: every point within `pad` of
/// the triangle passes all three. `None` for a triangle whose orientation
/// is not clear of the lines' own rounding.
#[inline(always)]
fn widened_edges(sx: [f64; 3], sy: [f64; 3], pad: f64) -> Option<[[f64; 3]; 3]> {
    let area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
    let size = (0..3)
        .map(|i| sx[i].abs().max(sy[i].abs()))
        .fold(1.0, f64::max);
    // Far off-screen vertices (a perspective vertex near the eye's plane)
    // make lines whose evaluation rounds by more than the widening.
    let thin = area.abs().partial_cmp(&(1e-9 * size * size)) != Some(Ordering::Greater);
    if size > 1e9 || thin {
        return None;
    }
    let orient = area.signum();
    Some(std::array::from_fn(|i| {
        let j = (i + 1) % 3;
        // Inside is to the left of i -> j for a positive area.
        let (a, b) = (orient * (sy[i] - sy[j]), orient * (sx[j] - sx[i]));
        let c = -(a * sx[i] + b * sy[i]);
        let len = a.abs() + b.abs();
        [a, b, c + pad * len]
    }))
}

#[cfg(test)]
mod tests;
