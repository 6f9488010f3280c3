// The ray-casting kernel: one invocation per pixel enters the mesh through
// the boundary BVH, walks tetrahedron to tetrahedron across the exit face
// chosen by the exact edge predicate, integrates every segment, composites
// front to back and re-enters through the BVH after leaving the mesh (CPU
// twin: tetray_gpu::twin::raycast; reference: tetray_raycast).

// For the signs of the edges apex -> face slot i (bit i set when positive),
// the slot of the entry face that the exit face leaves out, or 3 where all
// signs agree (only a flat tetrahedron): the exit face (apex, slot k + 1,
// slot k + 2) has all its edges positive exactly when apex -> slot k + 1
// is positive and apex -> slot k + 2 negative, its third edge being the
// entry face's (tetray_raycast::LEFT_OUT_SLOT).
const LEFT_OUT_SLOT = array<u32, 8>(3u, 2u, 0u, 0u, 1u, 2u, 1u, 3u);
// "Unbounded" distances (WGSL has no infinity literal).
const FAR: f32 = 3.4e38;
// 2^-20 (tetray_boundary_bvh::REENTRY_REL).
const REENTRY_REL: f32 = 9.5367431640625e-7;

// The face a ray entered its current tetrahedron through, in the frame of
// the ray: per vertex its projection (x, y across the ray, z along it) and
// its scalar in w, in the cyclic order in which every edge is positive,
// and the vertices' point indices. The next cell shares the exit face, so
// of each cell only the vertex opposite the entry face is loaded: one
// point read per step. Three named registers, picked by `slot` with
// selects: dynamically indexed local arrays would live in (slow) local
// memory on many GPUs.
struct Face {
    v0: vec4<f32>,
    v1: vec4<f32>,
    v2: vec4<f32>,
    ids: vec3<u32>,
}

fn slot(face: Face, i: u32) -> vec4<f32> {
    return select(select(face.v0, face.v1, i == 1u), face.v2, i == 2u);
}

fn slot_id(face: Face, i: u32) -> u32 {
    return select(select(face.ids.x, face.ids.y, i == 1u), face.ids.z, i == 2u);
}

fn load_vertex(ray: Ray, index: u32) -> vec4<f32> {
    let q = point_at(index);
    return vec4<f32>(project(ray, q.xyz), q.w);
}

struct Entered {
    face: Face,
    // The scalar where the ray crosses the face.
    s: f32,
}

// Enters through the boundary face with point indices `ids`, all of whose
// edges are negative (the face tested by the BVH): reversed, they are
// positive.
fn enter_face(ray: Ray, ids: vec3<u32>) -> Entered {
    let a = load_vertex(ray, ids.x);
    let b = load_vertex(ray, ids.y);
    let c = load_vertex(ray, ids.z);
    let x = crossing(a.xyz, b.xyz, c.xyz);
    let s = dot(x.weights, vec3<f32>(a.w, b.w, c.w));
    return Entered(Face(a, c, b, vec3<u32>(ids.x, ids.z, ids.y)), s);
}

// The point index of the vertex opposite `face` in tetrahedron `tet`.
fn apex_of(face: Face, tet: u32) -> u32 {
    return tet_xor(tet) ^ face.ids.x ^ face.ids.y ^ face.ids.z;
}

// The rank of point index `id` among the four of the tetrahedron made of
// `face` and `apex` (how many are smaller; `id` is one of them): the slot
// of the neighbour across the face opposite it.
fn rank_of(face: Face, apex: u32, id: u32) -> u32 {
    let below = select(vec3<u32>(0u), vec3<u32>(1u), face.ids < vec3<u32>(id));
    return below.x + below.y + below.z + select(0u, 1u, apex < id);
}

struct Exit {
    ok: bool,
    // The rank of the entry face's vertex not on the exit face: the slot
    // of the neighbour across the exit face.
    rank: u32,
    t: f32,
    s: f32,
}

// Leaves the cell whose vertex opposite `face` is `pa` (point index
// `apex`): the distance to the exit face and the scalar there; the exit
// face becomes `face`, the next cell's entry face.
fn exit_face(face: ptr<function, Face>, apex: u32, pa: vec4<f32>) -> Exit {
    let f = *face;
    // Edge functions apex -> each slot, and their exact signs.
    let e = vec3<f32>(edge_value(pa.xyz, f.v0.xyz), edge_value(pa.xyz, f.v1.xyz), edge_value(pa.xyz, f.v2.xyz));
    var code = 0u;
    if (edge_sign_of(pa.xyz, f.v0.xyz, e.x) > 0) {
        code |= 1u;
    }
    if (edge_sign_of(pa.xyz, f.v1.xyz, e.y) > 0) {
        code |= 2u;
    }
    if (edge_sign_of(pa.xyz, f.v2.xyz, e.z) > 0) {
        code |= 4u;
    }
    let k = LEFT_OUT_SLOT[code];
    if (k == 3u) {
        return Exit(false, 0u, 0.0, 0.0);
    }
    // The exit face in cyclic order: the apex, then the slots following
    // and preceding k.
    let next = (k + 1u) % 3u;
    let prev = (k + 2u) % 3u;
    let pn = slot(f, next);
    let pp = slot(f, prev);
    let e_next = select(select(e.x, e.y, next == 1u), e.z, next == 2u);
    let e_prev = select(select(e.x, e.y, prev == 1u), e.z, prev == 2u);
    // Weights of (apex, next, prev): the edge functions of the opposite
    // edges, ef(prev, apex) = -ef(apex, prev).
    let w = vec3<f32>(edge_value(pn.xyz, pp.xyz), -e_prev, e_next);
    let x = crossing_from(w, vec3<f32>(pa.z, pn.z, pp.z));
    let s = dot(x.weights, vec3<f32>(pa.w, pn.w, pp.w));
    let rank = rank_of(f, apex, slot_id(f, k));
    // The apex takes slot k: (apex, next, prev) in the same cyclic order.
    (*face).v0 = select(f.v0, pa, k == 0u);
    (*face).v1 = select(f.v1, pa, k == 1u);
    (*face).v2 = select(f.v2, pa, k == 2u);
    (*face).ids = select(f.ids, vec3<u32>(apex), vec3<u32>(k) == vec3<u32>(0u, 1u, 2u));
    return Exit(true, rank, x.t, s);
}

var<workgroup> group_stats: array<atomic<u32>, STAT_COUNT>;

struct Counters {
    hit: u32,
    segments: u32,
    steps: u32,
    entries: u32,
    bound_hit: u32,
    failure: u32,
    overlap_segments: u32,
    overlap_overflow: u32,
}

struct Pixel {
    color: vec4<f32>,
    counters: Counters,
}

// Casts the ray of pixel (px, py).
fn cast_ray(px: u32, py: u32) -> Pixel {
    let x = (f32(px) + 0.5 - params.view.half_width) * params.view.pixel;
    let y = (params.view.half_height - (f32(py) + 0.5)) * params.view.pixel;
    let offset = params.view.right * x + params.view.up * y;
    var ray: Ray;
    var inside: bool;
    if (params.view.orthographic == 1u) {
        ray = make_ray(params.view.position + offset, params.view.direction);
        inside = all(ray.origin >= params.bounds_min) && all(ray.origin <= params.bounds_max);
    } else {
        ray = make_ray(params.view.position, params.view.direction + offset);
        inside = params.eye_inside == 1u;
    }
    // A ray whose origin may be inside the mesh walks from its line's first
    // entry, behind the origin too, and integrates from distance 0.
    var t_cursor = select(0.0, -FAR, inside);
    var color = vec3<f32>(0.0);
    var trans = vec3<f32>(1.0);
    var counters = Counters(0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u);
    counters.overlap_overflow = find_holes(ray);
    // Boundary faces entered at distance skip_t with no segment since: a
    // re-entry query must not return them again.
    var skip: Skip;
    skip.len = 0u;
    var skip_t = 0.0;
    var done = false;
    for (var entry_count = 0u; entry_count < params.max_steps && !done; entry_count++) {
        // Re-entries start a little before the exit: the exit distance and
        // a coincident face's entry distance round differently
        // (tetray_boundary_bvh::REENTRY_REL).
        var t_query = t_cursor;
        if (counters.entries > 0u) {
            let o = abs(ray.origin);
            t_query = t_cursor - REENTRY_REL * (params.scene_abs_max + max(max(o.x, o.y), o.z));
        }
        let entry = first_entry(ray, t_query, FAR, skip);
        if (hole_count > 0u) {
            // The gap before this entry (or after the last exit).
            let filled = fill_gap(t_cursor, select(FAR, entry.t, entry.found), &color, &trans);
            counters.overlap_segments += filled.segments;
            if (filled.opaque) {
                break;
            }
        }
        if (!entry.found) {
            break;
        }
        counters.entries++;
        counters.hit = 1u;
        if (skip.len == 0u || entry.t != skip_t) {
            skip.len = 0u;
            skip_t = entry.t;
        }
        if (skip.len < SKIP_MAX) {
            skip.faces[skip.len] = entry.face;
            skip.len++;
        }
        var tet = face_entry(entry.face) >> 2u;
        let entered = enter_face(ray, entry.ids);
        var face = entered.face;
        var t_in = max(entry.t, t_cursor);
        var s_in = entered.s;
        var sample_in = sample_at(s_in);
        loop {
            counters.steps++;
            if (counters.steps > params.max_steps) {
                counters.bound_hit = 1u;
                done = true;
                break;
            }
            let apex = apex_of(face, tet);
            let ex = exit_face(&face, apex, load_vertex(ray, apex));
            if (!ex.ok) {
                // Only a flat tetrahedron has no exit face.
                counters.failure = 1u;
                done = true;
                break;
            }
            let t_out = max(ex.t, t_in);
            let sample_out = sample_near(ex.s, sample_in);
            if (t_out > t_in) {
                skip.len = 0u;
                if (t_out > 0.0) {
                    // Clip at the ray origin; the scalar is linear along
                    // the segment.
                    var front = sample_in;
                    if (t_in < 0.0) {
                        front = sample_at(s_in + (ex.s - s_in) * (-t_in / (t_out - t_in)));
                    }
                    let light = segment_light(front, sample_out, t_out - max(t_in, 0.0));
                    color += trans * light.emitted;
                    trans *= light.transmittance;
                    counters.segments++;
                    if (trans.x + trans.y + trans.z <= params.stop_below_sum) {
                        done = true;
                        break;
                    }
                }
            }
            t_in = t_out;
            s_in = ex.s;
            sample_in = sample_out;
            let next = tet_next(tet, ex.rank);
            if (next >= FINAL_EXIT) {
                // Left through the convex hull: nothing more to meet but
                // the gap of a left-out cell beyond; otherwise ask the BVH
                // where the ray comes back.
                done = next == FINAL_EXIT && !holes_beyond(t_out);
                t_cursor = t_out;
                break;
            }
            tet = next;
        }
    }
    let alpha = 1.0 - (trans.x + trans.y + trans.z) / 3.0;
    return Pixel(vec4<f32>(color, alpha), counters);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    if (lid < STAT_COUNT) {
        atomicStore(&group_stats[lid], 0u);
    }
    workgroupBarrier();
    if (gid.x < tile.width && gid.y < tile.height) {
        let px = tile.x0 + gid.x;
        let py = tile.y0 + gid.y;
        let pixel = cast_ray(px, py);
        image[py * params.width + px] = pixel.color;
        let c = pixel.counters;
        atomicAdd(&group_stats[STAT_RAYS_HIT], c.hit);
        atomicAdd(&group_stats[STAT_SEGMENTS_LO], c.segments);
        atomicAdd(&group_stats[STAT_STEPS_LO], c.steps);
        atomicAdd(&group_stats[STAT_ENTRIES], c.entries);
        atomicAdd(&group_stats[STAT_BOUND_HITS], c.bound_hit);
        atomicAdd(&group_stats[STAT_WALK_FAILURES], c.failure);
        // Rarely nonzero: an atomic only where there is something to add.
        if (c.overlap_segments != 0u) {
            atomicAdd(&group_stats[STAT_OVERLAP_SEGMENTS], c.overlap_segments);
        }
        if (c.overlap_overflow != 0u) {
            atomicAdd(&group_stats[STAT_OVERLAP_OVERFLOWS], c.overlap_overflow);
        }
    }
    workgroupBarrier();
    if (lid == 0u) {
        atomicAdd(&stats[STAT_RAYS_HIT], atomicLoad(&group_stats[STAT_RAYS_HIT]));
        add_wide(STAT_SEGMENTS_LO, STAT_SEGMENTS_HI, atomicLoad(&group_stats[STAT_SEGMENTS_LO]));
        add_wide(STAT_STEPS_LO, STAT_STEPS_HI, atomicLoad(&group_stats[STAT_STEPS_LO]));
        atomicAdd(&stats[STAT_ENTRIES], atomicLoad(&group_stats[STAT_ENTRIES]));
        atomicAdd(&stats[STAT_BOUND_HITS], atomicLoad(&group_stats[STAT_BOUND_HITS]));
        atomicAdd(&stats[STAT_WALK_FAILURES], atomicLoad(&group_stats[STAT_WALK_FAILURES]));
        atomicAdd(&stats[STAT_OVERLAP_SEGMENTS], atomicLoad(&group_stats[STAT_OVERLAP_SEGMENTS]));
        atomicAdd(&stats[STAT_OVERLAP_OVERFLOWS], atomicLoad(&group_stats[STAT_OVERLAP_OVERFLOWS]));
    }
}
