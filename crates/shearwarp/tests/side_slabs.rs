//! Rays that enter or leave the grid through its side faces (the faces
//! parallel to the principal axis) cross those faces between two slices:
//! the slab they cut must count for the length inside the grid. A
//! constant field on a 32^3 grid over the unit cube, opacity 0.35 per unit
//! distance 0.5, against Beer-Lambert on the exact chord, at every pixel
//! inside the silhouette, in oblique parallel and perspective views.
//!
//! Each ray of the intermediate image passes through a point of the front
//! slice's lattice; its light here is exact (a constant field: its slabs,
//! whole or clipped at a side face, add up to its chord), and the warp
//! interpolates those rays bilinearly. So every pixel must equal the
//! bilinear interpolation of Beer-Lambert on the chords of the four
//! lattice rays around it (tolerance 1e-4: f32 rounding over 32 slabs and
//! the table's length correction, measured below 1e-5). What remains
//! against the pixel's own ray is the warp's resampling, printed.

mod support;

use glam::{DVec3, Vec3};
use support::{principal, tf, view};
use tetray_core::Camera;
use tetray_shearwarp::{Classification, ClassifyOptions, RegularGrid, ShearWarp, ShearWarpOptions};

const LUM: [f32; 3] = [0.3, 0.7, 0.9];

fn cube() -> RegularGrid {
    RegularGrid::from_fn([32, 32, 32], Vec3::ZERO, Vec3::splat(1.0 / 31.0), |_| 0.5).unwrap()
}

/// Where the ray `o + t d` crosses the box, if it does.
fn chord(lo: DVec3, hi: DVec3, o: DVec3, d: DVec3) -> Option<f64> {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for a in 0..3 {
        if d[a] == 0.0 {
            if o[a] < lo[a] || o[a] > hi[a] {
                return None;
            }
            continue;
        }
        let (ta, tb) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    (t1 > t0).then(|| (t1 - t0) * d.length())
}

/// The worst difference from the bilinear warp of the exact lattice
/// rays; the worst difference from the pixel's own ray where the four
/// lattice rays around it all meet the grid (the warp's resampling inside
/// the silhouette); and the number of those pixels whose ray crosses a
/// side face.
fn check(sw: &ShearWarp, cam: &Camera, size: u32, alpha: impl Fn(f64) -> f64) -> (f64, f64, usize) {
    let out = sw
        .render(
            cam,
            &ShearWarpOptions {
                width: size,
                height: size,
                ..ShearWarpOptions::default()
            },
        )
        .unwrap();
    let (lo, hi) = sw.grid().bounds();
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    let c = principal(sw.grid(), cam);
    let (a, b) = ((c + 1) % 3, (c + 2) % 3);
    let cell = sw.grid().spacing().as_dvec3();
    let rays = cam.pixel_rays(size, size).unwrap();
    let eye = cam
        .parallel_scale
        .is_none()
        .then(|| cam.position.as_dvec3());
    let (mut warped, mut resampling, mut sides) = (0.0f64, 0.0f64, 0);
    for py in 0..size {
        for px in 0..size {
            let ray = rays.ray(px, py);
            let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
            // The front slice, and where the pixel's ray meets its plane,
            // in cells from the grid's corner.
            let front = if d[c] > 0.0 { lo[c] } else { hi[c] };
            let p = o + d * ((front - o[c]) / d[c]);
            let (ia, ib) = ((p[a] - lo[a]) / cell[a], (p[b] - lo[b]) / cell[b]);
            // The chord of the ray through lattice point (i, j) of the
            // front slice (the pixel's ray through the real point).
            let through = |i: f64, j: f64| {
                let mut q = p;
                q[a] = lo[a] + i * cell[a];
                q[b] = lo[b] + j * cell[b];
                match eye {
                    Some(e) => chord(lo, hi, e, q - e),
                    None => chord(lo, hi, q - d * 10.0, d),
                }
                .unwrap_or(0.0)
            };
            let (i0, j0) = (ia.floor(), ib.floor());
            let (fa, fb) = (ia - i0, ib - j0);
            let mut want = 0.0;
            let mut all_meet = true;
            for (di, wi) in [(0.0, 1.0 - fa), (1.0, fa)] {
                for (dj, wj) in [(0.0, 1.0 - fb), (1.0, fb)] {
                    let l = through(i0 + di, j0 + dj);
                    all_meet &= l > 0.0;
                    want += wi * wj * alpha(l);
                }
            }
            let got = out.image.pixel(px, py).unwrap();
            let mut error = (f64::from(got[3]) - want).abs();
            for k in 0..3 {
                error = error.max((f64::from(got[k]) - f64::from(LUM[k]) * want).abs());
            }
            warped = warped.max(error);
            let own = through(ia, ib);
            if own > 0.0 && all_meet {
                resampling = resampling.max((f64::from(got[3]) - alpha(own)).abs());
                // Does it enter or leave through a side face?
                let back = if d[c] > 0.0 { hi[c] } else { lo[c] };
                let at = |plane: f64| o + d * ((plane - o[c]) / d[c]);
                let on_face = |q: DVec3| (0..3).all(|k| k == c || (lo[k]..=hi[k]).contains(&q[k]));
                if !(on_face(at(front)) && on_face(at(back))) {
                    sides += 1;
                }
            }
        }
    }
    (warped, resampling, sides)
}

/// Four views, two image sizes, both classifications; with the side slabs
/// dropped, the pixels were up to 6e-2 off their warped lattice rays.
#[test]
fn side_slabs_count_for_the_length_inside_the_grid() {
    let t = tf(&[(0.0, LUM, 0.35), (1.0, LUM, 0.35)]);
    let alpha = |l: f64| 1.0 - (1.0f64 - 0.35).powf(l / 0.5);
    for c in [
        Classification::PreIntegrated,
        Classification::PostClassified,
    ] {
        let opts = ClassifyOptions {
            classification: c,
            unit_distance: 0.5,
            ..ClassifyOptions::default()
        };
        let sw = ShearWarp::new(cube(), &t, &opts).unwrap();
        let mut oblique = view(sw.grid(), 0.0, 0.0, true);
        oblique.position = Vec3::new(2.2, 1.4, 2.9);
        oblique.focal_point = Vec3::splat(0.5);
        oblique.orthogonalize_view_up().unwrap();
        let cameras = [
            ("parallel, camera at (2.2, 1.4, 2.9)", oblique),
            (
                "parallel, azimuth 30, elevation 20",
                view(sw.grid(), 30.0, 20.0, true),
            ),
            (
                "parallel, azimuth -120, elevation -40",
                view(sw.grid(), -120.0, -40.0, true),
            ),
            (
                "perspective, azimuth 25, elevation 15",
                view(sw.grid(), 25.0, 15.0, false),
            ),
        ];
        for (name, cam) in &cameras {
            for size in [48, 160] {
                let (warped, resampling, sides) = check(&sw, cam, size, alpha);
                println!(
                    "{} {name} {size}: {warped:.2e} from the warped lattice rays, \
                     {resampling:.2e} from the pixel's ray inside the silhouette, \
                     {sides} pixels through a side face",
                    c.name()
                );
                assert!(
                    sides > 10,
                    "{name} {size}: {sides} pixels through a side face"
                );
                assert!(warped < 1e-4, "{} {name} {size}: {warped}", c.name());
            }
        }
    }
}
