// The cells left out of the walk (tangled, overlapping a neighbour),
// composited in the gaps they leave: a ray finds the left-out tetrahedra it
// crosses once, then fills each gap between an exit and the next entry
// with the pieces whose signs sum to 1 or more, the scalar their signed
// mean (rule and CPU twin: tetray_scene::overlaps; the same operations).

const MAX_OVERLAP_CROSSINGS: u32 = 32u;

// Per crossing: t_in, t_out, s_in, s_out; and its sign.
var<private> hole_crossings: array<vec4<f32>, MAX_OVERLAP_CROSSINGS>;
var<private> hole_signs: array<f32, MAX_OVERLAP_CROSSINGS>;
var<private> hole_count: u32;

fn overlap_vertex(ray: Ray, id: u32) -> vec4<f32> {
    let q = point_at(id);
    return vec4<f32>(project(ray, q.xyz), q.w);
}

// Where the ray passes through the face (a, b, c): (t, s, sum of the edge
// functions, 1) or w = 0 where it does not.
fn overlap_face(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>) -> vec4<f32> {
    let wa = b.x * c.y - b.y * c.x;
    let wb = c.x * a.y - c.y * a.x;
    let wc = a.x * b.y - a.y * b.x;
    let inside = (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) || (wa <= 0.0 && wb <= 0.0 && wc <= 0.0);
    let sum = wa + wb + wc;
    if (!inside || sum == 0.0) {
        return vec4<f32>(0.0);
    }
    let t = (wa * a.z + wb * b.z + wc * c.z) / sum;
    let s = (wa * a.w + wb * b.w + wc * c.w) / sum;
    return vec4<f32>(t, s, sum, 1.0);
}

// Finds the left-out tetrahedra the ray's line crosses; returns 1 when it
// crosses more than it keeps.
fn find_holes(ray: Ray) -> u32 {
    hole_count = 0u;
    if (params.overlap_count == 0u) {
        return 0u;
    }
    let lo = bitcast<vec4<f32>>(bvh[params.overlap_offset]).xyz;
    let hi = bitcast<vec4<f32>>(bvh[params.overlap_offset + 1u]).xyz;
    var near = -FAR;
    var far = FAR;
    for (var axis = 0u; axis < 3u; axis++) {
        let o = ray.origin[axis];
        let d = ray.dir[axis];
        if (d == 0.0) {
            if (o < lo[axis] || o > hi[axis]) {
                return 0u;
            }
        } else {
            let a = (lo[axis] - o) / d;
            let b = (hi[axis] - o) / d;
            near = max(near, min(a, b));
            far = min(far, max(a, b));
        }
    }
    if (near > far) {
        return 0u;
    }
    for (var i = 0u; i < params.overlap_count; i++) {
        let ids = bvh[params.overlap_offset + 2u + i];
        let v0 = overlap_vertex(ray, ids.x);
        let v1 = overlap_vertex(ray, ids.y);
        let v2 = overlap_vertex(ray, ids.z);
        let v3 = overlap_vertex(ray, ids.w);
        // Faces in FACE_VERTS order; the first nearest and first farthest.
        var hits = array<vec4<f32>, 4>(
            overlap_face(v1, v2, v3),
            overlap_face(v0, v3, v2),
            overlap_face(v0, v1, v3),
            overlap_face(v0, v2, v1),
        );
        var first = vec4<f32>(0.0);
        var last = vec4<f32>(0.0);
        for (var f = 0u; f < 4u; f++) {
            let h = hits[f];
            if (h.w == 0.0) {
                continue;
            }
            if (first.w == 0.0 || h.x < first.x) {
                first = h;
            }
            if (last.w == 0.0 || h.x > last.x) {
                last = h;
            }
        }
        if (first.w == 0.0 || !(last.x > first.x)) {
            continue;
        }
        if (hole_count == MAX_OVERLAP_CROSSINGS) {
            return 1u;
        }
        hole_crossings[hole_count] = vec4<f32>(first.x, last.x, first.y, last.y);
        hole_signs[hole_count] = select(-1.0, 1.0, first.z < 0.0);
        hole_count++;
    }
    return 0u;
}

// Whether a kept crossing reaches beyond distance t.
fn holes_beyond(t: f32) -> bool {
    for (var i = 0u; i < hole_count; i++) {
        if (hole_crossings[i].y > t) {
            return true;
        }
    }
    return false;
}

fn hole_scalar(c: vec4<f32>, t: f32) -> f32 {
    return c.z + (c.w - c.z) * ((t - c.x) / (c.y - c.x));
}

struct Filled {
    segments: u32,
    opaque: bool,
}

// Composites into (color, trans) the pieces of the gap from `start`
// (clipped at the eye) to `end`.
fn fill_gap(start: f32, end: f32, color: ptr<function, vec3<f32>>, trans: ptr<function, vec3<f32>>) -> Filled {
    var filled = Filled(0u, false);
    var e = max(start, 0.0);
    for (var k = 0u; k <= 2u * hole_count; k++) {
        if (e >= end) {
            break;
        }
        var n = end;
        for (var i = 0u; i < hole_count; i++) {
            let c = hole_crossings[i];
            if (c.x > e && c.x < n) {
                n = c.x;
            }
            if (c.y > e && c.y < n) {
                n = c.y;
            }
        }
        let mid = 0.5 * (e + n);
        var w = 0.0;
        var front = 0.0;
        var back = 0.0;
        for (var i = 0u; i < hole_count; i++) {
            let c = hole_crossings[i];
            if (c.x < mid && mid < c.y) {
                let sign = hole_signs[i];
                w += sign;
                front += sign * hole_scalar(c, e);
                back += sign * hole_scalar(c, n);
            }
        }
        if (w >= 1.0) {
            let light = segment_light(sample_at(front / w), sample_at(back / w), n - e);
            *color += *trans * light.emitted;
            *trans *= light.transmittance;
            filled.segments++;
            if ((*trans).x + (*trans).y + (*trans).z <= params.stop_below_sum) {
                filled.opaque = true;
                break;
            }
        }
        e = n;
    }
    return filled;
}
