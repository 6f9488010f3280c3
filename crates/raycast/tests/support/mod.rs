//! Shared helpers for the ray caster's tests: closed-form chords through
//! boxes (f64) and integrators whose output is a known functional of the
//! ray, so walks can be checked against geometry alone.

#![allow(dead_code)]

pub mod compare;
pub mod optics;

use glam::{DVec3, Vec3};
use tetray_boundary_bvh::BuildPreset;
use tetray_core::watertight::RayFrame;
use tetray_mesh::{TetMesh, Topology};
use tetray_raycast::SegmentIntegrator;
use tetray_scene::Scene;

/// Builds a scene with the default BVH preset.
pub fn scene(mesh: TetMesh, field: &str) -> Scene {
    let topology = Topology::build(&mesh).expect("topology");
    Scene::new(mesh, topology, field, BuildPreset::default()).expect("scene")
}

/// The interval `[t0, t1]` (clipped to `t >= 0`) of the ray inside the box,
/// in f64 from the ray's own f32 origin and direction.
pub fn box_interval(ray: &RayFrame, lo: Vec3, hi: Vec3) -> Option<(f64, f64)> {
    let o = ray.origin.as_dvec3();
    let d = ray.dir.as_dvec3();
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for a in 0..3 {
        let (l, h) = (f64::from(lo[a]), f64::from(hi[a]));
        if d[a] == 0.0 {
            if o[a] < l || o[a] > h {
                return None;
            }
            continue;
        }
        let (ta, tb) = ((l - o[a]) / d[a], (h - o[a]) / d[a]);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    (t0 < t1).then_some((t0, t1))
}

/// Chord length of the ray through the box (0 if it misses).
pub fn box_chord(ray: &RayFrame, lo: Vec3, hi: Vec3) -> f64 {
    box_interval(ray, lo, hi).map_or(0.0, |(a, b)| b - a)
}

/// `integral of (offset + gradient . p) dt` over `[t0, t1]` of the ray.
pub fn linear_integral(ray: &RayFrame, offset: f64, gradient: DVec3, t0: f64, t1: f64) -> f64 {
    let o = ray.origin.as_dvec3();
    let d = ray.dir.as_dvec3();
    (offset + gradient.dot(o)) * (t1 - t0) + gradient.dot(d) * (t1 * t1 - t0 * t0) * 0.5
}

/// Makes the red channel the total length integrated and the green one the
/// integral of the scalar (exact per segment for a linear scalar), with no
/// attenuation, so a pixel reads back two integrals along its ray.
pub struct LengthAndScalar;

impl SegmentIntegrator for LengthAndScalar {
    type Sample = f32;

    fn sample(&self, s: f32) -> f32 {
        s
    }

    fn segment(&self, &s_front: &f32, &s_back: &f32, length: f32) -> (glam::Vec3A, glam::Vec3A) {
        let mean = 0.5 * (f64::from(s_front) + f64::from(s_back));
        (
            glam::Vec3A::new(length, (mean * f64::from(length)) as f32, 0.0),
            glam::Vec3A::ONE,
        )
    }
}

/// Constant-property emission-absorption: luminance `l`, attenuation `tau`
/// per unit length (eq. 2.1 with constant terms: Beer-Lambert).
pub struct BeerLambert {
    pub l: Vec3,
    pub tau: f32,
}

impl SegmentIntegrator for BeerLambert {
    type Sample = f32;

    fn sample(&self, s: f32) -> f32 {
        s
    }

    fn segment(&self, &_s_front: &f32, &_s_back: &f32, length: f32) -> (glam::Vec3A, glam::Vec3A) {
        let t = (-f64::from(self.tau) * f64::from(length)).exp() as f32;
        ((self.l * (1.0 - t)).into(), glam::Vec3A::splat(t))
    }
}
