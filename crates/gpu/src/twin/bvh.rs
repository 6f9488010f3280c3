//! Twin of shaders/bvh.wgsl: nearest-first traversal of the flattened
//! boundary BVH with padded, inclusive slab tests.

use glam::{UVec3, Vec3};

use super::predicate::{Ray, crossing, edge_sign, project};
use super::{Inputs, RECORD_BYTES, Traffic};

const STACK_SIZE: usize = 64;
const PAD_REL: f32 = 1.525_878_9e-5;
pub const SKIP_MAX: usize = 8;

struct Slab {
    origin_plus_pad: Vec3,
    origin_minus_pad: Vec3,
    inv_dir: Vec3,
    parallel: UVec3,
}

fn make_slab(ray: &Ray, scene_abs_max: f32) -> Slab {
    let o = ray.origin;
    let pad = PAD_REL * (scene_abs_max + o.x.abs().max(o.y.abs()).max(o.z.abs()));
    let inv = Vec3::ONE / ray.dir;
    let finite = |x: f32| x.abs() <= f32::MAX;
    let mut parallel = UVec3::ZERO;
    let mut inv_dir = Vec3::ZERO;
    for axis in 0..3 {
        if finite(inv[axis]) {
            inv_dir[axis] = inv[axis];
        } else {
            parallel[axis] = 1;
        }
    }
    Slab {
        origin_plus_pad: o + Vec3::splat(pad),
        origin_minus_pad: o - Vec3::splat(pad),
        inv_dir,
        parallel,
    }
}

fn slab_entry(slab: &Slab, bmin: Vec3, bmax: Vec3, t_lo: f32, t_hi: f32) -> Option<f32> {
    let (mut near, mut far) = (t_lo, t_hi);
    for axis in 0..3 {
        if slab.parallel[axis] == 1 {
            if !(bmin[axis] <= slab.origin_plus_pad[axis]
                && slab.origin_minus_pad[axis] <= bmax[axis])
            {
                return None;
            }
        } else {
            let t0 = (bmin[axis] - slab.origin_plus_pad[axis]) * slab.inv_dir[axis];
            let t1 = (bmax[axis] - slab.origin_minus_pad[axis]) * slab.inv_dir[axis];
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
    }
    (near <= far).then_some(near)
}

/// Node `i`'s two records: its bounds, and in their fourth words its link
/// (first child, or first face slot) and face count (0 for an inner node).
struct Node {
    min: Vec3,
    max: Vec3,
    link: u32,
    count: u32,
}

fn load_node(input: &Inputs, i: u32, traffic: &mut Traffic) -> Node {
    let head = input.bvh[2 * i as usize];
    let tail = input.bvh[2 * i as usize + 1];
    traffic.bvh_bytes += 2 * RECORD_BYTES;
    let v = |w: [u32; 4]| {
        Vec3::new(
            f32::from_bits(w[0]),
            f32::from_bits(w[1]),
            f32::from_bits(w[2]),
        )
    };
    Node {
        min: v(head),
        max: v(tail),
        link: head[3],
        count: tail[3],
    }
}

/// Boundary face `f`: its tetrahedron << 2 | local face.
pub fn face_entry(input: &Inputs, f: u32, traffic: &mut Traffic) -> u32 {
    traffic.bvh_bytes += 4;
    input.bvh[(input.params.face_offset + f / 4) as usize][(f % 4) as usize]
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Entry {
    pub found: bool,
    pub face: u32,
    pub t: f32,
    /// The face's point indices, in the order tested (all edges negative).
    pub ids: [u32; 3],
}

#[derive(Debug, Clone, Copy, Default)]
pub struct Skip {
    pub faces: [u32; SKIP_MAX],
    pub len: usize,
}

impl Skip {
    fn contains(&self, face: u32) -> bool {
        self.faces[..self.len].contains(&face)
    }
}

/// The kernel's query, its loads of the BVH array and of the points counted
/// in `traffic` (the root's records, an inner node's children's records, a
/// leaf's face records and their three points each).
pub fn first_entry(
    input: &Inputs,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    skip: &Skip,
    traffic: &mut Traffic,
) -> Entry {
    let params = input.params;
    let mut best = Entry {
        found: false,
        face: 0,
        t: t_max,
        ids: [0; 3],
    };
    traffic.bvh_queries += 1;
    let slab = make_slab(ray, params.scene_abs_max);
    let root = load_node(input, 0, traffic);
    if slab_entry(&slab, root.min, root.max, t_min, t_max).is_none() {
        return best;
    }
    // A node is visited with its link and count, read with its bounds when
    // its parent tested it: a visit loads only its children.
    let mut stack_link = [0u32; STACK_SIZE];
    let mut stack_count = [0u32; STACK_SIZE];
    let mut stack_t = [0f32; STACK_SIZE];
    let mut stack_len = 0usize;
    let (mut link, mut count) = (root.link, root.count);
    for _ in 0..params.prim_offset {
        let mut next = None;
        if count > 0 {
            for slot in link..link + count {
                let prim = input.bvh[(params.prim_offset + slot) as usize];
                traffic.bvh_bytes += RECORD_BYTES;
                traffic.bvh_point_bytes += 3 * RECORD_BYTES;
                let p = |i: usize| project(ray, input.point(prim[i]).truncate());
                let (a, b, c) = (p(0), p(1), p(2));
                let (sab, sbc, sca) = (edge_sign(a, b), edge_sign(b, c), edge_sign(c, a));
                if sab < 0 && sbc < 0 && sca < 0 {
                    let t = crossing(a, b, c).t;
                    let better = !best.found || t < best.t || (t == best.t && prim[3] < best.face);
                    if t >= t_min && t <= t_max && better && !skip.contains(prim[3]) {
                        best = Entry {
                            found: true,
                            face: prim[3],
                            t,
                            ids: [prim[0], prim[1], prim[2]],
                        };
                    }
                }
            }
        } else {
            let t_hi = best.t;
            let l = load_node(input, link, traffic);
            let r = load_node(input, link + 1, traffic);
            let hl = slab_entry(&slab, l.min, l.max, t_min, t_hi);
            let hr = slab_entry(&slab, r.min, r.max, t_min, t_hi);
            next = match (hl, hr) {
                (Some(tl), Some(tr)) => {
                    let (near, far, t_far) = if tr < tl { (r, l, tl) } else { (l, r, tr) };
                    if stack_len < STACK_SIZE {
                        stack_link[stack_len] = far.link;
                        stack_count[stack_len] = far.count;
                        stack_t[stack_len] = t_far;
                        stack_len += 1;
                    }
                    Some((near.link, near.count))
                }
                (Some(_), None) => Some((l.link, l.count)),
                (None, Some(_)) => Some((r.link, r.count)),
                (None, None) => None,
            };
        }
        if next.is_none() {
            loop {
                if stack_len == 0 {
                    return best;
                }
                stack_len -= 1;
                if stack_t[stack_len] <= best.t {
                    next = Some((stack_link[stack_len], stack_count[stack_len]));
                    break;
                }
            }
        }
        (link, count) = next.unwrap_or((0, 0));
    }
    best
}
