//! Twins of shaders/project.wgsl's vertex and fragment stages, in the same
//! f32 operations in the same order.

use glam::{Vec2, Vec3, Vec4};
use tetray_gpu::twin::integrate::IntegratorInputs;
use tetray_gpu::twin::integrate::{Light, in_interval, sample_at, segment_light};

use crate::draws::NO_CLIP;
use crate::layout::Params;

const BIG: f32 = 1e30;

/// What the vertex stage hands the rasterizer for one corner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    pub clip: Vec4,
    pub entry: Vec2,
    pub plane_a: Vec4,
    pub plane_b: Vec4,
    pub opposite: Vec4,
    pub clip_code: u32,
    /// The cell's (z_min, z_max, s_min, s_max).
    pub bounds: Vec4,
}

fn ratio(num: f32, den: f32) -> f32 {
    if num.abs() < BIG * den.abs() {
        num / den
    } else if (num >= 0.0) == (den >= 0.0) {
        BIG
    } else {
        -BIG
    }
}

fn v3(v: [f32; 3]) -> Vec3 {
    Vec3::from_array(v)
}

/// The vertex stage for corner `corner` of a tetrahedron with points (and
/// scalars in w) `q`.
pub fn vertex(params: &Params, q: &[Vec4; 4], corner: usize, clip_code: u32) -> Corner {
    let (mut me, mut a, mut b, mut c) = (q[0], q[1], q[2], q[3]);
    if corner == 1 {
        me = q[1];
        a = q[0];
    } else if corner == 2 {
        me = q[2];
        a = q[0];
        b = q[1];
    } else if corner == 3 {
        me = q[3];
        a = q[0];
        b = q[1];
        c = q[2];
    }
    let p = me.truncate();
    let rel = p - v3(params.view.position);
    let z = rel.dot(v3(params.view.direction));
    let sx = rel.dot(v3(params.view.right)) / (params.view.pixel * params.view.half_width);
    let sy = rel.dot(v3(params.view.up)) / (params.view.pixel * params.view.half_height);
    let ortho = params.view.orthographic == 1;
    let ray = if ortho {
        v3(params.view.direction)
    } else {
        rel
    };
    let (ea, eb, ec) = (a.truncate() - p, b.truncate() - p, c.truncate() - p);
    let (cx, cy, cz) = (eb.cross(ec), ec.cross(ea), ea.cross(eb));
    let det = ea.dot(cx);
    let (xr, yr, zr) = (cx.dot(ray), cy.dot(ray), cz.dot(ray));
    let nr = xr + yr + zr;
    let sr = (a.w - me.w) * xr + (b.w - me.w) * yr + (c.w - me.w) * zr;
    let (clip, own, far) = if ortho {
        (
            Vec4::new(sx, sy, 0.5, 1.0),
            Vec2::new(z, me.w),
            Vec2::new(z + ratio(det, nr), me.w + ratio(sr, nr)),
        )
    } else {
        let den = z * (nr + det);
        (
            Vec4::new(sx, sy, 0.5 * z, z),
            Vec2::new(1.0 / z, me.w / z),
            Vec2::new(ratio(nr, den), ratio(me.w * nr + sr, den)),
        )
    };
    let depths =
        q.map(|v| (v.truncate() - v3(params.view.position)).dot(v3(params.view.direction)));
    let scalars = q.map(|v| v.w);
    let bounds = Vec4::new(
        depths[0].min(depths[1]).min(depths[2].min(depths[3])),
        depths[0].max(depths[1]).max(depths[2].max(depths[3])),
        scalars[0].min(scalars[1]).min(scalars[2].min(scalars[3])),
        scalars[0].max(scalars[1]).max(scalars[2].max(scalars[3])),
    );
    let pick = |own: f32, far: f32| {
        Vec4::from_array(std::array::from_fn(|j| if j == corner { far } else { own }))
    };
    Corner {
        clip,
        entry: own,
        plane_a: pick(own.x, far.x),
        plane_b: pick(own.y, far.y),
        opposite: pick(0.0, 1.0),
        clip_code,
        bounds,
    }
}

/// The fragment stage's inputs at one pixel.
pub struct Fragment {
    pub x: f32,
    pub y: f32,
    pub entry: Vec2,
    pub plane_a: Vec4,
    pub plane_b: Vec4,
    pub opposite: Vec4,
    pub clip_code: u32,
    pub bounds: Vec4,
}

impl Fragment {
    /// Screen-space linear interpolation with the pixel centre's weights.
    pub fn interpolate(tri: &[&Corner; 3], w: [f32; 3], px: u32, py: u32) -> Fragment {
        Fragment {
            x: px as f32 + 0.5,
            y: py as f32 + 0.5,
            entry: tri[0].entry * w[0] + tri[1].entry * w[1] + tri[2].entry * w[2],
            plane_a: tri[0].plane_a * w[0] + tri[1].plane_a * w[1] + tri[2].plane_a * w[2],
            plane_b: tri[0].plane_b * w[0] + tri[1].plane_b * w[1] + tri[2].plane_b * w[2],
            opposite: tri[0].opposite * w[0] + tri[1].opposite * w[1] + tri[2].opposite * w[2],
            // Flat: the provoking (first) corner's.
            clip_code: tri[0].clip_code,
            bounds: tri[0].bounds,
        }
    }
}

/// The fragment stage: the light of the pixel's segment through the piece,
/// or `None` where the fragment is discarded.
pub fn fragment(params: &Params, inputs: &IntegratorInputs, f: &Fragment) -> Option<Light> {
    let (mut z_in, mut s_in, mut z_out, mut s_out, scale);
    if params.view.orthographic == 1 {
        let mut best = BIG;
        let mut best_s = 0.0;
        for j in 0..4 {
            let zj = f.plane_a[j];
            if f.opposite[j] > 0.0 && zj > f.entry.x && zj < best {
                best = zj;
                best_s = f.plane_b[j];
            }
        }
        if best >= BIG {
            return None;
        }
        (z_in, s_in, z_out, s_out, scale) = (f.entry.x, f.entry.y, best, best_s, 1.0);
    } else {
        let a_in = f.entry.x;
        let mut best = 0.0f32;
        let mut best_b = 0.0;
        for j in 0..4 {
            let aj = f.plane_a[j];
            if f.opposite[j] > 0.0 && aj < a_in && aj > best {
                best = aj;
                best_b = f.plane_b[j];
            }
        }
        if best.is_nan() || best <= 0.0 {
            return None;
        }
        let x = (f.x - params.view.half_width) * params.view.pixel;
        let y = (params.view.half_height - f.y) * params.view.pixel;
        let ray = v3(params.view.direction) + v3(params.view.right) * x + v3(params.view.up) * y;
        (z_in, s_in, z_out, s_out, scale) = (
            1.0 / a_in,
            f.entry.y / a_in,
            1.0 / best,
            best_b / best,
            ray.length(),
        );
    }
    // The segment lies in the cell: within its depth and scalar ranges.
    z_in = z_in.max(f.bounds.x);
    z_out = z_out.min(f.bounds.y);
    s_in = s_in.max(f.bounds.z).min(f.bounds.w);
    s_out = s_out.max(f.bounds.z).min(f.bounds.w);
    let length = (z_out - z_in) * scale;
    if length.is_nan() || length <= 0.0 {
        return None;
    }
    if f.clip_code == NO_CLIP {
        let (front, back) = (sample_at(inputs, s_in), sample_at(inputs, s_out));
        return Some(segment_light(inputs, &front, &back, length));
    }
    let k = f.clip_code as i32 - 1;
    let span = s_out - s_in;
    let (mut t_front, mut t_back, mut s_front, mut s_back) = (0.0f32, 1.0f32, s_in, s_out);
    let knot = |k: i32| inputs.tables[4 * (k as usize + 1)][3];
    if span == 0.0 {
        if sample_at(inputs, s_in).interval != k {
            return None;
        }
    } else {
        if k >= 0 {
            let lo = knot(k);
            let t = (lo - s_in) / span;
            if span > 0.0 && t > t_front {
                (t_front, s_front) = (t, lo);
            } else if span < 0.0 && t < t_back {
                (t_back, s_back) = (t, lo);
            }
        }
        if k + 1 < params.integrator.knot_count as i32 {
            let hi = knot(k + 1);
            let t = (hi - s_in) / span;
            if span > 0.0 && t < t_back {
                (t_back, s_back) = (t, hi);
            } else if span < 0.0 && t > t_front {
                (t_front, s_front) = (t, hi);
            }
        }
    }
    let piece = length * (t_back - t_front);
    if piece.is_nan() || piece <= 0.0 {
        return None;
    }
    let (front, back) = (
        in_interval(inputs, k, s_front),
        in_interval(inputs, k, s_back),
    );
    Some(segment_light(inputs, &front, &back, piece))
}
