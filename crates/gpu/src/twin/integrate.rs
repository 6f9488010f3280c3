//! Twin of shaders/integrate.wgsl: transfer-function sampling and every
//! method the kernel has, in the kernel's f32 arithmetic.

use glam::{Vec3, Vec4};

use tetray_integrate::Method;

use crate::layout::IntegratorParams;
use crate::upload::IntegratorData;

/// What integrate.wgsl reads: the integrator's parameter block, its tables
/// and the Psi table (the ray caster and the projection bind the same).
#[derive(Debug, Clone, Copy)]
pub struct IntegratorInputs<'a> {
    pub params: &'a IntegratorParams,
    pub tables: &'a [[f32; 4]],
    pub psi: &'a [f32],
}

impl<'a> IntegratorInputs<'a> {
    /// `params` (the block a frame uploads) with `data`'s tables.
    pub fn new(params: &'a IntegratorParams, data: &'a IntegratorData) -> Self {
        IntegratorInputs {
            params,
            tables: &data.tables,
            psi: &data.psi,
        }
    }
}

const SQRT_PI_2: f32 = 0.886_226_9;
const ALPHA_MAX: f32 = 0.999_999;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub lum: Vec3,
    pub q: Vec3,
    pub s: f32,
    pub interval: i32,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    pub emitted: Vec3,
    pub transmittance: Vec3,
}

const CLEAR: Light = Light {
    emitted: Vec3::ZERO,
    transmittance: Vec3::ONE,
};

fn then(front: Light, behind: Light) -> Light {
    Light {
        emitted: front.emitted + front.transmittance * behind.emitted,
        transmittance: front.transmittance * behind.transmittance,
    }
}

fn table(input: &IntegratorInputs, i: u32) -> Vec4 {
    Vec4::from_array(input.tables[i as usize])
}

pub fn in_interval(input: &IntegratorInputs, k: i32, s: f32) -> Sample {
    let base = 4 * (k + 1).clamp(0, input.params.knot_count as i32) as u32;
    let head = table(input, base);
    let slope = table(input, base + 1);
    let t = ((s - head.w) * slope.w).clamp(0.0, 1.0);
    Sample {
        lum: head.truncate() + slope.truncate() * t,
        q: table(input, base + 2).truncate() + table(input, base + 3).truncate() * t,
        s,
        interval: k,
    }
}

fn knot_scalar(input: &IntegratorInputs, k: u32) -> f32 {
    input.tables[4 * (k as usize + 1)][3]
}

fn interval_up(input: &IntegratorInputs, s: f32) -> i32 {
    let (mut lo, mut hi) = (0u32, input.params.knot_count);
    let mut i = 0;
    while i < 32 && lo < hi {
        let mid = (lo + hi) / 2;
        if knot_scalar(input, mid) <= s {
            lo = mid + 1;
        } else {
            hi = mid;
        }
        i += 1;
    }
    lo as i32 - 1
}

pub fn sample_at(input: &IntegratorInputs, s: f32) -> Sample {
    in_interval(input, interval_up(input, s), s)
}

pub fn sample_near(input: &IntegratorInputs, s: f32, near: &Sample) -> Sample {
    let k = near.interval;
    let last = input.params.knot_count as i32 - 1;
    let above_start = k < 0 || knot_scalar(input, k as u32) <= s;
    let below_end = k >= last || s < knot_scalar(input, (k + 1) as u32);
    if above_start && below_end {
        in_interval(input, k, s)
    } else {
        sample_at(input, s)
    }
}

fn psi_lookup(input: &IntegratorInputs, a: f32, b: f32) -> f32 {
    let n = input.params.psi_size;
    let last = (n - 1) as f32;
    let x = (1.0 - 1.0 / (1.0 + a).sqrt()).clamp(0.0, 1.0) * last;
    let y = (1.0 - 1.0 / (1.0 + b).sqrt()).clamp(0.0, 1.0) * last;
    let i = (x as u32).min(n - 2);
    let j = (y as u32).min(n - 2);
    let (fx, fy) = (x - i as f32, y - j as f32);
    let v = |i: u32, j: u32| input.psi[(j * n + i) as usize];
    let bottom = v(i, j) + (v(i + 1, j) - v(i, j)) * fx;
    let top = v(i, j + 1) + (v(i + 1, j + 1) - v(i, j + 1)) * fx;
    bottom + (top - bottom) * fy
}

fn ppi_weights(input: &IntegratorInputs, a: f32, b: f32) -> (f32, f32) {
    let zeta = (-0.5 * (a + b)).exp();
    (zeta, psi_lookup(input, a, b).clamp(zeta, 1.0))
}

fn average_weights(a: f32, b: f32) -> (f32, f32) {
    let zeta = (-0.5 * (a + b)).exp();
    (zeta, 0.5 * (1.0 + zeta))
}

fn log1p(x: f32) -> f32 {
    let u = 1.0 + x;
    if u == 1.0 {
        return x;
    }
    u.ln() * x / (u - 1.0)
}

fn psi_homogeneous(x: f32) -> f32 {
    if x < 1e-3 {
        return 1.0 - x * (0.5 - x / 6.0);
    }
    (1.0 - (-x).exp()) / x
}

fn opacity_weights(method: u32, alpha_back: f32, alpha_front: f32, units: f32) -> (f32, f32) {
    let ab = alpha_back.clamp(0.0, ALPHA_MAX);
    let af = alpha_front.clamp(0.0, ALPHA_MAX);
    let mean = 0.5 * (ab + af);
    if method == code(Method::AverageOpacity) {
        let zeta = (units * log1p(-mean)).exp();
        return (zeta, 0.5 * (1.0 + zeta));
    }
    if method == code(Method::LinAvgOpacity) {
        let tau_d = -units * log1p(-mean);
        return ((-tau_d).exp(), psi_homogeneous(tau_d));
    }
    let diff = ab - af;
    let alpha_zeta = (mean + 0.108_165 * diff * diff).clamp(0.0, ALPHA_MAX);
    let alpha_psi = (0.27 * ab + 0.73 * af).clamp(0.0, ALPHA_MAX);
    let zeta = (units * log1p(-alpha_zeta)).exp();
    (zeta, psi_homogeneous(-units * log1p(-alpha_psi)))
}

/// The kernel's f32 erfcx: `t exp(P(t))`, the project's degree-10 fit.
pub fn erfcx(x: f32) -> f32 {
    const P: [f32; 11] = [
        0.008_006_514,
        0.130_793_65,
        -0.736_885_14,
        1.388_085_2,
        -1.063_721_3,
        0.247_379_3,
        -0.177_843_81,
        0.095_483_57,
        0.374_193_7,
        1.000_020_6,
        -1.265_512_2,
    ];
    let t = 1.0 / (1.0 + 0.5 * x);
    let p = P.iter().fold(0.0f32, |p, &c| p * t + c);
    t * p.exp()
}

/// The kernel's f32 Dawson integral (series, Rybicki h = 0.4, asymptote).
pub fn dawson(x: f32) -> f32 {
    if x < 0.2 {
        let x2 = x * x;
        return x * (1.0 - 0.666_666_7 * x2 * (1.0 - 0.4 * x2 * (1.0 - 0.285_714_3 * x2)));
    }
    if x > 1e4 {
        return 0.5 / x;
    }
    let weights = [-0.16f32, -1.44, -4.0, -7.84, -12.96, -19.36].map(f32::exp);
    let n0 = 2.0 * (1.25 * x).round_ties_even();
    let xp = x - n0 * 0.4;
    let e_step = (1.6 * xp).exp();
    let mut e1 = (0.8 * xp).exp();
    let (mut d1, mut d2) = (n0 + 1.0, n0 - 1.0);
    let mut sum = 0.0;
    for w in weights {
        sum += w * (e1 / d1 + 1.0 / (d2 * e1));
        d1 += 2.0;
        d2 -= 2.0;
        e1 *= e_step;
    }
    0.564_189_6 * (-xp * xp).exp() * sum
}

/// The terms `(-1)^j / (j! (j + 7))` of `M_6(b)`, `j <= 15`, as the kernel
/// writes them.
const M6_SERIES: [f32; 16] = [
    1.4285715e-1,
    -1.25e-1,
    5.5555556e-2,
    -1.6666668e-2,
    3.787879e-3,
    -6.9444446e-4,
    1.0683761e-4,
    -1.4172336e-5,
    1.6534392e-6,
    -1.7223324e-7,
    1.6210187e-8,
    -1.3917838e-9,
    1.0987767e-10,
    -8.0295215e-12,
    5.46226e-13,
    -3.4759837e-14,
];

fn moments(b: f32) -> [f32; 4] {
    let e = (-b).exp();
    if b <= 2.0 {
        let b2 = b * b;
        let m6 = M6_SERIES.iter().rev().fold(0.0f32, |sum, &t| sum * b + t);
        let m4 = (b2 * m6 + e * (b + 6.0)) / 30.0;
        let m2 = (b2 * m4 + e * (b + 4.0)) / 12.0;
        let m0 = (b2 * m2 + e * (b + 2.0)) / 2.0;
        return [m0, m2, m4, m6];
    }
    let mut m = [0.0f32; 7];
    m[0] = (1.0 - e) / b;
    for k in 1..7 {
        m[k] = (k as f32 * m[k - 1] - e) / b;
    }
    [m[0], m[2], m[4], m[6]]
}

fn exact_weights(a: f32, b: f32) -> (f32, f32) {
    let zeta = (-0.5 * (a + b)).exp();
    let c = 0.5 * (a - b);
    let psi = if c.abs() < 0.01 {
        let m = moments(b);
        m[0] - c * (m[1] - c * (0.5 * m[2] - c * m[3] / 6.0))
    } else if c > 0.0 {
        let k = c.sqrt();
        SQRT_PI_2 / k * (erfcx(b / (2.0 * k)) - zeta * erfcx(a / (2.0 * k)))
    } else {
        let k = (-c).sqrt();
        (dawson(b / (2.0 * k)) - zeta * dawson(a / (2.0 * k))) / k
    };
    (zeta, psi.clamp(zeta, 1.0))
}

fn code(method: Method) -> u32 {
    method.gpu_code().expect("a GPU method")
}

fn channel_weights(input: &IntegratorInputs, q_back: f32, q_front: f32, d: f32) -> (f32, f32) {
    let method = input.params.method;
    if method == code(Method::Ppi) {
        ppi_weights(input, q_back * d, q_front * d)
    } else if method == code(Method::Exact) {
        exact_weights(q_back * d, q_front * d)
    } else if method == code(Method::Average) {
        average_weights(q_back * d, q_front * d)
    } else {
        opacity_weights(method, q_back, q_front, d * input.params.inv_unit_distance)
    }
}

fn piece_light(input: &IntegratorInputs, front: &Sample, back: &Sample, d: f32) -> Light {
    let (zeta, psi) = if input.params.grey == 1 {
        let (z, p) = channel_weights(input, back.q.x, front.q.x, d);
        (Vec3::splat(z), Vec3::splat(p))
    } else {
        let mut zeta = Vec3::ZERO;
        let mut psi = Vec3::ZERO;
        for c in 0..3 {
            let (z, p) = channel_weights(input, back.q[c], front.q[c], d);
            zeta[c] = z;
            psi[c] = p;
        }
        (zeta, psi)
    };
    Light {
        emitted: front.lum * (Vec3::ONE - psi) + back.lum * (psi - zeta),
        transmittance: zeta,
    }
}

fn split_light(input: &IntegratorInputs, front: &Sample, back: &Sample, length: f32) -> Light {
    if front.interval == back.interval || input.params.split == 0 {
        return piece_light(input, front, back, length);
    }
    let span = back.s - front.s;
    let per_scalar = length / span.abs();
    let increasing = span > 0.0;
    let last = input.params.knot_count as i32 - 1;
    let mut k = front.interval;
    if !increasing && k >= 0 && knot_scalar(input, k as u32) == front.s {
        k -= 1;
    }
    let mut s = front.s;
    let mut light = CLEAR;
    let mut first = true;
    for _ in 0..=input.params.knot_count + 1 {
        let (bound, next) = if increasing {
            let bound = if k < last {
                knot_scalar(input, (k + 1) as u32)
            } else {
                3.4e38
            };
            (bound, k + 1)
        } else {
            let bound = if k >= 0 {
                knot_scalar(input, k.max(0) as u32)
            } else {
                -3.4e38
            };
            (bound, k - 1)
        };
        let reached = if increasing {
            bound >= back.s
        } else {
            bound <= back.s
        };
        let s_end = if reached { back.s } else { bound };
        let mut d = (s_end - s).abs() * per_scalar;
        if reached && first {
            d = length;
        }
        if d > 0.0 || reached {
            let piece = piece_light(
                input,
                &in_interval(input, k, s),
                &in_interval(input, k, s_end),
                d,
            );
            light = then(light, piece);
            first = false;
        }
        if reached {
            break;
        }
        s = s_end;
        k = next;
    }
    light
}

fn riemann_light(input: &IntegratorInputs, s_front: f32, s_back: f32, length: f32) -> Light {
    let steps = (length / input.params.riemann_step)
        .ceil()
        .clamp(1.0, 65536.0) as u32;
    let h = length / steps as f32;
    let mut light = CLEAR;
    for k in 0..steps {
        let t = (k as f32 + 0.5) / steps as f32;
        let m = sample_at(input, s_front + (s_back - s_front) * t);
        let zeta = (-m.q * h).exp();
        light = then(
            light,
            Light {
                emitted: m.lum * (Vec3::ONE - zeta),
                transmittance: zeta,
            },
        );
    }
    light
}

fn preintegrated_light(input: &IntegratorInputs, s_front: f32, s_back: f32, length: f32) -> Light {
    let p = input.params;
    let n = p.preint_size;
    let last = (n - 1) as f32;
    let x = ((s_front - p.preint_lo) * p.preint_scale).clamp(0.0, last);
    let y = ((s_back - p.preint_lo) * p.preint_scale).clamp(0.0, last);
    let i = (x as u32).min(n - 2);
    let j = (y as u32).min(n - 2);
    let (ti, tj) = (x - i as f32, y - j as f32);
    let r0 = p.preint_offset + 2 * (i * n + j);
    let r1 = r0 + 2 * n;
    let mix = |a: Vec4, b: Vec4, t: f32| a + (b - a) * t;
    let at = |r: u32| table(input, r);
    let e = mix(mix(at(r0), at(r0 + 2), tj), mix(at(r1), at(r1 + 2), tj), ti);
    let tr = mix(
        mix(at(r0 + 1), at(r0 + 3), tj),
        mix(at(r1 + 1), at(r1 + 3), tj),
        ti,
    );
    let ratio = length / p.preint_length;
    if ratio == 1.0 {
        return Light {
            emitted: e.truncate(),
            transmittance: tr.truncate(),
        };
    }
    let mut out = CLEAR;
    for c in 0..3 {
        let t = tr[c].clamp(0.0, 1.0);
        let t_new = t.powf(ratio);
        out.transmittance[c] = t_new;
        out.emitted[c] = if 1.0 - t > 1e-6 {
            e[c] * (1.0 - t_new) / (1.0 - t)
        } else {
            e[c] * ratio
        };
    }
    out
}

pub fn segment_light(
    input: &IntegratorInputs,
    front: &Sample,
    back: &Sample,
    length: f32,
) -> Light {
    if length.is_nan() || length <= 0.0 {
        return CLEAR;
    }
    let method = input.params.method;
    if method == code(Method::Riemann) {
        return riemann_light(input, front.s, back.s, length);
    }
    if method == code(Method::Preintegrated) {
        return preintegrated_light(input, front.s, back.s, length);
    }
    split_light(input, front, back, length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tetray_integrate::special;

    #[test]
    fn f32_special_functions_match_f64() {
        let mut worst: (f64, f64) = (0.0, 0.0);
        for i in 0..20_000 {
            let x = if i < 10_000 {
                i as f32 * 5e-4
            } else {
                (i - 10_000) as f32 * 0.5
            };
            let e =
                (f64::from(erfcx(x)) - special::erfcx(f64::from(x))) / special::erfcx(f64::from(x));
            worst.0 = worst.0.max(e.abs());
            if x > 0.0 {
                let f = special::dawson(f64::from(x));
                worst.1 = worst.1.max(((f64::from(dawson(x)) - f) / f).abs());
            }
        }
        // The fit's measured 4e-7 plus f32 evaluation; Rybicki's h = 0.4.
        assert!(worst.0 < 1e-6 && worst.1 < 1e-6, "{worst:?}");
    }

    #[test]
    fn f32_moments_match_gauss_legendre() {
        // Series and backward recurrence up to b = 2, forward recurrence
        // above; 16-point Gauss-Legendre in f64 is exact far beyond f32.
        for i in 0..=300 {
            let b = 3.0 * i as f32 / 300.0;
            let m = moments(b);
            for (n, &got) in m.iter().enumerate() {
                let k = 2 * n as i32;
                let want = special::gauss_legendre_panel(0.0, 1.0, |x| {
                    x.powi(k) * (-f64::from(b) * x).exp()
                });
                // A few f32 ulp (measured at most 6.8e-7 up to b = 2); the
                // forward recurrence above b = 2 multiplies rounding by up
                // to k! / b^k per moment (11 for M_6), measured 1.7e-6 for
                // M_4 and 1.9e-5 for M_6, which enter Psi times c^2 / 2 and
                // c^3 / 6 (below 5e-5 and 2e-7).
                let tolerance = match (b <= 2.0, k) {
                    (true, _) | (false, 0 | 2) => 1e-6,
                    (false, 4) => 5e-6,
                    _ => 5e-5,
                };
                assert!(
                    ((f64::from(got) - want) / want).abs() < tolerance,
                    "M_{k}({b}): f32 {got}, f64 {want}"
                );
            }
        }
    }

    #[test]
    fn f32_exact_weights_match_the_f64_closed_form() {
        let depths = [0.0f32, 1e-3, 0.02, 0.3, 1.0, 2.5, 9.0, 60.0, 500.0];
        for &a in &depths {
            for &b in &depths {
                let (_, psi) = exact_weights(a, b);
                let (_, want) = tetray_integrate::exact::exact_zeta_psi(f64::from(a), f64::from(b));
                assert!(
                    (f64::from(psi) - want).abs() < 2e-6,
                    "Psi({a}, {b}): f32 {psi}, f64 {want}"
                );
            }
        }
    }
}
