//! Segments cut at transfer-function knots (adaptive transfer-function
//! sampling, section 4.3), full pre-integration and the Riemann sum,
//! checked against a fine Riemann sum of the true piecewise-linear model
//! (an independent discretisation that converges as h^2).

use glam::Vec3;
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityMode, OpacityPoint, ScalarIntegrator,
    SegmentLight, TfKnots, TransferFunction,
};

/// A transfer function with a sharp opacity spike and colour knots that do
/// not coincide with the opacity knots, plus a step in colour.
fn spiky_tf() -> TransferFunction {
    let color = vec![
        ColorPoint {
            scalar: 0.0,
            rgb: Vec3::new(0.0, 0.0, 1.0),
        },
        ColorPoint {
            scalar: 0.35,
            rgb: Vec3::new(0.0, 1.0, 0.0),
        },
        ColorPoint {
            scalar: 0.6,
            rgb: Vec3::new(1.0, 1.0, 0.0),
        },
        ColorPoint {
            scalar: 0.6,
            rgb: Vec3::new(1.0, 0.0, 0.0),
        },
        ColorPoint {
            scalar: 1.0,
            rgb: Vec3::new(1.0, 1.0, 1.0),
        },
    ];
    let opacity = vec![
        OpacityPoint {
            scalar: 0.0,
            alpha: 0.05,
        },
        OpacityPoint {
            scalar: 0.48,
            alpha: 0.05,
        },
        OpacityPoint {
            scalar: 0.5,
            alpha: 0.95,
        },
        OpacityPoint {
            scalar: 0.52,
            alpha: 0.05,
        },
        OpacityPoint {
            scalar: 1.0,
            alpha: 0.2,
        },
    ];
    TransferFunction::new(color, opacity).unwrap()
}

/// Midpoint Riemann sum with `steps` steps of the exact model: material from
/// the knots at each step's scalar, each step homogeneous (eq. 3.13), in f64.
fn fine_riemann(knots: &TfKnots, s_front: f32, s_back: f32, length: f32, steps: usize) -> [f64; 6] {
    let h = f64::from(length) / steps as f64;
    let mut color = [0.0f64; 3];
    let mut t = [1.0f64; 3];
    for k in 0..steps {
        let f = (k as f64 + 0.5) / steps as f64;
        let s = f64::from(s_front) + (f64::from(s_back) - f64::from(s_front)) * f;
        let m = knots.at(s as f32);
        for c in 0..3 {
            let zeta = (-f64::from(m.tau[c]) * h).exp();
            color[c] += t[c] * f64::from(m.lum[c]) * (1.0 - zeta);
            t[c] *= zeta;
        }
    }
    [color[0], color[1], color[2], t[0], t[1], t[2]]
}

fn max_diff(light: SegmentLight, want: [f64; 6]) -> f64 {
    (0..3)
        .map(|c| {
            let e = (f64::from(light.emitted[c]) - want[c]).abs();
            let t = (f64::from(light.transmittance[c]) - want[3 + c]).abs();
            e.max(t)
        })
        .fold(0.0, f64::max)
}

const SEGMENTS: [(f32, f32, f32); 7] = [
    (0.0, 1.0, 2.0),
    (1.0, 0.0, 2.0),
    (0.3, 0.7, 0.5),
    (0.49, 0.51, 3.0),
    (0.6, 0.6, 1.0),
    (-0.5, 0.55, 1.2),
    (0.9, 1.7, 0.8),
];

#[test]
fn split_methods_match_a_fine_riemann_sum() {
    let tf = spiky_tf();
    let options = IntegratorOptions {
        unit_distance: 0.25,
        ..IntegratorOptions::default()
    };
    let knots = TfKnots::new(&tf, options.unit_distance, OpacityMode::Exact);
    for (method, tol) in [
        (Method::Exact, 2e-6),
        (Method::Ppi, 2e-5),
        (Method::Reference, 2e-6),
    ] {
        let integrator = ScalarIntegrator::new(method, &tf, &options).unwrap();
        for &(sf, sb, d) in &SEGMENTS {
            // 2e5 midpoint steps: error ~ h^2 |f''| / 24, below 1e-7 here.
            let want = fine_riemann(&knots, sf, sb, d, 200_000);
            let e = max_diff(integrator.integrate(sf, sb, d), want);
            assert!(e < tol, "{method} on ({sf}, {sb}, {d}): error {e}");
        }
    }
}

#[test]
fn not_splitting_at_knots_misses_the_spike() {
    // The dissertation's fig. 4.1: a segment spanning a narrow opacity peak
    // integrated from its end values alone does not see the peak.
    let tf = spiky_tf();
    let knots = TfKnots::new(&tf, 0.25, OpacityMode::Exact);
    let split = IntegratorOptions {
        unit_distance: 0.25,
        ..IntegratorOptions::default()
    };
    let unsplit = IntegratorOptions {
        split_at_knots: false,
        ..split.clone()
    };
    let (sf, sb, d) = (0.3, 0.7, 0.5);
    let want = fine_riemann(&knots, sf, sb, d, 200_000);
    let with = ScalarIntegrator::new(Method::Ppi, &tf, &split)
        .unwrap()
        .integrate(sf, sb, d);
    let without = ScalarIntegrator::new(Method::Ppi, &tf, &unsplit)
        .unwrap()
        .integrate(sf, sb, d);
    let (e_with, e_without) = (max_diff(with, want), max_diff(without, want));
    eprintln!("spike: split error {e_with:.2e}, unsplit error {e_without:.2e}");
    assert!(e_with < 2e-5 && e_without > 0.1, "{e_with} {e_without}");
}

#[test]
fn pieces_cover_the_segment_in_order() {
    let tf = spiky_tf();
    let knots = TfKnots::new(&tf, 1.0, OpacityMode::Vtk);
    // The colour step at 0.6 is two knots at one scalar.
    assert_eq!(knots.scalars().iter().filter(|&&x| x == 0.6).count(), 2);
    for &(sf, sb, d) in &SEGMENTS {
        let mut total = 0.0f64;
        let mut pieces = Vec::new();
        let count = knots.split(sf, sb, d, |p| {
            total += f64::from(p.length);
            pieces.push(*p);
        });
        assert_eq!(count, pieces.len());
        assert!(
            (total - f64::from(d)).abs() < 1e-6 * f64::from(d),
            "({sf}, {sb}): {total}"
        );
        // Interior knots between the end scalars, each cutting once (the
        // step's two knots cut once).
        let (lo, hi) = (sf.min(sb), sf.max(sb));
        let mut cuts: Vec<f32> = knots
            .scalars()
            .iter()
            .copied()
            .filter(|&x| x > lo && x < hi)
            .collect();
        cuts.dedup();
        assert_eq!(pieces.len(), cuts.len() + 1, "({sf}, {sb})");
        // Adjacent pieces meet with equal material unless a step sits there.
        for w in pieces.windows(2) {
            let (a, b) = (w[0].back, w[1].front);
            if (a.lum - b.lum).abs().max_element() > 1e-6 {
                assert!(cuts.contains(&0.6), "a jump away from the step");
            }
            assert!((a.tau - b.tau).abs().max_element() < 1e-4);
        }
    }
}

#[test]
fn full_preintegration_matches_at_its_length_and_corrects_others() {
    let tf = spiky_tf();
    let base = IntegratorOptions {
        unit_distance: 0.25,
        preintegration_length: 0.5,
        ..IntegratorOptions::default()
    };
    let knots = TfKnots::new(&tf, base.unit_distance, OpacityMode::Exact);
    let mut errors = Vec::new();
    for size in [64, 256, 1024] {
        let options = IntegratorOptions {
            preintegration_table_size: size,
            ..base.clone()
        };
        let integrator = ScalarIntegrator::new(Method::Preintegrated, &tf, &options).unwrap();
        let table = integrator.preintegration_table().unwrap();
        eprintln!("pre-integration {size}^2 built in {:?}", table.build_time());
        // At the table's length, scalars on nodes: the exact integral.
        let node = |i: usize| i as f32 / (size - 1) as f32;
        let (sf, sb) = (node(size / 7), node(size - 3));
        let want = fine_riemann(&knots, sf, sb, 0.5, 200_000);
        assert!(max_diff(integrator.integrate(sf, sb, 0.5), want) < 2e-6);
        // Off the nodes at the table's length: bilinear error shrinks with size.
        let worst = [(0.31, 0.77), (0.505, 0.49), (0.13, 0.62)]
            .iter()
            .map(|&(f, b)| {
                max_diff(
                    integrator.integrate(f, b, 0.5),
                    fine_riemann(&knots, f, b, 0.5, 200_000),
                )
            })
            .fold(0.0, f64::max);
        errors.push(worst);
    }
    eprintln!("pre-integration errors at D0 by size 64/256/1024: {errors:?}");
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
    // Other lengths: Schulze's correction is exact for constant material,
    // up to f32 rounding of T^(D/D0) (1.1e-5 measured at D/D0 = 18).
    let options = IntegratorOptions {
        preintegration_table_size: 256,
        ..base
    };
    let integrator = ScalarIntegrator::new(Method::Preintegrated, &tf, &options).unwrap();
    let exact = ScalarIntegrator::new(Method::Exact, &tf, &options).unwrap();
    for d in [0.05, 0.5, 2.0, 9.0] {
        let a = integrator.integrate(0.9, 0.9, d);
        let b = exact.integrate(0.9, 0.9, d);
        assert!(
            (a.emitted - b.emitted).abs().max_element() < 3e-5,
            "D {d}: {a:?} vs {b:?}"
        );
        assert!(
            (a.transmittance - b.transmittance).abs().max_element() < 3e-5,
            "D {d}"
        );
    }
}

#[test]
fn riemann_converges_to_the_exact_integral() {
    let tf = spiky_tf();
    let exact = ScalarIntegrator::new(
        Method::Exact,
        &tf,
        &IntegratorOptions {
            unit_distance: 0.25,
            ..IntegratorOptions::default()
        },
    )
    .unwrap();
    // Away from the spike, where the midpoint rule's h^2 error shows.
    let (sf, sb, d) = (0.6, 1.0, 2.0);
    let want = exact.integrate(sf, sb, d);
    let mut errors = Vec::new();
    for step in [0.4, 0.1, 0.025] {
        let options = IntegratorOptions {
            unit_distance: 0.25,
            riemann_step: step,
            ..IntegratorOptions::default()
        };
        let got = ScalarIntegrator::new(Method::Riemann, &tf, &options)
            .unwrap()
            .integrate(sf, sb, d);
        let e = (got.emitted - want.emitted).abs().max_element();
        errors.push(e);
    }
    eprintln!("riemann errors at steps 0.4/0.1/0.025: {errors:?}");
    // Second order: a quarter of the step, a sixteenth of the error.
    assert!(
        errors[0] > 10.0 * errors[1] && errors[1] > 10.0 * errors[2],
        "{errors:?}"
    );
    assert!(errors[2] < 1e-4);
}
