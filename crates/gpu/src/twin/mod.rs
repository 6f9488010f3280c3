//! The CPU twin of the ray-casting kernel: the same inputs (the uploaded
//! arrays and `Params`), the same f32 operations in the same order, one
//! pixel at a time. Tests hold the GPU to it and it to the f64 reference
//! ray caster; where the GPU and the twin differ, it is the device's
//! arithmetic (fused multiply-adds, its exp), not the algorithm.

mod bvh;
pub mod integrate;
pub mod predicate;

use glam::{Vec3, Vec4};
use rayon::prelude::*;
use tetray_core::{Camera, Image};

use crate::GpuError;
use crate::layout::{Params, STAT_COUNT};
use crate::render::{GpuRenderOptions, frame_params};
use crate::upload::{IntegratorData, SceneData};
use bvh::{SKIP_MAX, Skip, face_entry, first_entry};
use integrate::{IntegratorInputs, sample_at, sample_near, segment_light};
use predicate::{Ray, crossing, crossing_from, edge_sign_of, edge_value, make_ray, project};
use tetray_scene::{OverlapCrossing, collect_crossings, line_meets_box, window_segments};

pub use integrate::{dawson, erfcx};

/// Everything the kernel reads.
pub struct Inputs<'a> {
    pub params: &'a Params,
    pub points: &'a [[f32; 4]],
    pub tets: &'a [[u32; 4]],
    pub bvh: &'a [[u32; 4]],
    pub integrator: IntegratorInputs<'a>,
}

impl<'a> Inputs<'a> {
    /// The buffers a frame binds: `params`, the scene's arrays and the
    /// integrator's tables.
    pub fn new(params: &'a Params, scene: &'a SceneData, integrator: &'a IntegratorData) -> Self {
        Inputs {
            params,
            points: &scene.points,
            tets: &scene.tets,
            bvh: &scene.bvh,
            integrator: IntegratorInputs::new(&params.integrator, integrator),
        }
    }

    fn point(&self, i: u32) -> Vec4 {
        Vec4::from_array(self.points[i as usize])
    }
}

/// Renders a frame as the kernel does (in parallel over rows).
pub fn render(
    scene: &SceneData,
    integrator: &IntegratorData,
    camera: &Camera,
    opts: &GpuRenderOptions,
) -> Result<(Image, [u64; STAT_COUNT]), GpuError> {
    render_traffic(scene, integrator, camera, opts).map(|(image, stats, _)| (image, stats))
}

/// [`render`], and the bytes the kernel reads from the mesh's arrays for
/// the frame.
pub fn render_traffic(
    scene: &SceneData,
    integrator: &IntegratorData,
    camera: &Camera,
    opts: &GpuRenderOptions,
) -> Result<(Image, [u64; STAT_COUNT], Traffic), GpuError> {
    let params = frame_params(&scene.layout(), integrator, camera, opts)?;
    let input = Inputs::new(&params, scene, integrator);
    let width = opts.width as usize;
    let mut rgba = vec![[0.0f32; 4]; width * opts.height as usize];
    let (stats, traffic) = rgba
        .par_chunks_mut(width)
        .enumerate()
        .map(|(py, row)| {
            let mut stats = [0u64; STAT_COUNT];
            let mut traffic = Traffic::default();
            for (px, out) in row.iter_mut().enumerate() {
                let (color, c) = cast_ray(&input, px as u32, py as u32);
                *out = color.to_array();
                for (total, value) in stats.iter_mut().zip(c.as_stats()) {
                    *total += value;
                }
                traffic = traffic.add(c.traffic);
            }
            (stats, traffic)
        })
        .reduce(
            || ([0u64; STAT_COUNT], Traffic::default()),
            |a, b| (std::array::from_fn(|i| a.0[i] + b.0[i]), a.1.add(b.1)),
        );
    let image = Image::from_pixels(opts.width, opts.height, rgba)?;
    Ok((image, stats, traffic))
}

/// One pixel of a frame, as the kernel casts it: premultiplied RGBA and
/// the pixel's counters (for inspecting a pixel).
pub fn trace_pixel(
    scene: &SceneData,
    integrator: &IntegratorData,
    camera: &Camera,
    opts: &GpuRenderOptions,
    x: u32,
    y: u32,
) -> Result<([f32; 4], [u64; STAT_COUNT]), GpuError> {
    let params = frame_params(&scene.layout(), integrator, camera, opts)?;
    let input = Inputs::new(&params, scene, integrator);
    let (color, counters) = cast_ray(&input, x, y);
    Ok((color.to_array(), counters.as_stats()))
}

const FACE_VERTS: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
const APEX_OTHERS: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
/// The kernel's exit table (checked against the CPU walk's in tests).
pub const APEX_EXITS: [[u32; 8]; 4] = [
    [
        0xffff, 0x0312, 0x0123, 0x0312, 0x0231, 0x0231, 0x0123, 0xffff,
    ],
    [
        0xffff, 0x0203, 0x0320, 0x0320, 0x0032, 0x0203, 0x0032, 0xffff,
    ],
    [
        0xffff, 0x0301, 0x0013, 0x0301, 0x0130, 0x0130, 0x0013, 0xffff,
    ],
    [
        0xffff, 0x0102, 0x0210, 0x0210, 0x0021, 0x0102, 0x0021, 0xffff,
    ],
];
const FAR: f32 = 3.4e38;
const REENTRY_REL: f32 = tetray_boundary_bvh::REENTRY_REL;
const NO_EXIT: u32 = 0xffff;

struct Cell {
    p: [Vec3; 4],
    s: Vec4,
    ids: [u32; 4],
}

/// A cell entered from the BVH: all four vertices loaded and projected.
fn load_cell(input: &Inputs, ray: &Ray, tet: u32, traffic: &mut Traffic) -> Cell {
    let v = input.tets[2 * tet as usize];
    traffic.tet_bytes += RECORD_BYTES;
    traffic.point_bytes += 4 * RECORD_BYTES;
    let mut cell = Cell {
        p: [Vec3::ZERO; 4],
        s: Vec4::ZERO,
        ids: v,
    };
    for (i, &vertex) in v.iter().enumerate() {
        let q = input.point(vertex);
        cell.p[i] = project(ray, q.truncate());
        cell.s[i] = q.w;
    }
    cell
}

/// The neighbour `tet` entered through its face `f_in` from `cell`: the
/// face's three vertices carried over from `cell` (the kernel's `carried`:
/// the last vertex with a matching id, vertex 0 when none), the apex loaded
/// and projected.
fn next_cell(
    input: &Inputs,
    ray: &Ray,
    cell: &Cell,
    tet: u32,
    f_in: usize,
    traffic: &mut Traffic,
) -> Cell {
    let v = input.tets[2 * tet as usize];
    let q = input.point(v[f_in]);
    traffic.tet_bytes += RECORD_BYTES;
    traffic.point_bytes += RECORD_BYTES;
    let mut next = Cell {
        p: [Vec3::ZERO; 4],
        s: Vec4::ZERO,
        ids: v,
    };
    for (i, &vertex) in v.iter().enumerate() {
        let (p, s) = if i == f_in {
            (project(ray, q.truncate()), q.w)
        } else {
            let k = (1..4).rev().find(|&k| cell.ids[k] == vertex).unwrap_or(0);
            (cell.p[k], cell.s[k])
        };
        next.p[i] = p;
        next.s[i] = s;
    }
    next
}

fn face_scalar(cell: &Cell, f: usize) -> f32 {
    let [a, b, c] = FACE_VERTS[f];
    let x = crossing(cell.p[a], cell.p[b], cell.p[c]);
    x.weights.dot(Vec3::new(cell.s[a], cell.s[b], cell.s[c]))
}

/// `(face, t, s)` of the exit, or `None` for a flat tetrahedron.
fn exit_cell(cell: &Cell, f_in: usize) -> Option<(usize, f32, f32)> {
    let apex = f_in;
    let pa = cell.p[apex];
    let mut e = [0.0f32; 4];
    let mut code = 0;
    for (i, &k) in APEX_OTHERS[apex].iter().enumerate() {
        let value = edge_value(pa, cell.p[k]);
        e[k] = value;
        if edge_sign_of(pa, cell.p[k], value) > 0 {
            code |= 1 << i;
        }
    }
    let packed = APEX_EXITS[apex][code];
    if packed == NO_EXIT {
        return None;
    }
    let (f, next, prev) = (
        (packed & 0xf) as usize,
        ((packed >> 4) & 0xf) as usize,
        ((packed >> 8) & 0xf) as usize,
    );
    let w = Vec3::new(edge_value(cell.p[next], cell.p[prev]), -e[prev], e[next]);
    let z = Vec3::new(pa.z, cell.p[next].z, cell.p[prev].z);
    let x = crossing_from(w, z);
    let s = x
        .weights
        .dot(Vec3::new(cell.s[apex], cell.s[next], cell.s[prev]));
    Some((f, x.t, s))
}

#[derive(Default)]
struct Counters {
    hit: u64,
    segments: u64,
    steps: u64,
    entries: u64,
    bound_hit: u64,
    failure: u64,
    overlap_segments: u64,
    overlap_overflow: u64,
    traffic: Traffic,
}

/// Bytes the kernel reads, counted at each of the twin's loads, which are
/// the kernel's one for one: in the walk, from the mesh's arrays (the
/// tetrahedra's vertex and neighbour records, the points); in the entry
/// queries, from the BVH array (nodes, leaf faces, the face-to-cell map)
/// and the points of the faces tested. The integrator's small tables are
/// not counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Traffic {
    pub tet_bytes: u64,
    pub point_bytes: u64,
    pub bvh_bytes: u64,
    pub bvh_point_bytes: u64,
    /// Entry queries made (the last, missing one of a ray included).
    pub bvh_queries: u64,
}

impl Traffic {
    /// Bytes read by the walk: tetrahedra and points.
    pub fn walk_bytes(&self) -> u64 {
        self.tet_bytes + self.point_bytes
    }

    /// Bytes read by the entry queries: BVH and the faces' points.
    pub fn entry_bytes(&self) -> u64 {
        self.bvh_bytes + self.bvh_point_bytes
    }

    fn add(self, other: Traffic) -> Traffic {
        Traffic {
            tet_bytes: self.tet_bytes + other.tet_bytes,
            point_bytes: self.point_bytes + other.point_bytes,
            bvh_bytes: self.bvh_bytes + other.bvh_bytes,
            bvh_point_bytes: self.bvh_point_bytes + other.bvh_point_bytes,
            bvh_queries: self.bvh_queries + other.bvh_queries,
        }
    }
}

/// One record of the tetrahedron, point or BVH array.
const RECORD_BYTES: u64 = 16;

impl Counters {
    /// In the order of the kernel's counter array (wide counters in `LO`).
    fn as_stats(&self) -> [u64; STAT_COUNT] {
        [
            self.hit,
            self.segments,
            0,
            self.steps,
            0,
            self.entries,
            self.bound_hit,
            self.failure,
            self.overlap_segments,
            self.overlap_overflow,
        ]
    }
}

/// The kernel's `find_holes`: the left-out tetrahedra the ray's line
/// crosses, the first `MAX_OVERLAP_CROSSINGS` (more marks an overflow).
fn find_holes(input: &Inputs, ray: &Ray, counters: &mut Counters) -> Vec<OverlapCrossing> {
    let p = input.params;
    let mut holes = Vec::new();
    if p.overlap_count == 0 {
        return holes;
    }
    let at = |i: u32| Vec4::from_array(input.bvh[i as usize].map(f32::from_bits)).truncate();
    let (lo, hi) = (at(p.overlap_offset), at(p.overlap_offset + 1));
    if !line_meets_box(lo, hi, ray.origin, ray.dir) {
        return holes;
    }
    let start = (p.overlap_offset + 2) as usize;
    let tets = &input.bvh[start..start + p.overlap_count as usize];
    let vertex = |id: u32| {
        let q = input.point(id);
        project(ray, q.truncate()).extend(q.w).to_array()
    };
    if collect_crossings(tets, vertex, &mut holes) {
        counters.overlap_overflow = 1;
    }
    holes
}

fn cast_ray(input: &Inputs, px: u32, py: u32) -> (Vec4, Counters) {
    let p = input.params;
    let v = &p.view;
    let x = (px as f32 + 0.5 - v.half_width) * v.pixel;
    let y = (v.half_height - (py as f32 + 0.5)) * v.pixel;
    let (right, up) = (Vec3::from_array(v.right), Vec3::from_array(v.up));
    let (position, direction) = (Vec3::from_array(v.position), Vec3::from_array(v.direction));
    let offset = right * x + up * y;
    let (ray, inside) = if v.orthographic == 1 {
        let ray = make_ray(position + offset, direction);
        let (lo, hi) = (
            Vec3::from_array(p.bounds_min),
            Vec3::from_array(p.bounds_max),
        );
        let inside = ray.origin.cmpge(lo).all() && ray.origin.cmple(hi).all();
        (ray, inside)
    } else {
        (make_ray(position, direction + offset), p.eye_inside == 1)
    };
    let mut t_cursor = if inside { -FAR } else { 0.0 };
    let mut color = Vec3::ZERO;
    let mut trans = Vec3::ONE;
    let mut counters = Counters::default();
    let mut skip = Skip::default();
    let mut skip_t = 0.0f32;
    let mut done = false;
    let mut entry_count = 0;
    let holes = find_holes(input, &ray, &mut counters);
    while entry_count < p.max_steps && !done {
        entry_count += 1;
        let t_query = if counters.entries > 0 {
            let o = ray.origin.abs();
            t_cursor - REENTRY_REL * (p.scene_abs_max + o.x.max(o.y).max(o.z))
        } else {
            t_cursor
        };
        let entry = first_entry(input, &ray, t_query, FAR, &skip, &mut counters.traffic);
        if !holes.is_empty() {
            let end = if entry.found { entry.t } else { FAR };
            let mut opaque = false;
            window_segments(&holes, t_cursor.max(0.0), end, |_, front, back, length| {
                if opaque {
                    return;
                }
                let (f, b) = (
                    sample_at(&input.integrator, front),
                    sample_at(&input.integrator, back),
                );
                let light = segment_light(&input.integrator, &f, &b, length);
                color += trans * light.emitted;
                trans *= light.transmittance;
                counters.overlap_segments += 1;
                opaque = trans.x + trans.y + trans.z <= p.stop_below_sum;
            });
            if opaque {
                break;
            }
        }
        if !entry.found {
            break;
        }
        counters.entries += 1;
        counters.hit = 1;
        if skip.len == 0 || entry.t != skip_t {
            skip.len = 0;
            skip_t = entry.t;
        }
        if skip.len < SKIP_MAX {
            skip.faces[skip.len] = entry.face;
            skip.len += 1;
        }
        let code = face_entry(input, entry.face, &mut counters.traffic);
        let mut tet = code >> 2;
        let mut f_in = (code & 3) as usize;
        let mut cell = load_cell(input, &ray, tet, &mut counters.traffic);
        let mut t_in = entry.t.max(t_cursor);
        let mut s_in = face_scalar(&cell, f_in);
        let mut sample_in = sample_at(&input.integrator, s_in);
        loop {
            counters.steps += 1;
            if counters.steps > u64::from(p.max_steps) {
                counters.bound_hit = 1;
                done = true;
                break;
            }
            let Some((f_out, t_exit, s_out)) = exit_cell(&cell, f_in) else {
                counters.failure = 1;
                done = true;
                break;
            };
            let t_out = t_exit.max(t_in);
            let sample_out = sample_near(&input.integrator, s_out, &sample_in);
            if t_out > t_in {
                skip.len = 0;
                if t_out > 0.0 {
                    let front = if t_in < 0.0 {
                        sample_at(
                            &input.integrator,
                            s_in + (s_out - s_in) * (-t_in / (t_out - t_in)),
                        )
                    } else {
                        sample_in
                    };
                    let light = segment_light(
                        &input.integrator,
                        &front,
                        &sample_out,
                        t_out - t_in.max(0.0),
                    );
                    color += trans * light.emitted;
                    trans *= light.transmittance;
                    counters.segments += 1;
                    if trans.x + trans.y + trans.z <= p.stop_below_sum {
                        done = true;
                        break;
                    }
                }
            }
            t_in = t_out;
            s_in = s_out;
            sample_in = sample_out;
            let next = input.tets[2 * tet as usize + 1][f_out];
            counters.traffic.tet_bytes += RECORD_BYTES;
            if next >= tetray_scene::FINAL_EXIT {
                done = next == tetray_scene::FINAL_EXIT && !holes.iter().any(|c| c.t_out > t_out);
                t_cursor = t_out;
                break;
            }
            tet = next >> 2;
            f_in = (next & 3) as usize;
            cell = next_cell(input, &ray, &cell, tet, f_in, &mut counters.traffic);
        }
    }
    let alpha = 1.0 - (trans.x + trans.y + trans.z) / 3.0;
    (color.extend(alpha), counters)
}
