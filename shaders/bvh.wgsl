// Where a ray enters the mesh: nearest-first traversal of the boundary BVH
// (CPU twin: tetray_boundary_bvh::FlatBvh::first_entry). Boxes are padded
// and compared inclusively so that rounding never culls a face the edge
// predicate would accept (see tetray_boundary_bvh::slab).

const STACK_SIZE: u32 = 64u;
const PAD_REL: f32 = 1.52587890625e-5; // 2^-16
// Boundary faces entered at one distance without a segment in between
// (pinch points); more are not remembered.
const SKIP_MAX: u32 = 8u;

struct Slab {
    origin_plus_pad: vec3<f32>,
    origin_minus_pad: vec3<f32>,
    inv_dir: vec3<f32>,
    // 1 per axis along which the ray does not move measurably.
    parallel: vec3<u32>,
}

fn make_slab(ray: Ray) -> Slab {
    let o = ray.origin;
    let pad = PAD_REL * (params.scene_abs_max + max(max(abs(o.x), abs(o.y)), abs(o.z)));
    var slab: Slab;
    slab.origin_plus_pad = o + vec3<f32>(pad);
    slab.origin_minus_pad = o - vec3<f32>(pad);
    let inv = vec3<f32>(1.0) / ray.dir;
    // Not finite: |inv| above the largest f32 (or NaN).
    let finite = abs(inv) <= vec3<f32>(3.4028235e38);
    slab.parallel = select(vec3<u32>(1u), vec3<u32>(0u), finite);
    slab.inv_dir = select(vec3<f32>(0.0), inv, finite);
    return slab;
}

// Distance at which the ray enters the padded box, if its stretch inside
// overlaps [t_lo, t_hi]; -1e38 marks a miss (with `hit` false).
struct BoxHit {
    hit: bool,
    t: f32,
}

fn slab_entry(slab: Slab, bmin: vec3<f32>, bmax: vec3<f32>, t_lo: f32, t_hi: f32) -> BoxHit {
    var near = t_lo;
    var far = t_hi;
    for (var axis = 0; axis < 3; axis++) {
        if (slab.parallel[axis] == 1u) {
            if (!(bmin[axis] <= slab.origin_plus_pad[axis] && slab.origin_minus_pad[axis] <= bmax[axis])) {
                return BoxHit(false, 0.0);
            }
        } else {
            let t0 = (bmin[axis] - slab.origin_plus_pad[axis]) * slab.inv_dir[axis];
            let t1 = (bmax[axis] - slab.origin_minus_pad[axis]) * slab.inv_dir[axis];
            near = max(near, min(t0, t1));
            far = min(far, max(t0, t1));
        }
    }
    return BoxHit(near <= far, near);
}

fn node_min(i: u32) -> vec3<f32> {
    return bitcast<vec3<f32>>(bvh[2u * i].xyz);
}

fn node_max(i: u32) -> vec3<f32> {
    return bitcast<vec3<f32>>(bvh[2u * i + 1u].xyz);
}

// Boundary face f: its tetrahedron << 2 | local face.
fn face_entry(f: u32) -> u32 {
    return bvh[params.face_offset + f / 4u][f % 4u];
}

struct Entry {
    found: bool,
    face: u32,
    t: f32,
}

struct Skip {
    faces: array<u32, SKIP_MAX>,
    len: u32,
}

fn skipped(skip: Skip, face: u32) -> bool {
    for (var i = 0u; i < skip.len; i++) {
        if (skip.faces[i] == face) {
            return true;
        }
    }
    return false;
}

// The nearest boundary face the ray enters through with t in
// [t_min, t_max], ignoring `skip`; ties in t go to the lowest face index.
fn first_entry(ray: Ray, t_min: f32, t_max: f32, skip: Skip) -> Entry {
    var best = Entry(false, 0u, t_max);
    let slab = make_slab(ray);
    if (!slab_entry(slab, node_min(0u), node_max(0u), t_min, t_max).hit) {
        return best;
    }
    var stack_node: array<u32, STACK_SIZE>;
    var stack_t: array<f32, STACK_SIZE>;
    var stack_len = 0u;
    var current = 0u;
    // Every node is visited at most once: bound the loop by twice the count
    // of entries in the node array region.
    let budget = params.prim_offset;
    for (var visits = 0u; visits < budget; visits++) {
        let head = bvh[2u * current];
        let tail = bvh[2u * current + 1u];
        let count = tail.w;
        var next = 0xffffffffu;
        if (count > 0u) {
            for (var slot = head.w; slot < head.w + count; slot++) {
                let prim = bvh[params.prim_offset + slot];
                let a = project(ray, point_at(prim.x).xyz);
                let b = project(ray, point_at(prim.y).xyz);
                let c = project(ray, point_at(prim.z).xyz);
                let sab = edge_sign(a, b);
                let sbc = edge_sign(b, c);
                let sca = edge_sign(c, a);
                // All negative: the ray enters the face.
                if (sab < 0 && sbc < 0 && sca < 0) {
                    let t = crossing(a, b, c).t;
                    let better = !best.found || t < best.t || (t == best.t && prim.w < best.face);
                    if (t >= t_min && t <= t_max && better && !skipped(skip, prim.w)) {
                        best = Entry(true, prim.w, t);
                    }
                }
            }
        } else {
            let left = head.w;
            let t_hi = best.t;
            let hl = slab_entry(slab, node_min(left), node_max(left), t_min, t_hi);
            let hr = slab_entry(slab, node_min(left + 1u), node_max(left + 1u), t_min, t_hi);
            if (hl.hit && hr.hit) {
                var near = left;
                var far = left + 1u;
                var t_far = hr.t;
                if (hr.t < hl.t) {
                    near = left + 1u;
                    far = left;
                    t_far = hl.t;
                }
                if (stack_len < STACK_SIZE) {
                    stack_node[stack_len] = far;
                    stack_t[stack_len] = t_far;
                    stack_len++;
                }
                next = near;
            } else if (hl.hit) {
                next = left;
            } else if (hr.hit) {
                next = left + 1u;
            }
        }
        if (next == 0xffffffffu) {
            loop {
                if (stack_len == 0u) {
                    return best;
                }
                stack_len--;
                // Inclusive: a subtree entered exactly at the best distance
                // may still hold a lower face index.
                if (stack_t[stack_len] <= best.t) {
                    next = stack_node[stack_len];
                    break;
                }
            }
        }
        current = next;
    }
    return best;
}
