//! Shared helpers of the shear-warp tests: views, transfer functions, the
//! exact tetrahedral ray caster on the same grid, and the pixels whose ray
//! crosses the grid through its two principal faces.

#![allow(dead_code)]

use glam::{DVec3, Vec3};
use tetray_boundary_bvh::BuildPreset;
use tetray_core::{Camera, Image};
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityMode, OpacityPoint, ScalarIntegrator,
    TransferFunction,
};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;
use tetray_shearwarp::RegularGrid;

/// The VTK view after ResetCamera, turned by azimuth and elevation.
pub fn view(grid: &RegularGrid, azimuth: f32, elevation: f32, parallel: bool) -> Camera {
    let mut cam = Camera {
        parallel_scale: parallel.then_some(1.0),
        ..Camera::default()
    };
    let (lo, hi) = grid.bounds();
    cam.reset(lo, hi, 1.0).unwrap();
    cam.azimuth(azimuth).unwrap();
    cam.elevation(elevation).unwrap();
    cam.orthogonalize_view_up().unwrap();
    cam
}

/// Piecewise-linear transfer function from `(scalar, rgb, alpha)` points.
pub fn tf(points: &[(f32, [f32; 3], f32)]) -> TransferFunction {
    TransferFunction::new(
        points
            .iter()
            .map(|&(scalar, rgb, _)| ColorPoint {
                scalar,
                rgb: Vec3::from_array(rgb),
            })
            .collect(),
        points
            .iter()
            .map(|&(scalar, _, alpha)| OpacityPoint { scalar, alpha })
            .collect(),
    )
    .unwrap()
}

/// The grid as tetrahedra through the CPU ray caster, exact integrator.
pub fn ray_cast(
    grid: &RegularGrid,
    tf: &TransferFunction,
    camera: &Camera,
    size: u32,
    mode: OpacityMode,
) -> Image {
    let loaded = tetray_mesh::prepare(grid.to_tet_mesh("s")).unwrap();
    let scene = Scene::from_loaded(loaded, "s", BuildPreset::default()).unwrap();
    let options = IntegratorOptions {
        opacity_mode: mode,
        ..IntegratorOptions::default()
    };
    let integrator = ScalarIntegrator::new(Method::Exact, tf, &options).unwrap();
    let opts = RenderOptions {
        width: size,
        height: size,
        ..RenderOptions::default()
    };
    render_scalar(&scene, camera, &integrator, &opts)
        .unwrap()
        .image
}

/// Where a pixel's ray crosses the grid's box: `None` when it misses,
/// else the entry and exit distances and whether both lie on the faces
/// perpendicular to `axis`, at least `margin` cells inside their edges.
pub struct Chord {
    pub t0: f64,
    pub t1: f64,
    pub full: bool,
}

pub fn chord(grid: &RegularGrid, camera: &Camera, size: u32, px: u32, py: u32) -> Option<Chord> {
    let ray = camera.pixel_rays(size, size).unwrap().ray(px, py);
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    let (lo, hi) = grid.bounds();
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut a0, mut a1) = (0, 0);
    for a in 0..3 {
        let (ta, tb) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
        let (near, far) = (ta.min(tb), ta.max(tb));
        if near > t0 {
            t0 = near;
            a0 = a;
        }
        if far < t1 {
            t1 = far;
            a1 = a;
        }
    }
    if t1 <= t0.max(0.0) {
        return None;
    }
    let axis = principal(grid, camera);
    let margin = 1.5 * grid.spacing().as_dvec3();
    let inside = |p: DVec3| {
        (0..3).all(|a| a == axis || (p[a] > lo[a] + margin[a] && p[a] < hi[a] - margin[a]))
    };
    let full = a0 == axis && a1 == axis && inside(o + d * t0) && inside(o + d * t1);
    Some(Chord { t0, t1, full })
}

/// The principal viewing axis in index space.
pub fn principal(grid: &RegularGrid, camera: &Camera) -> usize {
    let d = (camera.focal_point - camera.position) / grid.spacing();
    (0..3)
        .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
        .unwrap()
}

/// Largest and mean absolute difference over the channels of the pixels
/// `keep` selects; and how many it selected.
pub fn difference(a: &Image, b: &Image, keep: impl Fn(u32, u32) -> bool) -> (f32, f32, usize) {
    let (mut max, mut sum, mut n) = (0.0f32, 0.0f64, 0usize);
    for py in 0..a.height {
        for px in 0..a.width {
            if !keep(px, py) {
                continue;
            }
            let (p, q) = (a.pixel(px, py).unwrap(), b.pixel(px, py).unwrap());
            for c in 0..4 {
                let e = (p[c] - q[c]).abs();
                max = max.max(e);
                sum += f64::from(e);
            }
            n += 1;
        }
    }
    (max, (sum / (4 * n.max(1)) as f64) as f32, n)
}
