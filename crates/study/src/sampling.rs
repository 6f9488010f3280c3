//! `shearwarp`: the sampling-rate result of Schulze, Kraus, Lang and Ertl
//! (2003), section 2.3-2.4, through this project's shear-warp. One analytic
//! field is sampled on regular grids of decreasing spacing (the slice
//! distance), seen obliquely in parallel projection through a transfer
//! function of narrow opacity peaks (a high Nyquist frequency). Each grid is
//! rendered by shear-warp, pre-integrated and post-classified, and by the
//! exact tetrahedral ray caster on the same grid split into tetrahedra (the
//! reference: the exact integral of the same interpolated data). The error
//! is taken over the pixels whose ray crosses the grid through its two
//! principal faces (where shear-warp drops no side slabs).
//!
//! Post-classification needs a sampling rate of about pi f_U f_S (Carson's
//! rule) and converges slowly; pre-integration integrates the transfer
//! function exactly between slices and is accurate at the data's rate.

use glam::{DVec3, Vec3};
use serde::Serialize;
use tetray_core::{Camera, Image};
use tetray_engine::{
    Engine, FrameOptions, IntegratorChoice, Log, Source, TfSource, WalkOptions, prepare, tf,
};
use tetray_integrate::{ColorPoint, Method, OpacityPoint};
use tetray_shearwarp::{Classification, ClassifyOptions, RegularGrid, ShearWarp, ShearWarpOptions};

use crate::output::{Cell, Csv, OutputDir};
use crate::svg::Axis;
use crate::svg::line::{LinePanel, Series, line_figure};
use crate::{Check, StudyError};

/// Sizes of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct SamplingOptions {
    /// Points per axis of each grid (over the same box).
    pub grids: Vec<usize>,
    /// Image pixels per side.
    pub pixels: u32,
    /// Pre-integration table nodes per axis.
    pub table_size: usize,
}

impl Default for SamplingOptions {
    fn default() -> Self {
        SamplingOptions {
            grids: vec![9, 13, 17, 25, 33, 49],
            pixels: 128,
            table_size: 1024,
        }
    }
}

/// One grid, one classification.
#[derive(Debug, Clone, Serialize)]
pub struct SamplingRow {
    pub points_per_axis: usize,
    pub slice_distance: f64,
    pub classification: &'static str,
    pub pixels_compared: usize,
    pub mean_error: f64,
    pub max_error: f64,
    pub ms_per_frame: f64,
    /// Every pixel whose ray meets the grid, by the length of its chord
    /// through the grid in slice distances: where rays cross the grid's
    /// side faces, short chords cut slabs.
    pub by_chord: Vec<ChordBin>,
}

/// The error of the pixels whose chord through the grid is `slabs` slice
/// distances long.
#[derive(Debug, Clone, Serialize)]
pub struct ChordBin {
    pub slabs: &'static str,
    pub pixels: usize,
    pub mean_error: f64,
    pub max_error: f64,
}

/// Chord lengths binned, in slice distances: (label, upper bound).
const CHORD_BINS: [(&str, f64); 4] = [
    ("under 1", 1.0),
    ("1 to 4", 4.0),
    ("4 to 16", 16.0),
    ("16 and over", f64::INFINITY),
];

/// What the study found.
#[derive(Debug, Clone, Serialize)]
pub struct SamplingSummary {
    pub pixels: u32,
    pub table_size: usize,
    pub rows: Vec<SamplingRow>,
    pub checks: Vec<Check>,
}

/// The box every grid samples.
const HALF: f32 = 1.0;

/// The field: a smooth bump with a ripple.
fn field(p: Vec3) -> f32 {
    0.1 + 0.8 * (-1.5 * p.length_squared()).exp() + 0.05 * (3.0 * p.x).sin() * (2.0 * p.y).cos()
}

/// A transfer function's control points: colour and opacity.
type Points = (Vec<ColorPoint>, Vec<OpacityPoint>);

/// Eight narrow opacity peaks over the field's range, alternating colour.
fn peaks() -> Points {
    let mut color = Vec::new();
    let mut opacity = vec![OpacityPoint {
        scalar: 0.0,
        alpha: 0.0,
    }];
    for i in 0..8 {
        let s = 0.12 + 0.1 * i as f32;
        let rgb = if i % 2 == 0 {
            Vec3::new(1.0, 0.6, 0.2)
        } else {
            Vec3::new(0.2, 0.5, 1.0)
        };
        color.push(ColorPoint { scalar: s, rgb });
        color.push(ColorPoint {
            scalar: s + 0.04,
            rgb,
        });
        opacity.push(OpacityPoint {
            scalar: s,
            alpha: 0.0,
        });
        opacity.push(OpacityPoint {
            scalar: s + 0.02,
            alpha: 0.6,
        });
        opacity.push(OpacityPoint {
            scalar: s + 0.04,
            alpha: 0.0,
        });
    }
    (color, opacity)
}

/// Runs the study, writing its plot and tables into `out`.
pub fn run(
    options: &SamplingOptions,
    out: &mut OutputDir,
    log: &dyn Fn(&str),
) -> Result<SamplingSummary, StudyError> {
    if options.grids.len() < 2 || options.grids.iter().any(|&n| n < 5) || options.pixels < 16 {
        return Err(StudyError::Option(
            "shearwarp: needs two or more grids of 5 or more points per axis and 16 pixels".into(),
        ));
    }
    let points = peaks();
    let tf = tf::from_points(points.0.clone(), points.1.clone())?;
    let unit = 0.1;
    let mut rows = Vec::new();
    for &n in &options.grids {
        let h = 2.0 * HALF / (n - 1) as f32;
        let grid = RegularGrid::from_fn([n; 3], Vec3::splat(-HALF), Vec3::splat(h), field)?;
        let camera = view(&grid)?;
        let reference = reference(&grid, &points, &camera, options.pixels, unit)?;
        for c in [
            Classification::PreIntegrated,
            Classification::PostClassified,
        ] {
            let sw = ShearWarp::new(
                grid.clone(),
                &tf,
                &ClassifyOptions {
                    classification: c,
                    unit_distance: unit,
                    table_size: options.table_size,
                    ..ClassifyOptions::default()
                },
            )?;
            let frame = ShearWarpOptions {
                width: options.pixels,
                height: options.pixels,
                ..ShearWarpOptions::default()
            };
            let image = sw.render(&camera, &frame)?;
            let (mean, max, count, by_chord) = error(&grid, &camera, &image.image, &reference);
            log(&format!(
                "shearwarp: {n}^3 (slice distance {h:.4}) {}: mean error {mean:.2e}, max {max:.2e} over {count} pixels",
                c.name()
            ));
            rows.push(SamplingRow {
                points_per_axis: n,
                slice_distance: f64::from(h),
                classification: c.name(),
                pixels_compared: count,
                mean_error: mean,
                max_error: max,
                ms_per_frame: image.stats.elapsed.as_secs_f64() * 1e3,
                by_chord,
            });
        }
    }
    write(out, options, &rows)?;
    let checks = checks(&rows);
    let summary = SamplingSummary {
        pixels: options.pixels,
        table_size: options.table_size,
        rows,
        checks,
    };
    out.json("summary.json", &summary)?;
    Ok(summary)
}

/// Parallel projection, azimuth 30, elevation 20 after the ResetCamera fit.
fn view(grid: &RegularGrid) -> Result<Camera, StudyError> {
    let mut camera = Camera {
        parallel_scale: Some(1.0),
        ..Camera::default()
    };
    let (lo, hi) = grid.bounds();
    camera.reset(lo, hi, 1.0)?;
    camera.azimuth(30.0)?;
    camera.elevation(20.0)?;
    camera.orthogonalize_view_up()?;
    Ok(camera)
}

/// The exact tetrahedral ray caster on the grid split into tetrahedra,
/// made and rendered by the engine as `tetray render` makes a frame.
fn reference(
    grid: &RegularGrid,
    (color, opacity): &Points,
    camera: &Camera,
    pixels: u32,
    unit: f32,
) -> Result<Image, StudyError> {
    let mesh = tetray_mesh::prepare(grid.to_tet_mesh("s"))?;
    let options = FrameOptions {
        integrator: IntegratorChoice {
            scalar: Some("s".into()),
            method: Method::Exact,
            tf: TfSource::Points {
                color: color.clone(),
                opacity: opacity.clone(),
            },
            unit_distance: Some(unit),
            ..IntegratorChoice::default()
        },
        size: (pixels, pixels),
        ..FrameOptions::default()
    };
    let source = Source::Mesh {
        mesh: Box::new(mesh),
        name: "the grid split into tetrahedra".into(),
    };
    let setup = prepare(source, &options, Log::quiet())?;
    let frame = Engine::Cpu.render(
        &setup,
        camera,
        WalkOptions::default(),
        (pixels, pixels),
        None,
    )?;
    Ok(frame.image)
}

/// Mean and largest absolute difference over the RGBA channels of the
/// pixels whose ray enters and leaves through the faces perpendicular to
/// the principal axis, 1.5 cells inside their edges; their number; and
/// the error of every pixel whose ray meets the grid by its chord length.
fn error(
    grid: &RegularGrid,
    camera: &Camera,
    image: &Image,
    reference: &Image,
) -> (f64, f64, usize, Vec<ChordBin>) {
    let Ok(rays) = camera.pixel_rays(image.width, image.height) else {
        return (f64::NAN, f64::NAN, 0, Vec::new());
    };
    // Per chord bin: pixels, error sum, largest error.
    let mut bins = [(0usize, 0.0f64, 0.0f64); CHORD_BINS.len()];
    let (lo, hi) = grid.bounds();
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    let spacing = grid.spacing().as_dvec3();
    let dir = (camera.focal_point - camera.position).as_dvec3() / spacing;
    let axis = (0..3)
        .max_by(|&i, &j| dir[i].abs().total_cmp(&dir[j].abs()))
        .unwrap_or(2);
    let inside = |p: DVec3| {
        (0..3).all(|a| {
            a == axis || (p[a] > lo[a] + 1.5 * spacing[a] && p[a] < hi[a] - 1.5 * spacing[a])
        })
    };
    let (mut sum, mut max, mut count) = (0.0f64, 0.0f64, 0usize);
    for py in 0..image.height {
        for px in 0..image.width {
            let ray = rays.ray(px, py);
            let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
            let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
            let (mut a0, mut a1) = (3, 3);
            for a in 0..3 {
                let (ta, tb) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
                if ta.min(tb) > t0 {
                    t0 = ta.min(tb);
                    a0 = a;
                }
                if ta.max(tb) < t1 {
                    t1 = ta.max(tb);
                    a1 = a;
                }
            }
            if t1 <= t0.max(0.0) {
                continue;
            }
            let i = (py * image.width + px) as usize;
            let e = (0..4).map(|c| f64::from((image.rgba[i][c] - reference.rgba[i][c]).abs()));
            let slabs = (t1 - t0.max(0.0)) * d.length() / spacing[axis];
            let bin = CHORD_BINS
                .iter()
                .position(|&(_, upper)| slabs < upper)
                .unwrap_or(0);
            bins[bin].0 += 1;
            for e in e.clone() {
                bins[bin].1 += e;
                bins[bin].2 = bins[bin].2.max(e);
            }
            let full = a0 == axis && a1 == axis && inside(o + d * t0) && inside(o + d * t1);
            if !full {
                continue;
            }
            for e in e {
                sum += e;
                max = max.max(e);
            }
            count += 1;
        }
    }
    let by_chord = CHORD_BINS
        .iter()
        .zip(bins)
        .map(|(&(slabs, _), (pixels, sum, max))| ChordBin {
            slabs,
            pixels,
            mean_error: sum / (4 * pixels.max(1)) as f64,
            max_error: max,
        })
        .collect();
    (sum / (4 * count.max(1)) as f64, max, count, by_chord)
}

fn write(
    out: &mut OutputDir,
    options: &SamplingOptions,
    rows: &[SamplingRow],
) -> Result<(), StudyError> {
    let mut csv = Csv::new(&[
        "points_per_axis",
        "slice_distance",
        "classification",
        "pixels_compared",
        "mean_error",
        "max_error",
        "ms_per_frame",
    ]);
    for r in rows {
        csv.row(&[
            Cell::Int(r.points_per_axis as u64),
            Cell::Num(r.slice_distance),
            Cell::Text(r.classification.into()),
            Cell::Int(r.pixels_compared as u64),
            Cell::Num(r.mean_error),
            Cell::Num(r.max_error),
            Cell::Num(r.ms_per_frame),
        ]);
    }
    out.csv("sampling.csv", &csv)?;
    let mut chords = Csv::new(&[
        "points_per_axis",
        "classification",
        "chord_slice_distances",
        "pixels",
        "mean_error",
        "max_error",
    ]);
    for r in rows {
        for b in &r.by_chord {
            chords.row(&[
                Cell::Int(r.points_per_axis as u64),
                Cell::Text(r.classification.into()),
                Cell::Text(b.slabs.into()),
                Cell::Int(b.pixels as u64),
                Cell::Num(b.mean_error),
                Cell::Num(b.max_error),
            ]);
        }
    }
    out.csv("sampling_by_chord.csv", &chords)?;
    let series = |c: Classification, colour: usize, max: bool| {
        let points = rows
            .iter()
            .filter(|r| r.classification == c.name())
            .map(|r| {
                (
                    r.slice_distance,
                    if max { r.max_error } else { r.mean_error }.max(1e-9),
                )
            })
            .collect();
        let label = format!("{} {}", c.name(), if max { "max" } else { "mean" });
        let s = Series::new(label, colour, points).with_markers();
        if max { s.dashed() } else { s }
    };
    let panel = LinePanel {
        title: format!(
            "error against the exact tetrahedral ray caster ({0}x{0} px, table {1}^2)",
            options.pixels, options.table_size
        ),
        x: Axis::log("slice distance (grid spacing)"),
        y: Axis::log("absolute error (RGBA)"),
        series: vec![
            series(Classification::PreIntegrated, 0, false),
            series(Classification::PreIntegrated, 0, true),
            series(Classification::PostClassified, 1, false),
            series(Classification::PostClassified, 1, true),
        ],
    };
    out.write(
        "sampling.svg",
        &line_figure(
            "Shear-warp: pre-integrated vs post-classified over the slice distance (Schulze et al. 2003)",
            &[panel],
            1,
        ),
    )
}

fn checks(rows: &[SamplingRow]) -> Vec<Check> {
    let of = |c: Classification| -> Vec<&SamplingRow> {
        rows.iter()
            .filter(|r| r.classification == c.name())
            .collect()
    };
    let (pre, post) = (
        of(Classification::PreIntegrated),
        of(Classification::PostClassified),
    );
    let better = pre
        .iter()
        .zip(&post)
        .all(|(a, b)| a.mean_error < b.mean_error);
    let detail: Vec<String> = pre
        .iter()
        .zip(&post)
        .map(|(a, b)| {
            format!(
                "{}: {:.2e} vs {:.2e}",
                a.points_per_axis, a.mean_error, b.mean_error
            )
        })
        .collect();
    let converges = match (post.first(), post.last()) {
        (Some(coarse), Some(fine)) => fine.mean_error < coarse.mean_error,
        _ => false,
    };
    let compared = rows.iter().all(|r| r.pixels_compared > 0);
    vec![
        Check::new(
            "pre-integrated mean error below post-classified at every slice distance",
            better,
            detail.join(", "),
        ),
        Check::new(
            "post-classified error falls as the slices get closer",
            converges,
            format!(
                "coarsest {:.2e}, finest {:.2e}",
                post.first().map_or(f64::NAN, |r| r.mean_error),
                post.last().map_or(f64::NAN, |r| r.mean_error)
            ),
        ),
        Check::new("every grid has compared pixels", compared, String::new()),
    ]
}
