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

// Exact products in integers: the float pipeline of a driver may reorder
// or fuse additions (SPIR-V from WGSL carries no "exact" marks), which
// would break float error-free transformations; integer arithmetic it
// cannot touch.

// |x| = m * 2^(e - 150): the significand as an integer and the exponent.
struct Unpacked {
    m: u32,
    e: i32,
    negative: bool,
}

fn unpack(x: f32) -> Unpacked {
    let bits = bitcast<u32>(x);
    let biased = (bits >> 23u) & 0xffu;
    var m = bits & 0x7fffffu;
    var e = i32(biased);
    if (biased == 0u) {
        // Subnormal (or zero): no implicit bit, the smallest exponent.
        e = 1;
    } else {
        m |= 0x800000u;
    }
    return Unpacked(m, e, (bits >> 31u) == 1u);
}

// The exact 48-bit product of two 24-bit integers as (high, low) words.
fn mul48(a: u32, b: u32) -> vec2<u32> {
    let a1 = a >> 12u;
    let a0 = a & 0xfffu;
    let b1 = b >> 12u;
    let b0 = b & 0xfffu;
    let high_part = a1 * b1;
    let middle = a1 * b0 + a0 * b1;
    let low_part = a0 * b0;
    // high_part << 24 + middle << 12 + low_part, with carries.
    let lo1 = low_part + (middle << 12u);
    let carry1 = select(0u, 1u, lo1 < low_part);
    let lo2 = lo1 + (high_part << 24u);
    let carry2 = select(0u, 1u, lo2 < lo1);
    return vec2<u32>((middle >> 20u) + (high_part >> 8u) + carry1 + carry2, lo2);
}

// |x y| as (exponent, high, low) with the leading bit of the 64-bit
// significand at bit 47, comparable lexicographically; (-huge, 0, 0) for 0.
struct Magnitude {
    e: i32,
    hi: u32,
    lo: u32,
    zero: bool,
    negative: bool,
}

fn product_magnitude(x: f32, y: f32) -> Magnitude {
    let a = unpack(x);
    let b = unpack(y);
    var p = mul48(a.m, b.m);
    var out: Magnitude;
    out.negative = a.negative != b.negative;
    out.zero = p.x == 0u && p.y == 0u;
    if (out.zero) {
        out.e = -100000;
        out.hi = 0u;
        out.lo = 0u;
        return out;
    }
    var lz: u32;
    if (p.x != 0u) {
        lz = countLeadingZeros(p.x);
    } else {
        lz = 32u + countLeadingZeros(p.y);
    }
    // Shift left so the leading bit is bit 47 (bit 15 of the high word).
    let shift = lz - 16u;
    if (shift >= 32u) {
        p = vec2<u32>(p.y << (shift - 32u), 0u);
    } else if (shift > 0u) {
        p = vec2<u32>((p.x << shift) | (p.y >> (32u - shift)), p.y << shift);
    }
    out.e = a.e + b.e - i32(shift);
    out.hi = p.x;
    out.lo = p.y;
    return out;
}

// -1, 0 or 1 as |p| is below, equal to or above |q|.
fn compare_magnitudes(p: Magnitude, q: Magnitude) -> i32 {
    if (p.e != q.e) {
        return select(-1, 1, p.e > q.e);
    }
    if (p.hi != q.hi) {
        return select(-1, 1, p.hi > q.hi);
    }
    if (p.lo != q.lo) {
        return select(-1, 1, p.lo > q.lo);
    }
    return 0;
}

// The exact sign of `ax * by - ay * bx`: both products exactly, as
// integers, then compared.
fn det_sign_exact(ax: f32, ay: f32, bx: f32, by: f32) -> i32 {
    let p = product_magnitude(ax, by);
    let q = product_magnitude(ay, bx);
    let sp = select(select(1, -1, p.negative), 0, p.zero);
    let sq = select(select(1, -1, q.negative), 0, q.zero);
    if (sq == 0) {
        return sp;
    }
    if (sp == 0) {
        return -sq;
    }
    if (sp != sq) {
        return sp;
    }
    return sp * compare_magnitudes(p, q);
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
