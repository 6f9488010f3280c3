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
/// - A cached tree: the Blunt Fin (13 514 faces, 0.7 MB), best of 7 frames,
///   one thread: 64 x 64 (0.30 pixels per face) 2.8-2.9 against
///   3.3-3.4 ms; 96 x 96 (0.68) 5.8-6.1 against 5.9; 128 x 128 (1.2)
///   10.2-10.6 against 9.7-9.8.
/// - Larger trees, two threads: the 1 M torus shell (88 944 faces) 128 x
///   128 (0.18) 36.2-38.3 against 38.2-41.5 M segments/s, 192 x 192
///   (0.41) 36.3-41.3 against 45.1-51.5; the 10 M shell (400 000 faces)
///   256 x 256 (0.16) 42.7-43.3 against 43.1-43.2, 512 x 512 (0.66)
///   50.6-53.7 against 58.9-64.6; the 40 M shell (1 000 224 faces) 256 x
///   256 (0.066) 34.3 against 33.9, 384 x 384 (0.15) 43.7-44.0 against
///   45.4-45.8, 512 x 512 (0.26) 50.0-50.3 against 53.4-53.9.
///
/// [`BoundaryBvh::query_bytes`]: tetray_boundary_bvh::BoundaryBvh::query_bytes
const MIN_PIXELS_PER_FACE: f64 = 0.7;
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
}

impl EntryBins {
    /// The bins of a `width x height` frame of `rays` in `tile x tile`
    /// tiles, or `None` where the frame keeps the BVH: a perspective eye
    /// inside the mesh's bounds (`eye_inside`) or not in front of every
    /// boundary face, or more candidate tests than the queries would cost.
    pub fn new(
        scene: &Scene,
        rays: &PixelRays,
        width: usize,
        height: usize,
        eye_inside: bool,
        tile: usize,
    ) -> Option<EntryBins> {
        let ortho = rays.is_orthographic();
        let face_count = scene.topology.boundary_faces.len() as f64;
        let min_pixels_per_face = if scene.bvh.query_bytes() > CACHED_BVH_BYTES {
            MIN_PIXELS_PER_FACE_UNCACHED
        } else {
            MIN_PIXELS_PER_FACE
        };
        if (eye_inside && !ortho) || ((width * height) as f64) < min_pixels_per_face * face_count {
            return None;
        }
        let screen = Screen::new(rays);
        let points = &scene.mesh.points;
        let (w, h) = (width as f64 - 1.0, height as f64 - 1.0);
        // Only the faces that may cover a pixel centre are kept (at less
        // than a pixel per face, most cover none), collected straight into
        // one vector; a face the frame cannot bound ends the collection.
        let faces: Option<Vec<ScreenFace>> = (scene.topology.boundary_faces)
            .par_iter()
            .with_min_len(FACES_PER_JOB)
            .enumerate()
            .filter_map(|(face, bf)| {
                let tri = bf.vertices.map(|v| points[v as usize]);
                let Some(screen_tri) = screen.face_box(tri.map(|p| p.as_dvec3())) else {
                    return Some(None);
                };
                let ScreenTri { bounds, edges } = screen_tri?;
                let [x0, x1, y0, y1] = bounds;
                if x0 > x1 || y0 > y1 || x1 < 0.0 || y1 < 0.0 || x0 > w || y0 > h {
                    return None;
                }
                Some(Some(ScreenFace {
                    face: face as u32,
                    tri,
                    x: [x0, x1].map(|v| v.clamp(0.0, w) as u32),
                    y: [y0, y1].map(|v| v.clamp(0.0, h) as u32),
                    edges,
                }))
            })
            .collect();
        let faces = faces?;
        let tests: usize = (faces.iter())
            .map(|f| (f.x[1] - f.x[0] + 1) as usize * (f.y[1] - f.y[0] + 1) as usize)
            .sum();
        if tests > MAX_TESTS_PER_PIXEL * width * height {
            return None;
        }
        Some(EntryBins::bin(faces, width, height, tile))
    }

    /// Sorts the faces into the tiles their pixel ranges meet.
    fn bin(faces: Vec<ScreenFace>, width: usize, height: usize, tile: usize) -> EntryBins {
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

    /// The widened box `[x0, x1, y0, y1]` (pixel coordinates, rounded
    /// inwards to pixel centres) of a face that may be entered; `Some(None)`
    /// for a face no ray of the frame can enter; `None` when the frame
    /// cannot bound the face (a vertex not in front of a perspective eye).
    fn face_box(&self, [a, b, c]: [DVec3; 3]) -> Option<Option<ScreenTri>> {
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
mod tests {
    use glam::Vec3;
    use tetray_boundary_bvh::{EntryHit, brute_force_first_entry, reentry_start};
    use tetray_core::watertight::{RayFrame, cross_triangle};
    use tetray_mesh::Topology;

    use super::*;
    use tetray_core::camera::Camera;
    use tetray_mesh::synthetic::{CellSplit, add_field, box_grid, hollow_box, jittered_box, merge};

    fn scene(mut mesh: tetray_mesh::TetMesh) -> Scene {
        add_field(
            &mut mesh,
            "s",
            tetray_mesh::synthetic::ScalarSpec::Constant(1.0),
        );
        let topology = Topology::build(&mesh).unwrap();
        Scene::new(mesh, topology, "s", Default::default()).unwrap()
    }

    /// A holed jittered box and, beside it, a row of ten small boxes along
    /// z (rays along z enter more faces than a list holds).
    fn scenes() -> Vec<Scene> {
        let (lo, hi) = (Vec3::ZERO, Vec3::ONE);
        let holed = hollow_box(lo, hi, [4, 4, 4], [1, 1, 1], [3, 3, 3], CellSplit::Five).unwrap();
        let mut row = jittered_box(lo, hi, [3, 4, 3], 0.2, 7, CellSplit::Six).unwrap();
        for k in 0..10 {
            let z = 1.2 + 0.15 * k as f32;
            let b = Vec3::new(0.3, 0.3, z);
            let cube = box_grid(b, b + Vec3::new(0.4, 0.4, 0.1), [1, 1, 1], CellSplit::Five);
            row = merge(row, cube.unwrap()).unwrap();
        }
        vec![scene(holed), scene(row)]
    }

    /// Views from outside: oblique, zoomed in (pixels of 1e-4 radians),
    /// along an axis with pixel centres on grid lines (perspective and
    /// orthographic), and orthographic with its view plane through the
    /// mesh (rays starting inside).
    fn cameras(scene: &Scene) -> Vec<Camera> {
        let (lo, hi) = scene.bounds();
        let mut oblique = Camera::reset_to_bounds(lo, hi).unwrap();
        oblique.azimuth(30.0).unwrap();
        oblique.elevation(20.0).unwrap();
        oblique.orthogonalize_view_up().unwrap();
        let mut zoomed = oblique;
        zoomed.zoom(300.0).unwrap();
        let centre = (lo + hi) * 0.5;
        let axis = Camera {
            position: Vec3::new(0.5, 0.5, -3.0),
            focal_point: Vec3::new(0.5, 0.5, 0.0),
            view_up: Vec3::Y,
            ..oblique
        };
        let axis_ortho = Camera {
            parallel_scale: Some(0.75),
            ..axis
        };
        let through = Camera {
            position: centre - oblique.basis().unwrap().direction * 0.01,
            parallel_scale: Some(1.5),
            ..oblique
        };
        vec![oblique, zoomed, axis, axis_ortho, through]
    }

    /// Every entering crossing of `ray`, in the lists' order.
    fn all_entries(scene: &Scene, ray: &RayFrame) -> Vec<EntryHit> {
        let mut all: Vec<EntryHit> = (0u32..)
            .zip(&scene.topology.boundary_faces)
            .filter_map(|(face, bf)| {
                let [a, b, c] = bf
                    .vertices
                    .map(|v| ray.project(scene.mesh.points[v as usize]));
                let crossing = cross_triangle(a, b, c)?;
                crossing.entering.then_some(EntryHit {
                    face,
                    t: crossing.t,
                })
            })
            .collect();
        all.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.face.cmp(&b.face)));
        all
    }

    /// Each pixel's list holds exactly the entries of its ray (or says it
    /// overflowed, when there are more), and answers the queries a walk
    /// makes (from the start, from each entry, from each re-entry start,
    /// skipping the faces entered there) as the brute-force scan does.
    #[test]
    fn lists_answer_as_the_brute_force_scan() {
        let (width, height) = (33, 24);
        let (mut lists, mut frames) = (Vec::new(), Vec::new());
        let (mut pixels, mut overflowed, mut reentering) = (0, 0, 0);
        for scene in scenes() {
            for camera in cameras(&scene) {
                let rays = camera.pixel_rays(width as u32, height as u32).unwrap();
                let bins = EntryBins::new(&scene, &rays, width, height, false, 8).unwrap();
                for (y0, x0) in (0..height)
                    .step_by(8)
                    .flat_map(|y| (0..width).step_by(8).map(move |x| (y, x)))
                {
                    let size = ((x0 + 8).min(width) - x0, (y0 + 8).min(height) - y0);
                    bins.fill_tile(&rays, (x0, y0), size, &mut lists, &mut frames);
                    for (list, ray) in lists.iter().zip(&frames) {
                        pixels += 1;
                        let all = all_entries(&scene, ray);
                        if !list.is_complete() {
                            assert!(all.len() > LIST_LEN);
                            overflowed += 1;
                            continue;
                        }
                        assert_eq!(&list.hits[..usize::from(list.len)], &all[..]);
                        reentering += usize::from(all.len() > 1);
                        let abs_max = scene.bvh.scene_abs_max();
                        let mut starts = vec![f32::NEG_INFINITY, 0.0];
                        for h in &all {
                            starts.extend([h.t, reentry_start(ray, h.t, abs_max)]);
                        }
                        for &t_min in &starts {
                            for skip in [vec![]].into_iter().chain(all.iter().map(|h| vec![h.face]))
                            {
                                let want = brute_force_first_entry(
                                    &scene.mesh,
                                    &scene.topology,
                                    ray,
                                    t_min,
                                    f32::INFINITY,
                                    &skip,
                                );
                                assert_eq!(list.first_entry(t_min, f32::INFINITY, &skip), want);
                            }
                        }
                        assert_eq!(list.first_entry(f32::NAN, f32::INFINITY, &[]), None);
                    }
                }
            }
        }
        // Both paths ran, and many rays came back after leaving.
        assert!(
            overflowed > 20 && reentering > pixels / 8,
            "{overflowed} {reentering} {pixels}"
        );
    }

    /// A perspective eye inside the mesh's bounds sees faces behind it:
    /// the frame keeps the BVH.
    #[test]
    fn an_eye_inside_keeps_the_bvh() {
        let scene = &scenes()[0];
        let camera = Camera {
            position: Vec3::new(0.5, 0.5, 0.1),
            ..cameras(scene)[0]
        };
        let rays = camera.pixel_rays(16, 16).unwrap();
        assert!(EntryBins::new(scene, &rays, 16, 16, true, 8).is_none());
    }
}
