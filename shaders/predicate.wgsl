// The ray frame and the watertight edge predicate (CPU twin:
// tetray_gpu::twin::predicate; same rule as tetray_boundary_bvh::watertight).
//
// Points are projected into a frame whose third axis is the ray direction.
// The sign of an edge function `ax * by - ay * bx` decides which side of an
// edge the ray passes. It is computed exactly: a fast f32 evaluation whose
// error bound proves its sign, else an exact sum of the split products.
// An exactly zero edge function (the ray through an edge or a vertex) is
// decided by simulation of simplicity, as on the CPU, so faces sharing an
// edge always disagree and the ray never leaks, doubles or loops.

struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,
    u: vec3<f32>,
    v: vec3<f32>,
}

// A unit direction and an orthonormal basis around it (Duff et al. 2017,
// as RayFrame::new: exact for axis-aligned directions).
fn make_ray(origin: vec3<f32>, direction: vec3<f32>) -> Ray {
    let len2 = direction.x * direction.x + direction.y * direction.y + direction.z * direction.z;
    let dir = direction * (1.0 / sqrt(len2));
    // copysign(1, dir.z), -0 included.
    let sign = select(1.0, -1.0, (bitcast<u32>(dir.z) >> 31u) == 1u);
    let a = -1.0 / (sign + dir.z);
    let b = dir.x * dir.y * a;
    var ray: Ray;
    ray.origin = origin;
    ray.dir = dir;
    ray.u = vec3<f32>(1.0 + sign * dir.x * dir.x * a, sign * b, -sign * dir.x);
    ray.v = vec3<f32>(b, sign + dir.y * dir.y * a, -dir.y);
    return ray;
}

// A point in the frame of the ray: across (x, y) and along (z).
fn project(ray: Ray, p: vec3<f32>) -> vec3<f32> {
    let d = p - ray.origin;
    return vec3<f32>(
        d.x * ray.u.x + d.y * ray.u.y + d.z * ray.u.z,
        d.x * ray.v.x + d.y * ray.v.y + d.z * ray.v.z,
        d.x * ray.dir.x + d.y * ray.dir.y + d.z * ray.dir.z,
    );
}

// The high 12 significant bits of `x` (by masking, so no rounding and no
// compiler contraction can touch it); `x - hi` is exact.
fn split_high(x: f32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) & 0xfffff000u);
}

// `(s, e)` with `s + e = a + b` exactly (Knuth's TwoSum).
fn two_sum(a: f32, b: f32) -> vec2<f32> {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    return vec2<f32>(s, (a - av) + (b - bv));
}

// The exact sign of `ax * by - ay * bx`: each product is the sum of four
// exact products of 12-bit halves, and the eight terms are summed into a
// non-overlapping expansion (Shewchuk's grow-expansion) whose most
// significant non-zero component carries the sign.
fn det_sign_exact(ax: f32, ay: f32, bx: f32, by: f32) -> i32 {
    let axh = split_high(ax);
    let axl = ax - axh;
    let ayh = split_high(ay);
    let ayl = ay - ayh;
    let bxh = split_high(bx);
    let bxl = bx - bxh;
    let byh = split_high(by);
    let byl = by - byh;
    var terms = array<f32, 8>(
        axh * byh, axh * byl, axl * byh, axl * byl,
        -(ayh * bxh), -(ayh * bxl), -(ayl * bxh), -(ayl * bxl),
    );
    var expansion: array<f32, 8>;
    var len = 0u;
    for (var i = 0u; i < 8u; i++) {
        var q = terms[i];
        for (var j = 0u; j < len; j++) {
            let r = two_sum(q, expansion[j]);
            q = r.x;
            expansion[j] = r.y;
        }
        expansion[len] = q;
        len++;
    }
    for (var k = 8u; k > 0u; k--) {
        let c = expansion[k - 1u];
        if (c > 0.0) {
            return 1;
        }
        if (c < 0.0) {
            return -1;
        }
    }
    return 0;
}

// The exact sign of `ax * by - ay * bx`. Rounded in f32 (fused or not) the
// difference is within 2^-22 (|ax by| + |ay bx|) of the truth; beyond that
// its sign is right, else the exact sum decides.
fn det_sign(ax: f32, ay: f32, bx: f32, by: f32, value: f32) -> i32 {
    let bound = 2.4e-7 * (abs(ax * by) + abs(ay * bx));
    if (value > bound) {
        return 1;
    }
    if (value < -bound) {
        return -1;
    }
    return det_sign_exact(ax, ay, bx, by);
}

// Edge function of `a -> b` (rounded; its sign is `edge_sign`).
fn edge_value(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.y - a.y * b.x;
}

// Side of the ray relative to `a -> b`: +1 or -1, ties broken by moving the
// ray by (eps, eps^2) in the projected plane; 0 only for an edge parallel
// to the ray. Antisymmetric.
fn edge_sign_of(a: vec3<f32>, b: vec3<f32>, value: f32) -> i32 {
    let s = det_sign(a.x, a.y, b.x, b.y, value);
    if (s != 0) {
        return s;
    }
    // The sign of an f32 difference is exact.
    let ey = b.y - a.y;
    if (ey != 0.0) {
        return select(-1, 1, ey < 0.0);
    }
    let ex = b.x - a.x;
    if (ex > 0.0) {
        return 1;
    }
    if (ex < 0.0) {
        return -1;
    }
    return 0;
}

fn edge_sign(a: vec3<f32>, b: vec3<f32>) -> i32 {
    return edge_sign_of(a, b, edge_value(a, b));
}

// Distance to the plane of the triangle where the ray crosses it, from the
// barycentric weights of the projected triangle, clamped into the vertices'
// range; and the weights (summing to 1).
struct Crossing {
    t: f32,
    weights: vec3<f32>,
}

fn crossing(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>) -> Crossing {
    let wa = edge_value(b, c);
    let wb = edge_value(c, a);
    let wc = edge_value(a, b);
    return crossing_from(vec3<f32>(wa, wb, wc), vec3<f32>(a.z, b.z, c.z));
}

fn crossing_from(w: vec3<f32>, z: vec3<f32>) -> Crossing {
    let sum = w.x + w.y + w.z;
    let lo = min(min(z.x, z.y), z.z);
    let hi = max(max(z.x, z.y), z.z);
    var out: Crossing;
    if (sum == 0.0) {
        // The ray in the plane of the face: the nearest vertex.
        out.t = lo;
        if (lo == z.x) {
            out.weights = vec3<f32>(1.0, 0.0, 0.0);
        } else if (lo == z.y) {
            out.weights = vec3<f32>(0.0, 1.0, 0.0);
        } else {
            out.weights = vec3<f32>(0.0, 0.0, 1.0);
        }
        return out;
    }
    let inv = 1.0 / sum;
    out.weights = w * inv;
    out.t = clamp((w.x * z.x + w.y * z.y + w.z * z.z) * inv, lo, hi);
    return out;
}
