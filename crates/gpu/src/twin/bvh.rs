//! Twin of shaders/bvh.wgsl: nearest-first traversal of the flattened
//! boundary BVH with padded, inclusive slab tests.

use glam::{UVec3, Vec3};

use super::predicate::{crossing, edge_sign, project, Ray};
use super::{Inputs, Traffic, RECORD_BYTES};

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

fn node_bounds(input: &Inputs, i: u32) -> (Vec3, Vec3) {
    let head = input.bvh[2 * i as usize];
    let tail = input.bvh[2 * i as usize + 1];
    let v = |w: [u32; 4]| {
        Vec3::new(
            f32::from_bits(w[0]),
            f32::from_bits(w[1]),
            f32::from_bits(w[2]),
        )
    };
    (v(head), v(tail))
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
/// in `traffic` (a node's two records, its children's bounds, a leaf's
/// face records and their three points each).
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
    };
    traffic.bvh_queries += 1;
    let slab = make_slab(ray, params.scene_abs_max);
    let (rmin, rmax) = node_bounds(input, 0);
    traffic.bvh_bytes += 2 * RECORD_BYTES;
    if slab_entry(&slab, rmin, rmax, t_min, t_max).is_none() {
        return best;
    }
    let mut stack_node = [0u32; STACK_SIZE];
    let mut stack_t = [0f32; STACK_SIZE];
    let mut stack_len = 0usize;
    let mut current = 0u32;
    for _ in 0..params.prim_offset {
        let head = input.bvh[2 * current as usize];
        let count = input.bvh[2 * current as usize + 1][3];
        traffic.bvh_bytes += 2 * RECORD_BYTES;
        let mut next = None;
        if count > 0 {
            for slot in head[3]..head[3] + count {
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
                        };
                    }
                }
            }
        } else {
            let left = head[3];
            let t_hi = best.t;
            let (lmin, lmax) = node_bounds(input, left);
            let (qmin, qmax) = node_bounds(input, left + 1);
            traffic.bvh_bytes += 4 * RECORD_BYTES;
            let hl = slab_entry(&slab, lmin, lmax, t_min, t_hi);
            let hr = slab_entry(&slab, qmin, qmax, t_min, t_hi);
            next = match (hl, hr) {
                (Some(tl), Some(tr)) => {
                    let (near, far, t_far) = if tr < tl {
                        (left + 1, left, tl)
                    } else {
                        (left, left + 1, tr)
                    };
                    if stack_len < STACK_SIZE {
                        stack_node[stack_len] = far;
                        stack_t[stack_len] = t_far;
                        stack_len += 1;
                    }
                    Some(near)
                }
                (Some(_), None) => Some(left),
                (None, Some(_)) => Some(left + 1),
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
                    next = Some(stack_node[stack_len]);
                    break;
                }
            }
        }
        current = next.unwrap_or(0);
    }
    best
}
