//! Closed forms of the volume rendering integral along one ray, in f64:
//! Beer-Lambert for constant material (eq. 2.17), and a linear scalar field
//! through a piecewise-linear transfer function, cut at its knots (section
//! 4.3) and integrated piece by piece with the f64 reference.

use std::ops::{Add, Mul, Sub};

use glam::{DVec3, Vec3};
use tetray_core::watertight::RayFrame;
use tetray_integrate::{ColorPoint, OpacityPoint, TransferFunction, reference};
use tetray_mesh::synthetic::ScalarSpec;

/// A transfer function from `(scalar, rgb)` and `(scalar, alpha)` points.
pub fn transfer_function(colors: &[(f32, [f32; 3])], alphas: &[(f32, f32)]) -> TransferFunction {
    let color = colors
        .iter()
        .map(|&(scalar, rgb)| ColorPoint {
            scalar,
            rgb: Vec3::from_array(rgb),
        })
        .collect();
    let opacity = alphas
        .iter()
        .map(|&(scalar, alpha)| OpacityPoint { scalar, alpha })
        .collect();
    TransferFunction::new(color, opacity).unwrap()
}

/// Total variation of the luminance over the transfer function, the
/// largest of the channels: no ray sees its luminance change by more.
pub fn luminance_variation(tf: &TransferFunction) -> f64 {
    let points = tf.color_points();
    let change = |c: usize| {
        points
            .windows(2)
            .map(|w| f64::from((w[1].rgb[c] - w[0].rgb[c]).abs()))
            .sum::<f64>()
    };
    (0..3).map(change).fold(0.0, f64::max)
}

/// A piecewise-linear function of `(scalar, value)` points at `s`, constant
/// beyond the end points (the transfer function's definition).
pub fn piecewise_linear<T>(points: &[(f64, T)], s: f64) -> T
where
    T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f64, Output = T>,
{
    let above = points.partition_point(|p| p.0 <= s);
    if above == 0 {
        return points[0].1;
    }
    if above == points.len() {
        return points[above - 1].1;
    }
    let ((x0, v0), (x1, v1)) = (points[above - 1], points[above]);
    v0 + (v1 - v0) * ((s - x0) / (x1 - x0))
}

/// A transfer function read in f64 from its own f32 points.
pub struct TfF64 {
    lum: Vec<(f64, DVec3)>,
    alpha: Vec<(f64, f64)>,
}

impl TfF64 {
    pub fn new(tf: &TransferFunction) -> TfF64 {
        TfF64 {
            lum: tf
                .color_points()
                .iter()
                .map(|p| (f64::from(p.scalar), p.rgb.as_dvec3()))
                .collect(),
            alpha: tf
                .opacity_points()
                .iter()
                .map(|p| (f64::from(p.scalar), f64::from(p.alpha)))
                .collect(),
        }
    }

    /// Every scalar where luminance or opacity changes slope.
    pub fn knots(&self) -> impl Iterator<Item = f64> + '_ {
        self.lum
            .iter()
            .map(|p| p.0)
            .chain(self.alpha.iter().map(|p| p.0))
    }
}

/// Eq. 2.17 for a constant luminance and attenuation over `chord`.
pub fn beer_lambert(lum: DVec3, tau: f64, chord: f64) -> [f64; 4] {
    let alpha = -(-tau * chord).exp_m1();
    let c = lum * alpha;
    [c.x, c.y, c.z, alpha]
}

/// `offset + gradient . p`, with the scalar along a ray in f64.
#[derive(Clone, Copy)]
pub struct LinearField {
    pub offset: f32,
    pub gradient: Vec3,
}

impl LinearField {
    pub fn spec(self) -> ScalarSpec {
        ScalarSpec::Linear {
            offset: self.offset,
            gradient: self.gradient,
        }
    }

    /// `(s(0), ds/dt)` along `ray`.
    pub fn along(self, ray: &RayFrame) -> (f64, f64) {
        let g = self.gradient.as_dvec3();
        (
            f64::from(self.offset) + g.dot(ray.origin.as_dvec3()),
            g.dot(ray.dir.as_dvec3()),
        )
    }
}

/// Eq. 2.2 over `[t0, t1]` of `ray` through `field`, with the transfer
/// function in VTK opacity mode (`tau = alpha / u`, linear in the scalar
/// like the luminance). The scalar is linear in `t`, so cut where it
/// crosses a knot every piece has linear luminance and attenuation: each is
/// integrated by the f64 reference and composited front to back (eq. 2.13).
pub fn linear_field_light(
    ray: &RayFrame,
    field: LinearField,
    tf: &TfF64,
    unit_distance: f64,
    (t0, t1): (f64, f64),
) -> [f64; 4] {
    let (s0, slope) = field.along(ray);
    let mut cuts: Vec<f64> = vec![t0, t1];
    if slope != 0.0 {
        cuts.extend(
            tf.knots()
                .map(|x| (x - s0) / slope)
                .filter(|&t| t0 < t && t < t1),
        );
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let material = |t: f64| {
        let s = s0 + slope * t;
        let lum = piecewise_linear(&tf.lum, s);
        (lum, piecewise_linear(&tf.alpha, s) / unit_distance)
    };
    let (mut color, mut transmittance) = (DVec3::ZERO, DVec3::ONE);
    for piece in cuts.windows(2) {
        let ((lum_front, tau_front), (lum_back, tau_back)) =
            (material(piece[0]), material(piece[1]));
        for c in 0..3 {
            let light = reference::attenuation_segment(
                lum_back[c],
                lum_front[c],
                tau_back,
                tau_front,
                piece[1] - piece[0],
            );
            color[c] += transmittance[c] * light.emitted;
            transmittance[c] *= light.transmittance;
        }
    }
    [
        color.x,
        color.y,
        color.z,
        1.0 - transmittance.element_sum() / 3.0,
    ]
}
