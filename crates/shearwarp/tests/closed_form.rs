//! Shear-warp against closed forms, pixel by pixel, on the pixels whose
//! ray crosses the grid through its two faces perpendicular to the
//! principal axis, 1.5 cells or more inside their edges ("full" pixels):
//! there every intermediate-image ray that the warp interpolates runs
//! through all slices, so the only errors are the ones shear-warp has by
//! design (the warp's bilinear resampling of the intermediate image, the
//! pre-integration table's interpolation and its length correction) plus
//! f32 rounding. Pixels whose ray misses the grid must be exactly clear.

mod support;

use glam::{DVec3, Vec3};
use support::{chord, tf, view};
use tetray_integrate::OpacityMode;
use tetray_shearwarp::{
    Classification, ClassifyOptions, RegularGrid, ShearWarp, ShearWarpError, ShearWarpOptions,
};

const SIZE: u32 = 64;
/// (azimuth, elevation, parallel): along the z axis, oblique, from below
/// and behind, in both projections.
const VIEWS: [(f32, f32, bool); 6] = [
    (0.0, 0.0, true),
    (30.0, 20.0, true),
    (-120.0, -40.0, true),
    (75.0, 10.0, true),
    (25.0, 15.0, false),
    (200.0, -30.0, false),
];

fn grid(f: impl Fn(Vec3) -> f32) -> RegularGrid {
    // Anisotropic spacing, off-origin.
    RegularGrid::from_fn(
        [17, 13, 21],
        Vec3::new(-1.0, 0.5, 2.0),
        Vec3::new(0.25, 0.5, 0.2),
        f,
    )
    .unwrap()
}

fn options(c: Classification, mode: OpacityMode) -> ClassifyOptions {
    ClassifyOptions {
        classification: c,
        opacity_mode: mode,
        ..ClassifyOptions::default()
    }
}

/// Largest error over the full pixels of the parallel and of the
/// perspective views; checks that full pixels exist and that pixels far
/// from the grid are clear.
fn worst(sw: &ShearWarp, expected: impl Fn(f64, f64, DVec3, DVec3) -> [f64; 4]) -> (f32, f32) {
    let mut worst: f32;
    let mut by_projection = (0.0f32, 0.0f32);
    for &(az, el, parallel) in &VIEWS {
        let cam = view(sw.grid(), az, el, parallel);
        let out = sw
            .render(
                &cam,
                &ShearWarpOptions {
                    width: SIZE,
                    height: SIZE,
                    ..ShearWarpOptions::default()
                },
            )
            .unwrap();
        let rays = cam.pixel_rays(SIZE, SIZE).unwrap();
        let mut full = 0;
        worst = 0.0;
        for py in 0..SIZE {
            for px in 0..SIZE {
                let got = out.image.pixel(px, py).unwrap();
                match chord(sw.grid(), &cam, SIZE, px, py) {
                    Some(ch) if ch.full => {
                        full += 1;
                        let ray = rays.ray(px, py);
                        let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
                        let want = expected(ch.t0.max(0.0), ch.t1, o, d);
                        for c in 0..4 {
                            worst = worst.max((got[c] - want[c] as f32).abs());
                        }
                    }
                    _ => {}
                }
            }
        }
        assert!(full > 20, "view {az} {el} {parallel}: {full} full pixels");
        println!("  view {az} {el} parallel {parallel}: {full} full pixels, worst {worst:.2e}");
        if parallel {
            by_projection.0 = by_projection.0.max(worst);
        } else {
            by_projection.1 = by_projection.1.max(worst);
        }
        // Far from the grid the image is exactly clear.
        assert_eq!(out.image.pixel(0, 0).unwrap(), [0.0; 4]);
    }
    by_projection
}

/// Constant material: Beer-Lambert, `T = exp(-tau D)`, `C = c (1 - T)`.
/// Every full ray integrates exactly the chord (its slabs span it) and its
/// neighbours hold the same light, so the warp adds nothing: what is left
/// is f32 rounding over up to 40 slabs and the table's `T^(D/D0)`
/// (measured 3e-7; allowed 2e-6). In perspective the chord changes from
/// ray to ray and the warp interpolates it bilinearly: an error of
/// `h^2 / 8 |I''|` with `h` an intermediate pixel (measured 6.3e-5; allowed
/// 2e-4).
#[test]
fn constant_field_is_beer_lambert() {
    let g = grid(|_| 0.5);
    let lum = [0.2, 0.6, 0.9];
    let t = tf(&[(0.0, lum, 0.3), (1.0, lum, 0.3)]);
    let tau = -(1.0f64 - 0.3).ln();
    for c in [
        Classification::PreIntegrated,
        Classification::PostClassified,
    ] {
        let sw = ShearWarp::new(g.clone(), &t, &options(c, OpacityMode::Exact)).unwrap();
        let (par, persp) = worst(&sw, |t0, t1, _, _| {
            let tr = (-tau * (t1 - t0)).exp();
            let a = 1.0 - tr;
            [
                f64::from(lum[0]) * a,
                f64::from(lum[1]) * a,
                f64::from(lum[2]) * a,
                a,
            ]
        });
        println!(
            "{}: constant field, parallel {par:.2e}, perspective {persp:.2e}",
            c.name()
        );
        assert!(par < 2e-6, "{}: parallel {par}", c.name());
        assert!(persp < 2e-4, "{}: perspective {persp}", c.name());
    }
}

/// A linear field along the grid's x axis, a linear transfer function in
/// VTK opacity mode (`tau = alpha / u`, linear in the scalar): luminance
/// and attenuation are linear along each chord; the closed form is
/// `T = exp(-integral tau)` with the integral in closed form and the
/// emission `integral lum tau T(l) dl` by 4000-step Simpson in f64.
///
/// Errors by design: mostly the warp, which interpolates bilinearly a
/// light that varies nonlinearly across the image (`h^2 / 8 |I''|` with `h`
/// = 0.25, one x cell: about 3e-3 here, the same for both classifications
/// on the view along z, where every ray sees one scalar); for
/// pre-integration also the table (256 nodes) interpolated bilinearly and
/// the colour correction (exact only for constant slabs). Measured 3.2e-3
/// (allowed 5e-3). Post-classified slabs take the front scalar as constant:
/// an error first order in the scalar change per slab (measured 3.5e-2,
/// allowed 5e-2).
#[test]
fn linear_field_matches_the_closed_form() {
    let g = grid(|p| 0.5 + 0.4 * (p.x + 1.0) / 4.0);
    let (l0, l1) = ([0.9, 0.3, 0.1], [0.1, 0.5, 1.0]);
    let t = tf(&[(0.5, l0, 0.1), (0.9, l1, 0.9)]);
    let s_at = |p: DVec3| 0.5 + 0.4 * (p.x + 1.0) / 4.0;
    let lerp = |a: f64, b: f64, w: f64| a + (b - a) * w;
    let expected = |t0: f64, t1: f64, o: DVec3, d: DVec3| {
        let (s0, s1) = (s_at(o + d * t0), s_at(o + d * t1));
        let len = t1 - t0;
        let w = |s: f64| (s - 0.5) / 0.4;
        let tau = |l: f64| lerp(0.1, 0.9, w(lerp(s0, s1, l / len)));
        let depth = |l: f64| l * (tau(0.0) + tau(l)) / 2.0;
        let n = 4000;
        let h = len / n as f64;
        let mut e = [0.0f64; 3];
        for i in 0..=n {
            let l = i as f64 * h;
            let k = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let ws = w(lerp(s0, s1, l / len));
            let f = tau(l) * (-depth(l)).exp() * k * h / 3.0;
            for c in 0..3 {
                e[c] += lerp(f64::from(l0[c]), f64::from(l1[c]), ws) * f;
            }
        }
        let a = 1.0 - (-depth(len)).exp();
        [e[0], e[1], e[2], a]
    };
    for (c, limit) in [
        (Classification::PreIntegrated, 5e-3),
        (Classification::PostClassified, 5e-2),
    ] {
        let sw = ShearWarp::new(g.clone(), &t, &options(c, OpacityMode::Vtk)).unwrap();
        let (par, persp) = worst(&sw, expected);
        let err = par.max(persp);
        println!(
            "{}: linear field, parallel {par:.2e}, perspective {persp:.2e}",
            c.name()
        );
        assert!(err < limit, "{}: {err}", c.name());
    }
}

/// A perspective eye between the first and last slice along the
/// principal axis cannot be factorized: a clear error, no panic.
#[test]
fn perspective_eye_inside_the_slab_range_is_an_error() {
    let g = grid(|_| 0.5);
    let t = tf(&[(0.0, [1.0; 3], 0.5), (1.0, [1.0; 3], 0.5)]);
    let sw = ShearWarp::new(g, &t, &ClassifyOptions::default()).unwrap();
    let mut cam = view(sw.grid(), 0.0, 0.0, false);
    cam.dolly(20.0).unwrap();
    let err = sw.render(&cam, &ShearWarpOptions::default()).unwrap_err();
    assert!(matches!(err, ShearWarpError::EyeInsideSlab { .. }), "{err}");
    let bad = ShearWarpOptions {
        early_termination: 0.0,
        ..ShearWarpOptions::default()
    };
    let cam = view(sw.grid(), 0.0, 0.0, true);
    assert!(matches!(
        sw.render(&cam, &bad),
        Err(ShearWarpError::BadEarlyTermination(_))
    ));
}
