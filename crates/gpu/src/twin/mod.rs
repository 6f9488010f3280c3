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
use crate::upload::{IntegratorData, SceneData, TET_WORDS};
use bvh::{SKIP_MAX, Skip, face_entry, first_entry};
use integrate::{IntegratorInputs, sample_at, sample_near, segment_light};
use predicate::{Ray, crossing, crossing_from, edge_sign_of, edge_value, make_ray, project};
use tetray_scene::{OverlapCrossing, collect_crossings, line_meets_box, window_segments};

pub use integrate::{dawson, erfcx};

/// Everything the kernel reads.
pub struct Inputs<'a> {
    pub params: &'a Params,
    pub points: &'a [[f32; 4]],
    pub tets: &'a [u32],
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

/// The kernel's exit table (checked against the CPU walk's in tests): for
/// the signs of the edges apex -> face slot `i` (bit `i` set when
/// positive), the slot the exit face leaves out, or 3 for none.
pub const LEFT_OUT_SLOT: [u32; 8] = [3, 2, 0, 0, 1, 2, 1, 3];
const FAR: f32 = 3.4e38;
const REENTRY_REL: f32 = tetray_boundary_bvh::REENTRY_REL;

/// The kernel's `Face`: the face the ray entered its current cell
/// through, projected (`p`), with scalars (`s`) and point indices, in the
/// cyclic order in which every edge is positive.
struct Face {
    p: [Vec3; 3],
    s: [f32; 3],
    ids: [u32; 3],
}

/// The kernel's `load_vertex`.
fn load_vertex(input: &Inputs, ray: &Ray, id: u32, traffic: &mut Traffic) -> (Vec3, f32) {
    traffic.point_bytes += RECORD_BYTES;
    let q = input.point(id);
    (project(ray, q.truncate()), q.w)
}

/// The kernel's `enter_face`: the face `ids` (all edges negative) reversed,
/// and the scalar where the ray crosses it.
fn enter_face(input: &Inputs, ray: &Ray, ids: [u32; 3], traffic: &mut Traffic) -> (Face, f32) {
    let [a, b, c] = ids.map(|id| load_vertex(input, ray, id, traffic));
    let x = crossing(a.0, b.0, c.0);
    let s = x.weights.dot(Vec3::new(a.1, b.1, c.1));
    let face = Face {
        p: [a.0, c.0, b.0],
        s: [a.1, c.1, b.1],
        ids: [ids[0], ids[2], ids[1]],
    };
    (face, s)
}

/// The kernel's `tet_word`.
fn tet_word(input: &Inputs, tet: u32, word: usize, traffic: &mut Traffic) -> u32 {
    traffic.tet_bytes += 4;
    input.tets[TET_WORDS * tet as usize + word]
}

/// The kernel's `rank_of`.
fn rank_of(face: &Face, apex: u32, id: u32) -> usize {
    face.ids.iter().filter(|&&v| v < id).count() + usize::from(apex < id)
}

/// The kernel's `exit_face`: `(rank of the left-out vertex, t, s)` of the
/// exit, or `None` for a flat tetrahedron; the exit face becomes `face`.
fn exit_face(face: &mut Face, apex: u32, pa: Vec3, sa: f32) -> Option<(usize, f32, f32)> {
    let mut e = [0.0f32; 3];
    let mut code = 0;
    for (i, &p) in face.p.iter().enumerate() {
        e[i] = edge_value(pa, p);
        if edge_sign_of(pa, p, e[i]) > 0 {
            code |= 1 << i;
        }
    }
    let k = LEFT_OUT_SLOT[code] as usize;
    if k == 3 {
        return None;
    }
    let (next, prev) = ((k + 1) % 3, (k + 2) % 3);
    let (pn, pp) = (face.p[next], face.p[prev]);
    let w = Vec3::new(edge_value(pn, pp), -e[prev], e[next]);
    let x = crossing_from(w, Vec3::new(pa.z, pn.z, pp.z));
    let s = x.weights.dot(Vec3::new(sa, face.s[next], face.s[prev]));
    let rank = rank_of(face, apex, face.ids[k]);
    face.p[k] = pa;
    face.s[k] = sa;
    face.ids[k] = apex;
    Some((rank, x.t, s))
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
/// words of the tetrahedra's records, the points); in the entry
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

/// One record of the point or BVH array.
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
        let mut tet = face_entry(input, entry.face, &mut counters.traffic) >> 2;
        let (mut face, mut s_in) = enter_face(input, &ray, entry.ids, &mut counters.traffic);
        let mut t_in = entry.t.max(t_cursor);
        let mut sample_in = sample_at(&input.integrator, s_in);
        loop {
            counters.steps += 1;
            if counters.steps > u64::from(p.max_steps) {
                counters.bound_hit = 1;
                done = true;
                break;
            }
            let apex = tet_word(input, tet, 0, &mut counters.traffic)
                ^ face.ids[0]
                ^ face.ids[1]
                ^ face.ids[2];
            let (pa, sa) = load_vertex(input, &ray, apex, &mut counters.traffic);
            let Some((rank, t_exit, s_out)) = exit_face(&mut face, apex, pa, sa) else {
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
            let next = tet_word(input, tet, 1 + rank, &mut counters.traffic);
            if next >= tetray_scene::FINAL_EXIT {
                done = next == tetray_scene::FINAL_EXIT && !holes.iter().any(|c| c.t_out > t_out);
                t_cursor = t_out;
                break;
            }
            tet = next;
        }
    }
    let alpha = 1.0 - (trans.x + trans.y + trans.z) / 3.0;
    (color.extend(alpha), counters)
}
