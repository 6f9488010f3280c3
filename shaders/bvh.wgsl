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
    let finite = abs(inv) <= vec3<f32>(3.40282346e38);
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

// Node i's two records: its bounds, and in their fourth words its link
// (first child, or first face slot) and face count (0 for an inner node).
struct Node {
    min: vec3<f32>,
    max: vec3<f32>,
    link: u32,
    count: u32,
}

fn load_node(i: u32) -> Node {
    let head = bvh[2u * i];
    let tail = bvh[2u * i + 1u];
    return Node(bitcast<vec3<f32>>(head.xyz), bitcast<vec3<f32>>(tail.xyz), head.w, tail.w);
}

// Boundary face f: its tetrahedron << 2 | local face.
fn face_entry(f: u32) -> u32 {
    return bvh[params.face_offset + f / 4u][f % 4u];
}

struct Entry {
    found: bool,
    face: u32,
    t: f32,
    // The face's point indices, in the order tested (all edges negative).
    ids: vec3<u32>,
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
    var best = Entry(false, 0u, t_max, vec3<u32>(0u));
    let slab = make_slab(ray);
    let root = load_node(0u);
    if (!slab_entry(slab, root.min, root.max, t_min, t_max).hit) {
        return best;
    }
    // A node is visited with its link and count, read with its bounds when
    // its parent tested it: a visit loads only its children.
    var stack_link: array<u32, STACK_SIZE>;
    var stack_count: array<u32, STACK_SIZE>;
    var stack_t: array<f32, STACK_SIZE>;
    var stack_len = 0u;
    var link = root.link;
    var count = root.count;
    // Every node is visited at most once: bound the loop by twice the count
    // of entries in the node array region.
    let budget = params.prim_offset;
    for (var visits = 0u; visits < budget; visits++) {
        var found_next = false;
        if (count > 0u) {
            for (var slot = link; slot < link + count; slot++) {
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
                        best = Entry(true, prim.w, t, prim.xyz);
                    }
                }
            }
        } else {
            let t_hi = best.t;
            let l = load_node(link);
            let r = load_node(link + 1u);
            let hl = slab_entry(slab, l.min, l.max, t_min, t_hi);
            let hr = slab_entry(slab, r.min, r.max, t_min, t_hi);
            if (hl.hit && hr.hit) {
                var near = l;
                var far = r;
                var t_far = hr.t;
                if (hr.t < hl.t) {
                    near = r;
                    far = l;
                    t_far = hl.t;
                }
                if (stack_len < STACK_SIZE) {
                    stack_link[stack_len] = far.link;
                    stack_count[stack_len] = far.count;
                    stack_t[stack_len] = t_far;
                    stack_len++;
                }
                link = near.link;
                count = near.count;
                found_next = true;
            } else if (hl.hit) {
                link = l.link;
                count = l.count;
                found_next = true;
            } else if (hr.hit) {
                link = r.link;
                count = r.count;
                found_next = true;
            }
        }
        if (!found_next) {
            loop {
                if (stack_len == 0u) {
                    return best;
                }
                stack_len--;
                // Inclusive: a subtree entered exactly at the best distance
                // may still hold a lower face index.
                if (stack_t[stack_len] <= best.t) {
                    link = stack_link[stack_len];
                    count = stack_count[stack_len];
                    break;
                }
            }
        }
    }
    return best;
}
