// The ray-casting kernel: one invocation per pixel enters the mesh through
// the boundary BVH, walks tetrahedron to tetrahedron across the exit face
// chosen by the exact edge predicate, integrates every segment, composites
// front to back and re-enters through the BVH after leaving the mesh (CPU
// twin: tetray_gpu::twin::raycast; reference: tetray_raycast).

// Local face f is opposite vertex f, counter-clockwise seen from outside
// (tetray_mesh::FACE_VERTICES).
const FACE_VERTS = array<vec3<u32>, 4>(
    vec3<u32>(1u, 2u, 3u), vec3<u32>(0u, 3u, 2u), vec3<u32>(0u, 1u, 3u), vec3<u32>(0u, 2u, 1u),
);
// For the apex (the vertex opposite the entry face), its other vertices.
const APEX_OTHERS = array<vec3<u32>, 4>(
    vec3<u32>(1u, 2u, 3u), vec3<u32>(0u, 2u, 3u), vec3<u32>(0u, 1u, 3u), vec3<u32>(0u, 1u, 2u),
);
// Exit face of apex a for the signs of its three edges (bit i: the edge to
// APEX_OTHERS[a][i] is positive), at [8 a + code]: face | next << 4 |
// prev << 8 (the vertices after and before the apex in the face), or
// 0xffff where all signs agree (only a flat tetrahedron). The exit face is
// the one whose edge apex -> next is positive and apex -> prev negative
// (tetray_raycast::packed_exit_table derives the table).
const APEX_EXITS = array<u32, 32>(
    0xffffu, 0x0312u, 0x0123u, 0x0312u, 0x0231u, 0x0231u, 0x0123u, 0xffffu,
    0xffffu, 0x0203u, 0x0320u, 0x0320u, 0x0032u, 0x0203u, 0x0032u, 0xffffu,
    0xffffu, 0x0301u, 0x0013u, 0x0301u, 0x0130u, 0x0130u, 0x0013u, 0xffffu,
    0xffffu, 0x0102u, 0x0210u, 0x0210u, 0x0021u, 0x0102u, 0x0021u, 0xffffu,
);
// "Unbounded" distances (WGSL has no infinity literal).
const FAR: f32 = 3.4e38;
// 2^-20 (tetray_boundary_bvh::REENTRY_REL).
const REENTRY_REL: f32 = 9.5367431640625e-7;

// The current tetrahedron in the frame of the ray: per vertex its
// projection (x, y across the ray, z along it) and its scalar in w, and the
// vertex ids. Four named registers, picked by `vertex` with selects:
// dynamically indexed local arrays would live in (slow) local memory on
// many GPUs.
struct Cell {
    v0: vec4<f32>,
    v1: vec4<f32>,
    v2: vec4<f32>,
    v3: vec4<f32>,
    ids: vec4<u32>,
}

fn vertex(cell: Cell, i: u32) -> vec4<f32> {
    return select(select(select(cell.v0, cell.v1, i == 1u), cell.v2, i == 2u), cell.v3, i == 3u);
}

fn load_vertex(ray: Ray, index: u32) -> vec4<f32> {
    let q = point_at(index);
    return vec4<f32>(project(ray, q.xyz), q.w);
}

// A cell entered from the BVH: all four vertices loaded and projected.
fn load_cell(ray: Ray, tet: u32) -> Cell {
    let v = tet_verts(tet);
    return Cell(load_vertex(ray, v.x), load_vertex(ray, v.y), load_vertex(ray, v.z), load_vertex(ray, v.w), v);
}

// The vertex of `cell` with id `id` (v0 when none has it).
fn carried(cell: Cell, id: u32) -> vec4<f32> {
    return select(select(select(cell.v0, cell.v1, id == cell.ids.y), cell.v2, id == cell.ids.z), cell.v3, id == cell.ids.w);
}

// The neighbour `tet`, entered through its face `f_in` from `cell`: the
// three vertices of that face are the previous cell's exit face, carried
// over with the same bits (so both sides of the face agree exactly); only
// the apex opposite it is loaded and projected. One point read per step
// instead of four.
fn next_cell(ray: Ray, cell: Cell, tet: u32, f_in: u32) -> Cell {
    let v = tet_verts(tet);
    let apex = load_vertex(ray, v[f_in]);
    return Cell(
        select(carried(cell, v.x), apex, f_in == 0u),
        select(carried(cell, v.y), apex, f_in == 1u),
        select(carried(cell, v.z), apex, f_in == 2u),
        select(carried(cell, v.w), apex, f_in == 3u),
        v,
    );
}

// Scalar where the ray crosses face f.
fn face_scalar(cell: Cell, f: u32) -> f32 {
    let v = FACE_VERTS[f];
    let a = vertex(cell, v.x);
    let b = vertex(cell, v.y);
    let c = vertex(cell, v.z);
    let x = crossing(a.xyz, b.xyz, c.xyz);
    return dot(x.weights, vec3<f32>(a.w, b.w, c.w));
}

struct Exit {
    ok: bool,
    face: u32,
    t: f32,
    s: f32,
}

// Leaves a cell entered through f_in: the exit face, the distance to it and
// the scalar there.
fn exit_cell(cell: Cell, f_in: u32) -> Exit {
    let others = APEX_OTHERS[f_in];
    let pa = vertex(cell, f_in);
    let p0 = vertex(cell, others.x);
    let p1 = vertex(cell, others.y);
    let p2 = vertex(cell, others.z);
    // Edge functions apex -> each other vertex, and their exact signs.
    let e = vec3<f32>(edge_value(pa.xyz, p0.xyz), edge_value(pa.xyz, p1.xyz), edge_value(pa.xyz, p2.xyz));
    var code = 0u;
    if (edge_sign_of(pa.xyz, p0.xyz, e.x) > 0) {
        code |= 1u;
    }
    if (edge_sign_of(pa.xyz, p1.xyz, e.y) > 0) {
        code |= 2u;
    }
    if (edge_sign_of(pa.xyz, p2.xyz, e.z) > 0) {
        code |= 4u;
    }
    let packed = APEX_EXITS[8u * f_in + code];
    if (packed == 0xffffu) {
        return Exit(false, 0u, 0.0, 0.0);
    }
    let f = packed & 0xfu;
    let next = (packed >> 4u) & 0xfu;
    let prev = (packed >> 8u) & 0xfu;
    let pn = vertex(cell, next);
    let pp = vertex(cell, prev);
    // The apex edge functions of next and prev (which of the three).
    let e_next = select(select(e.x, e.y, next == others.y), e.z, next == others.z);
    let e_prev = select(select(e.x, e.y, prev == others.y), e.z, prev == others.z);
    // Weights of (apex, next, prev): the edge functions of the opposite
    // edges, ef(prev, apex) = -ef(apex, prev).
    let w = vec3<f32>(edge_value(pn.xyz, pp.xyz), -e_prev, e_next);
    let x = crossing_from(w, vec3<f32>(pa.z, pn.z, pp.z));
    let s = dot(x.weights, vec3<f32>(pa.w, pn.w, pp.w));
    return Exit(true, f, x.t, s);
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
        let code = face_entry(entry.face);
        var tet = code >> 2u;
        var f_in = code & 3u;
        var cell = load_cell(ray, tet);
        var t_in = max(entry.t, t_cursor);
        var s_in = face_scalar(cell, f_in);
        var sample_in = sample_at(s_in);
        loop {
            counters.steps++;
            if (counters.steps > params.max_steps) {
                counters.bound_hit = 1u;
                done = true;
                break;
            }
            let ex = exit_cell(cell, f_in);
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
            let next = tet_next(tet)[ex.face];
            if (next >= FINAL_EXIT) {
                // Left through the convex hull: nothing more to meet but
                // the gap of a left-out cell beyond; otherwise ask the BVH
                // where the ray comes back.
                done = next == FINAL_EXIT && !holes_beyond(t_out);
                t_cursor = t_out;
                break;
            }
            tet = next >> 2u;
            f_in = next & 3u;
            cell = next_cell(ray, cell, tet, f_in);
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
