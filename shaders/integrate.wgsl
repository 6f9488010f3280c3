// The volume rendering integral of one segment (CPU twin:
// tetray_gpu::twin::integrate; the f64 originals are in tetray_integrate).
// Every method but the Riemann sum and full pre-integration reduces to the
// two numbers of eq. 5.5, zeta and Psi:
// I = I0 zeta + L_b (Psi - zeta) + L_f (1 - Psi).
//
// Shared by the ray caster and the cell projection (tetray_project): the
// including module declares `params` with an `integrator: IntegratorParams`
// member (params.wgsl), the `tables` storage array and the `psi_table`
// texture; the METHOD_* codes come first (tetray_core::Method::gpu_code).

const SQRT_PI_2: f32 = 0.88622693;
const ALPHA_MAX: f32 = 0.999999;

// A classified scalar: its knot interval (right-continuous, -1 below the
// first knot) and its luminance and quantity q (attenuation per world unit
// for the attenuation methods, opacity of a unit distance for the opacity
// methods), per channel.
struct Sample {
    lum: vec3<f32>,
    q: vec3<f32>,
    s: f32,
    interval: i32,
}

// Transfer-function interval k (from -1 to knot_count - 1): four entries
// at 4 (k + 1): lum start + x0, lum delta + 1 / width, q start, q delta.
fn in_interval(k: i32, s: f32) -> Sample {
    let base = 4u * u32(clamp(k + 1, 0, i32(params.integrator.knot_count)));
    let head = tables[base];
    let slope = tables[base + 1u];
    let t = clamp((s - head.w) * slope.w, 0.0, 1.0);
    var out: Sample;
    out.lum = head.xyz + slope.xyz * t;
    out.q = tables[base + 2u].xyz + tables[base + 3u].xyz * t;
    out.s = s;
    out.interval = k;
    return out;
}

fn knot_scalar(k: u32) -> f32 {
    return tables[4u * (k + 1u)].w;
}

// The number of knots at or below s, minus one.
fn interval_up(s: f32) -> i32 {
    var lo = 0u;
    var hi = params.integrator.knot_count;
    // At most 32 halvings for any u32 count.
    for (var i = 0u; i < 32u && lo < hi; i++) {
        let mid = (lo + hi) / 2u;
        if (knot_scalar(mid) <= s) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return i32(lo) - 1;
}

fn sample_at(s: f32) -> Sample {
    return in_interval(interval_up(s), s);
}

// sample_at, trying the interval of a nearby sample first.
fn sample_near(s: f32, near: Sample) -> Sample {
    let k = near.interval;
    let last = i32(params.integrator.knot_count) - 1;
    let above_start = k < 0 || knot_scalar(u32(k)) <= s;
    let below_end = k >= last || s < knot_scalar(u32(k + 1));
    if (above_start && below_end) {
        return in_interval(k, s);
    }
    return sample_at(s);
}

struct Light {
    emitted: vec3<f32>,
    transmittance: vec3<f32>,
}

// `front` in front of `behind` (front-to-back compositing, eq. 2.13).
fn then(front: Light, behind: Light) -> Light {
    return Light(front.emitted + front.transmittance * behind.emitted,
                 front.transmittance * behind.transmittance);
}

// ---- Psi and zeta ------------------------------------------------------

// Bilinear lookup of the Psi table by (tau_b D, tau_f D): nodes uniform in
// u = 1 - 1/sqrt(1 + tau D) (tetray_integrate::GammaSpacing::Quadratic).
fn psi_lookup(a: f32, b: f32) -> f32 {
    let last = f32(params.integrator.psi_size - 1u);
    let x = clamp(1.0 - 1.0 / sqrt(1.0 + a), 0.0, 1.0) * last;
    let y = clamp(1.0 - 1.0 / sqrt(1.0 + b), 0.0, 1.0) * last;
    let i = min(u32(x), params.integrator.psi_size - 2u);
    let j = min(u32(y), params.integrator.psi_size - 2u);
    let fx = x - f32(i);
    let fy = y - f32(j);
    let v00 = textureLoad(psi_table, vec2<u32>(i, j), 0).x;
    let v10 = textureLoad(psi_table, vec2<u32>(i + 1u, j), 0).x;
    let v01 = textureLoad(psi_table, vec2<u32>(i, j + 1u), 0).x;
    let v11 = textureLoad(psi_table, vec2<u32>(i + 1u, j + 1u), 0).x;
    let bottom = v00 + (v10 - v00) * fx;
    let top = v01 + (v11 - v01) * fx;
    return bottom + (top - bottom) * fy;
}

fn ppi_weights(a: f32, b: f32) -> vec2<f32> {
    let zeta = exp(-0.5 * (a + b));
    // Psi is a mean transmittance: within [zeta, 1].
    return vec2<f32>(zeta, clamp(psi_lookup(a, b), zeta, 1.0));
}

fn average_weights(a: f32, b: f32) -> vec2<f32> {
    let zeta = exp(-0.5 * (a + b));
    return vec2<f32>(zeta, 0.5 * (1.0 + zeta));
}

// ln(1 + x) without the cancellation of log(1 + x) for small x.
fn log1p(x: f32) -> f32 {
    let u = 1.0 + x;
    if (u == 1.0) {
        return x;
    }
    return log(u) * x / (u - 1.0);
}

// (1 - exp(-x)) / x, 1 at 0.
fn psi_homogeneous(x: f32) -> f32 {
    if (x < 1e-3) {
        return 1.0 - x * (0.5 - x / 6.0);
    }
    return (1.0 - exp(-x)) / x;
}

fn opacity_weights(method: u32, alpha_back: f32, alpha_front: f32, units: f32) -> vec2<f32> {
    let ab = clamp(alpha_back, 0.0, ALPHA_MAX);
    let af = clamp(alpha_front, 0.0, ALPHA_MAX);
    let mean = 0.5 * (ab + af);
    if (method == METHOD_AVERAGE_OPACITY) {
        let zeta = exp(units * log1p(-mean));
        return vec2<f32>(zeta, 0.5 * (1.0 + zeta));
    }
    if (method == METHOD_LIN_AVG_OPACITY) {
        // Section 5.3.1.
        let tau_d = -units * log1p(-mean);
        return vec2<f32>(exp(-tau_d), psi_homogeneous(tau_d));
    }
    // Section 5.3.2: eq. 5.13 for zeta, eq. 5.14 for Psi.
    let diff = ab - af;
    let alpha_zeta = clamp(mean + 0.108165 * diff * diff, 0.0, ALPHA_MAX);
    let alpha_psi = clamp(0.27 * ab + 0.73 * af, 0.0, ALPHA_MAX);
    let zeta = exp(units * log1p(-alpha_zeta));
    return vec2<f32>(zeta, psi_homogeneous(-units * log1p(-alpha_psi)));
}

// exp(x^2) erfc(x) for x >= 0: t exp(P(t)), t = 1 / (1 + x/2), with P a
// degree-10 least-squares fit to ln(erfcx(x) / t) over (0, 1] (max relative
// error 4e-7 in f32; fitted for this project against the f64 erfcx).
fn erfcx(x: f32) -> f32 {
    let t = 1.0 / (1.0 + 0.5 * x);
    var p = 0.008006514;
    p = p * t + 0.13079365;
    p = p * t - 0.73688514;
    p = p * t + 1.3880852;
    p = p * t - 1.0637213;
    p = p * t + 0.2473793;
    p = p * t - 0.17784381;
    p = p * t + 0.09548357;
    p = p * t + 0.3741937;
    p = p * t + 1.0000206;
    p = p * t - 1.2655122;
    return t * exp(p);
}

// Dawson's integral for x >= 0: its series below 0.2, else Rybicki's
// sampling formula with h = 0.4 and six pairs of terms (error 2e-7).
fn dawson(x: f32) -> f32 {
    if (x < 0.2) {
        let x2 = x * x;
        return x * (1.0 - 0.6666667 * x2 * (1.0 - 0.4 * x2 * (1.0 - 0.2857143 * x2)));
    }
    if (x > 1e4) {
        return 0.5 / x;
    }
    // exp(-((2k+1) h)^2), h = 0.4.
    var weights = array<f32, 6>(exp(-0.16), exp(-1.44), exp(-4.0), exp(-7.84), exp(-12.96), exp(-19.36));
    let n0 = 2.0 * round(1.25 * x);
    let xp = x - n0 * 0.4;
    let e_step = exp(1.6 * xp);
    var e1 = exp(0.8 * xp);
    var d1 = n0 + 1.0;
    var d2 = n0 - 1.0;
    var sum = 0.0;
    for (var k = 0u; k < 6u; k++) {
        sum += weights[k] * (e1 / d1 + 1.0 / (d2 * e1));
        d1 += 2.0;
        d2 -= 2.0;
        e1 *= e_step;
    }
    return 0.5641896 * exp(-xp * xp) * sum;
}

// M_k(b) = int_0^1 x^k exp(-b x) dx for k = 0, 2, 4, 6.
fn moments(b: f32) -> vec4<f32> {
    let e = exp(-b);
    if (b <= 2.0) {
        // M_6 by its series, sum_j (-1)^j b^j / (j! (j + 7)) for j <= 15 (the
        // first omitted term is below 1.4e-10 at b = 2), then the backward
        // recurrence two steps at a time,
        // M_{k-2} = (b^2 M_k + exp(-b) (b + k)) / (k (k - 1)), which damps
        // errors (tetray_integrate::exact has the derivation).
        let b2 = b * b;
        var m6 = -3.4759837e-14;
        m6 = m6 * b + 5.46226e-13;
        m6 = m6 * b + -8.0295215e-12;
        m6 = m6 * b + 1.0987767e-10;
        m6 = m6 * b + -1.3917838e-9;
        m6 = m6 * b + 1.6210187e-8;
        m6 = m6 * b + -1.7223324e-7;
        m6 = m6 * b + 1.6534392e-6;
        m6 = m6 * b + -1.4172336e-5;
        m6 = m6 * b + 1.0683761e-4;
        m6 = m6 * b + -6.9444446e-4;
        m6 = m6 * b + 3.787879e-3;
        m6 = m6 * b + -1.6666668e-2;
        m6 = m6 * b + 5.5555556e-2;
        m6 = m6 * b + -1.25e-1;
        m6 = m6 * b + 1.4285715e-1;
        let m4 = (b2 * m6 + e * (b + 6.0)) / 30.0;
        let m2 = (b2 * m4 + e * (b + 4.0)) / 12.0;
        let m0 = (b2 * m2 + e * (b + 2.0)) / 2.0;
        return vec4<f32>(m0, m2, m4, m6);
    }
    var m: array<f32, 7>;
    m[0] = (1.0 - e) / b;
    for (var k = 1u; k < 7u; k++) {
        m[k] = (f32(k) * m[k - 1u] - e) / b;
    }
    return vec4<f32>(m[0], m[2], m[4], m[6]);
}

// Williams-Max-Stein (eq. 3.28) through eq. 5.5, in f32: Psi in the scaled
// erfcx / Dawson forms, its series in c = (a - b)/2 near constant
// attenuation (tetray_integrate::exact has the derivation).
fn exact_weights(a: f32, b: f32) -> vec2<f32> {
    let zeta = exp(-0.5 * (a + b));
    let c = 0.5 * (a - b);
    var psi: f32;
    if (abs(c) < 0.01) {
        let m = moments(b);
        psi = m.x - c * (m.y - c * (0.5 * m.z - c * m.w / 6.0));
    } else if (c > 0.0) {
        let k = sqrt(c);
        psi = SQRT_PI_2 / k * (erfcx(b / (2.0 * k)) - zeta * erfcx(a / (2.0 * k)));
    } else {
        let k = sqrt(-c);
        psi = (dawson(b / (2.0 * k)) - zeta * dawson(a / (2.0 * k))) / k;
    }
    return vec2<f32>(zeta, clamp(psi, zeta, 1.0));
}

// (zeta, Psi) of one channel for the method, from the end values of its
// quantity (attenuation, or opacity) and the piece length.
fn channel_weights(q_back: f32, q_front: f32, d: f32) -> vec2<f32> {
    switch params.integrator.method {
        case METHOD_PPI: {
            return ppi_weights(q_back * d, q_front * d);
        }
        case METHOD_EXACT: {
            return exact_weights(q_back * d, q_front * d);
        }
        case METHOD_AVERAGE: {
            return average_weights(q_back * d, q_front * d);
        }
        default: {
            return opacity_weights(params.integrator.method, q_back, q_front, d * params.integrator.inv_unit_distance);
        }
    }
}

// One piece with linear material between `front` and `back`.
fn piece_light(front: Sample, back: Sample, d: f32) -> Light {
    var zeta: vec3<f32>;
    var psi: vec3<f32>;
    if (params.integrator.grey == 1u) {
        let w = channel_weights(back.q.x, front.q.x, d);
        zeta = vec3<f32>(w.x);
        psi = vec3<f32>(w.y);
    } else {
        for (var c = 0; c < 3; c++) {
            let w = channel_weights(back.q[c], front.q[c], d);
            zeta[c] = w.x;
            psi[c] = w.y;
        }
    }
    return Light(front.lum * (vec3<f32>(1.0) - psi) + back.lum * (psi - zeta), zeta);
}

// A segment between two classified scalars, cut at the knots between them
// (adaptive transfer-function sampling, section 4.3) unless split is off.
fn split_light(front: Sample, back: Sample, length: f32) -> Light {
    if (front.interval == back.interval || params.integrator.split == 0u) {
        return piece_light(front, back, length);
    }
    let span = back.s - front.s;
    let per_scalar = length / abs(span);
    let increasing = span > 0.0;
    let last = i32(params.integrator.knot_count) - 1;
    // The interval holding the front scalar in the direction of travel.
    var k = front.interval;
    if (!increasing && k >= 0 && knot_scalar(u32(k)) == front.s) {
        k -= 1;
    }
    var s = front.s;
    var light = Light(vec3<f32>(0.0), vec3<f32>(1.0));
    var first = true;
    for (var guard = 0u; guard <= params.integrator.knot_count + 1u; guard++) {
        var bound: f32;
        var next: i32;
        if (increasing) {
            bound = select(3.4e38, knot_scalar(u32(k + 1)), k < last);
            next = k + 1;
        } else {
            bound = select(-3.4e38, knot_scalar(u32(max(k, 0))), k >= 0);
            next = k - 1;
        }
        let reached = select(bound <= back.s, bound >= back.s, increasing);
        let s_end = select(bound, back.s, reached);
        var d = abs(s_end - s) * per_scalar;
        if (reached && first) {
            d = length;
        }
        if (d > 0.0 || reached) {
            light = then(light, piece_light(in_interval(k, s), in_interval(k, s_end), d));
            first = false;
        }
        if (reached) {
            break;
        }
        s = s_end;
        k = next;
    }
    return light;
}

// ---- Methods that see the transfer function themselves -----------------

// Eq. 3.13: homogeneous steps at the midpoints of equal sub-segments.
fn riemann_light(s_front: f32, s_back: f32, length: f32) -> Light {
    let steps = u32(clamp(ceil(length / params.integrator.riemann_step), 1.0, 65536.0));
    let h = length / f32(steps);
    var light = Light(vec3<f32>(0.0), vec3<f32>(1.0));
    for (var k = 0u; k < steps; k++) {
        let t = (f32(k) + 0.5) / f32(steps);
        let m = sample_at(s_front + (s_back - s_front) * t);
        let zeta = exp(-m.q * h);
        light = then(light, Light(m.lum * (vec3<f32>(1.0) - zeta), zeta));
    }
    return light;
}

// Full pre-integration: bilinear in (s_front, s_back), corrected from the
// table's length to `length` (T' = T^r, C' = C (1 - T') / (1 - T)).
fn preintegrated_light(s_front: f32, s_back: f32, length: f32) -> Light {
    let n = params.integrator.preint_size;
    let last = f32(n - 1u);
    let x = clamp((s_front - params.integrator.preint_lo) * params.integrator.preint_scale, 0.0, last);
    let y = clamp((s_back - params.integrator.preint_lo) * params.integrator.preint_scale, 0.0, last);
    let i = min(u32(x), n - 2u);
    let j = min(u32(y), n - 2u);
    let ti = x - f32(i);
    let tj = y - f32(j);
    let r0 = params.integrator.preint_offset + 2u * (i * n + j);
    let r1 = r0 + 2u * n;
    let e = mix(mix(tables[r0], tables[r0 + 2u], tj), mix(tables[r1], tables[r1 + 2u], tj), ti);
    let tr = mix(mix(tables[r0 + 1u], tables[r0 + 3u], tj), mix(tables[r1 + 1u], tables[r1 + 3u], tj), ti);
    let ratio = length / params.integrator.preint_length;
    if (ratio == 1.0) {
        return Light(e.xyz, tr.xyz);
    }
    var out: Light;
    for (var c = 0; c < 3; c++) {
        let t = clamp(tr[c], 0.0, 1.0);
        let t_new = pow(t, ratio);
        out.transmittance[c] = t_new;
        if (1.0 - t > 1e-6) {
            out.emitted[c] = e[c] * (1.0 - t_new) / (1.0 - t);
        } else {
            out.emitted[c] = e[c] * ratio;
        }
    }
    return out;
}

// The light of a segment `length` long with scalar from `front.s` to
// `back.s`, by the frame's method.
fn segment_light(front: Sample, back: Sample, length: f32) -> Light {
    if (!(length > 0.0)) {
        return Light(vec3<f32>(0.0), vec3<f32>(1.0));
    }
    if (params.integrator.method == METHOD_RIEMANN) {
        return riemann_light(front.s, back.s, length);
    }
    if (params.integrator.method == METHOD_PREINTEGRATED) {
        return preintegrated_light(front.s, back.s, length);
    }
    return split_light(front, back, length);
}
