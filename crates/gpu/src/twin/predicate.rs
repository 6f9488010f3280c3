//! Twin of shaders/predicate.wgsl: the ray frame, projection, the exact
//! filtered edge predicate and the crossing weights, in the same f32
//! operations in the same order.

use glam::Vec3;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
    pub u: Vec3,
    pub v: Vec3,
}

pub fn make_ray(origin: Vec3, direction: Vec3) -> Ray {
    let len2 = direction.x * direction.x + direction.y * direction.y + direction.z * direction.z;
    let dir = direction * (1.0 / len2.sqrt());
    let sign = if dir.z.to_bits() >> 31 == 1 {
        -1.0
    } else {
        1.0
    };
    let a = -1.0 / (sign + dir.z);
    let b = dir.x * dir.y * a;
    Ray {
        origin,
        dir,
        u: Vec3::new(1.0 + sign * dir.x * dir.x * a, sign * b, -sign * dir.x),
        v: Vec3::new(b, sign + dir.y * dir.y * a, -dir.y),
    }
}

pub fn project(ray: &Ray, p: Vec3) -> Vec3 {
    let d = p - ray.origin;
    Vec3::new(
        d.x * ray.u.x + d.y * ray.u.y + d.z * ray.u.z,
        d.x * ray.v.x + d.y * ray.v.y + d.z * ray.v.z,
        d.x * ray.dir.x + d.y * ray.dir.y + d.z * ray.dir.z,
    )
}

/// `|x| = m 2^(e - 150)`: significand, exponent, sign.
fn unpack(x: f32) -> (u32, i32, bool) {
    let bits = x.to_bits();
    let biased = (bits >> 23) & 0xff;
    let m = bits & 0x7f_ffff;
    if biased == 0 {
        (m, 1, bits >> 31 == 1)
    } else {
        (m | 0x80_0000, biased as i32, bits >> 31 == 1)
    }
}

/// The exact 48-bit product as (high, low) words, assembled from 12-bit
/// halves with 32-bit wrapping arithmetic, as the kernel does.
fn mul48(a: u32, b: u32) -> (u32, u32) {
    let (a1, a0, b1, b0) = (a >> 12, a & 0xfff, b >> 12, b & 0xfff);
    let high_part = a1 * b1;
    let middle = a1 * b0 + a0 * b1;
    let low_part = a0 * b0;
    let lo1 = low_part.wrapping_add(middle << 12);
    let carry1 = u32::from(lo1 < low_part);
    let lo2 = lo1.wrapping_add(high_part << 24);
    let carry2 = u32::from(lo2 < lo1);
    ((middle >> 20) + (high_part >> 8) + carry1 + carry2, lo2)
}

/// `|x y|` as (exponent, high, low) normalised to bit 47, or `None` for 0;
/// and whether the product is negative.
fn product_magnitude(x: f32, y: f32) -> (Option<(i32, u32, u32)>, bool) {
    let (ma, ea, na) = unpack(x);
    let (mb, eb, nb) = unpack(y);
    let (hi, lo) = mul48(ma, mb);
    if hi == 0 && lo == 0 {
        return (None, na != nb);
    }
    let lz = if hi != 0 {
        hi.leading_zeros()
    } else {
        32 + lo.leading_zeros()
    };
    let shift = lz - 16;
    let (hi, lo) = if shift >= 32 {
        (lo << (shift - 32), 0)
    } else if shift > 0 {
        ((hi << shift) | (lo >> (32 - shift)), lo << shift)
    } else {
        (hi, lo)
    };
    (Some((ea + eb - shift as i32, hi, lo)), na != nb)
}

/// The exact sign of `ax * by - ay * bx`: both products exactly as
/// integers, then compared (the kernel's rule, in the same steps).
pub fn det_sign_exact(ax: f32, ay: f32, bx: f32, by: f32) -> i32 {
    let (p, p_negative) = product_magnitude(ax, by);
    let (q, q_negative) = product_magnitude(ay, bx);
    let sign = |m: &Option<(i32, u32, u32)>, negative: bool| match m {
        None => 0,
        Some(_) if negative => -1,
        Some(_) => 1,
    };
    let (sp, sq) = (sign(&p, p_negative), sign(&q, q_negative));
    if sq == 0 {
        return sp;
    }
    if sp == 0 {
        return -sq;
    }
    if sp != sq {
        return sp;
    }
    match p.cmp(&q) {
        std::cmp::Ordering::Less => -sp,
        std::cmp::Ordering::Equal => 0,
        std::cmp::Ordering::Greater => sp,
    }
}

pub fn det_sign(ax: f32, ay: f32, bx: f32, by: f32, value: f32) -> i32 {
    let bound = 2.4e-7 * ((ax * by).abs() + (ay * bx).abs());
    if value > bound {
        return 1;
    }
    if value < -bound {
        return -1;
    }
    det_sign_exact(ax, ay, bx, by)
}

pub fn edge_value(a: Vec3, b: Vec3) -> f32 {
    a.x * b.y - a.y * b.x
}

pub fn edge_sign_of(a: Vec3, b: Vec3, value: f32) -> i32 {
    let s = det_sign(a.x, a.y, b.x, b.y, value);
    if s != 0 {
        return s;
    }
    let ey = b.y - a.y;
    if ey != 0.0 {
        return if ey < 0.0 { 1 } else { -1 };
    }
    let ex = b.x - a.x;
    if ex > 0.0 {
        1
    } else if ex < 0.0 {
        -1
    } else {
        0
    }
}

pub fn edge_sign(a: Vec3, b: Vec3) -> i32 {
    edge_sign_of(a, b, edge_value(a, b))
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    pub t: f32,
    pub weights: Vec3,
}

pub fn crossing(a: Vec3, b: Vec3, c: Vec3) -> Crossing {
    let w = Vec3::new(edge_value(b, c), edge_value(c, a), edge_value(a, b));
    crossing_from(w, Vec3::new(a.z, b.z, c.z))
}

pub fn crossing_from(w: Vec3, z: Vec3) -> Crossing {
    let sum = w.x + w.y + w.z;
    let lo = z.x.min(z.y).min(z.z);
    let hi = z.x.max(z.y).max(z.z);
    if sum == 0.0 {
        let weights = if lo == z.x {
            Vec3::X
        } else if lo == z.y {
            Vec3::Y
        } else {
            Vec3::Z
        };
        return Crossing { t: lo, weights };
    }
    let inv = 1.0 / sum;
    Crossing {
        t: ((w.x * z.x + w.y * z.y + w.z * z.z) * inv).clamp(lo, hi),
        weights: w * inv,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sign of `ax by - ay bx` in f64, where f32 products are exact.
    fn sign_f64(ax: f32, ay: f32, bx: f32, by: f32) -> i32 {
        let v = f64::from(ax) * f64::from(by) - f64::from(ay) * f64::from(bx);
        (v > 0.0) as i32 - (v < 0.0) as i32
    }

    #[test]
    fn exact_sign_agrees_with_f64_on_near_degenerate_inputs() {
        // Nearly collinear pairs: (bx, by) = k (ax, ay) perturbed by an ulp
        // or two, at many scales, where the f32 difference is all rounding.
        let mut seed = 0x9e37_79b9_u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed
        };
        let mut checked = 0;
        for _ in 0..200_000 {
            let scale = 2f32.powi((next() % 40) as i32 - 20);
            let ax = (next() as f32 / u32::MAX as f32 - 0.5) * scale;
            let ay = (next() as f32 / u32::MAX as f32 - 0.5) * scale;
            let k = next() as f32 / u32::MAX as f32 * 3.0 - 1.5;
            let nudge =
                |x: f32, n: u32| f32::from_bits(x.to_bits().wrapping_add(n % 5).wrapping_sub(2));
            let (bx, by) = (nudge(ax * k, next()), nudge(ay * k, next()));
            let value = edge_value(Vec3::new(ax, ay, 0.0), Vec3::new(bx, by, 0.0));
            assert_eq!(
                det_sign(ax, ay, bx, by, value),
                sign_f64(ax, ay, bx, by),
                "({ax:e}, {ay:e}) x ({bx:e}, {by:e})"
            );
            checked += 1;
        }
        assert_eq!(checked, 200_000);
        assert_eq!(det_sign_exact(1.0, 2.0, 2.0, 4.0), 0);
        assert_eq!(det_sign_exact(0.0, 0.0, 3.0, -1.0), 0);
    }

    #[test]
    fn filter_never_decides_wrongly() {
        // Exact path and filtered path agree on random inputs.
        let mut seed = 12345u32;
        for _ in 0..100_000 {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let v: [f32; 4] = std::array::from_fn(|i| {
                ((seed.rotate_left(8 * i as u32) >> 8) as f32 / 16_777_216.0) - 0.5
            });
            let value = v[0] * v[3] - v[1] * v[2];
            assert_eq!(
                det_sign(v[0], v[1], v[2], v[3], value),
                det_sign_exact(v[0], v[1], v[2], v[3])
            );
        }
    }
}
