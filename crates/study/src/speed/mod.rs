//! `speed`: the timing tables of the dissertation (tables 6.3, 6.4) for our
//! renderers and integrators on the three datasets: frames/s, tetrahedra/s
//! (mesh tetrahedra times frames/s, the dissertation's measure) and
//! segments/s, with the adapter named; frames/s against image size
//! (fig. 6.3); and a sweep over generated meshes of growing size.
//!
//! Renderers: the CPU ray caster (rayon, wall clock), the GPU ray caster
//! (wall clock from submission to completion; see [`GpuRig::time`] for why
//! not timestamp queries) and the GPU cell projection of `tetray-project`
//! (balanced projected tetrahedra, adaptive transfer-function sampling,
//! MPVONC sort; wall clock of the whole frame, sort included).

mod setup;
mod timing;

use std::path::PathBuf;

use serde::Serialize;
use tetray_core::Camera;
use tetray_gpu::{GpuIntegrator, GpuScene};
use tetray_integrate::Method;

pub use setup::{DATASETS, Dataset, Prepared, cells_for, generated_box, load_dataset};
pub use timing::{GpuRig, Timing, time_cpu, time_projection};

use crate::cells;
use crate::output::{Csv, OutputDir};
use crate::svg::Axis;
use crate::svg::line::{LinePanel, Series, line_figure};
use crate::svg::table::table_figure;
use crate::{Check, StudyError};

/// Sizes of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedOptions {
    /// Folder of the PLOT3D datasets ([`DATASETS`]).
    pub data_dir: PathBuf,
    /// Image size of the timing table and the mesh sweep.
    pub size: (u32, u32),
    /// Timed frames per measurement (after one warm-up frame).
    pub frames: u32,
    pub methods: Vec<Method>,
    /// Square image sizes of the resolution sweep (Blunt Fin, default method).
    pub resolutions: Vec<u32>,
    /// Tetrahedra of the generated meshes (rounded to whole boxes).
    pub scaling_tets: Vec<usize>,
    /// Time the GPU ray caster when an adapter exists.
    pub gpu: bool,
}

impl SpeedOptions {
    /// The default: small enough for minutes on two cores.
    pub fn small(data_dir: PathBuf) -> SpeedOptions {
        SpeedOptions {
            data_dir,
            size: (96, 96),
            frames: 2,
            methods: TABLE_METHODS.to_vec(),
            resolutions: vec![16, 32, 64, 128, 256],
            scaling_tets: vec![250_000, 500_000, 1_000_000],
            gpu: true,
        }
    }

    /// The dissertation's size: 800 x 800, an orbit of 8 frames, meshes
    /// from 1 M to 40 M tetrahedra (hours on a CPU adapter).
    pub fn full(data_dir: PathBuf) -> SpeedOptions {
        SpeedOptions {
            size: (800, 800),
            frames: 8,
            resolutions: vec![16, 32, 64, 128, 256, 512, 800, 1024],
            scaling_tets: vec![
                1_000_000, 2_000_000, 5_000_000, 10_000_000, 20_000_000, 40_000_000,
            ],
            ..SpeedOptions::small(data_dir)
        }
    }
}

/// Table 6.4's methods, then full pre-integration and the Riemann sum.
pub const TABLE_METHODS: [Method; 8] = [
    Method::Average,
    Method::Exact,
    Method::Ppi,
    Method::AverageOpacity,
    Method::LinAvgOpacity,
    Method::LinOpacity,
    Method::Preintegrated,
    Method::Riemann,
];

/// One row of the timing table.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    pub mesh: String,
    pub tets: usize,
    pub renderer: &'static str,
    pub method: &'static str,
    pub width: u32,
    pub height: u32,
    pub ms_per_frame: f64,
    pub fps: f64,
    pub tets_per_s: f64,
    pub segments_per_frame: f64,
    pub segments_per_s: f64,
    pub clock: &'static str,
}

/// A measurement that could not be made (e.g. a mesh beyond the adapter's
/// binding limits), and why.
#[derive(Debug, Clone, Serialize)]
pub struct Skipped {
    pub mesh: String,
    pub renderer: &'static str,
    pub reason: String,
}

/// A generated mesh of the sweep and what it took to make.
#[derive(Debug, Clone, Serialize)]
pub struct Generated {
    pub tets: usize,
    pub build_s: f64,
    pub scene_s: f64,
}

/// What the study found.
#[derive(Debug, Clone, Serialize)]
pub struct SpeedSummary {
    pub cpu: String,
    pub gpu_adapter: Option<String>,
    pub notes: Vec<String>,
    pub table: Vec<Row>,
    pub resolution: Vec<Row>,
    pub scaling: Vec<Row>,
    pub generated: Vec<Generated>,
    pub skipped: Vec<Skipped>,
    pub checks: Vec<Check>,
}

/// The renderers of a run and where their rows go.
struct Run<'a> {
    options: &'a SpeedOptions,
    gpu: Option<GpuRig>,
    skipped: Vec<Skipped>,
    log: &'a dyn Fn(&str),
}

impl Run<'_> {
    /// Times `methods` on `prepared` with every renderer at `size`.
    fn measure(
        &mut self,
        prepared: &Prepared,
        camera: &Camera,
        methods: &[Method],
        size: (u32, u32),
    ) -> Result<Vec<Row>, StudyError> {
        let frames = self.options.frames;
        let tets = prepared.scene().tet_count();
        let row = |renderer, method: Method, t: Timing| Row {
            mesh: prepared.name.clone(),
            tets,
            renderer,
            method: method.name(),
            width: size.0,
            height: size.1,
            ms_per_frame: t.ms_per_frame,
            fps: t.fps(),
            tets_per_s: tets as f64 * t.fps(),
            segments_per_frame: t.segments_per_frame,
            segments_per_s: t.segments_per_s(),
            clock: t.clock,
        };
        let mut rows = Vec::new();
        let integrators = methods
            .iter()
            .map(|&m| prepared.integrator(m))
            .collect::<Result<Vec<_>, _>>()?;
        for (&method, integrator) in methods.iter().zip(&integrators) {
            let t = time_cpu(prepared.scene(), camera, integrator, size, frames)?;
            rows.push(row("cpu", method, t));
        }
        if let Some(gpu) = &self.gpu {
            match GpuScene::new(&gpu.ctx, prepared.scene()) {
                Ok(scene) => {
                    let mut projection = None;
                    for (&method, integrator) in methods.iter().zip(&integrators) {
                        let uploaded = GpuIntegrator::new(&gpu.ctx, integrator)?;
                        let t = gpu.time(&scene, &uploaded, camera, size, frames)?;
                        rows.push(row("gpu", method, t));
                        // One projection scene per mesh: the methods share
                        // the transfer function, so its knot intervals.
                        if projection.is_none() {
                            projection = Some(tetray_project::Projection::new(
                                &gpu.ctx,
                                prepared.scene(),
                                &uploaded,
                            )?);
                        }
                        if let Some(projection) = &projection {
                            let t =
                                time_projection(gpu, projection, &uploaded, camera, size, frames)?;
                            rows.push(row("projection", method, t));
                        }
                    }
                }
                Err(e) => {
                    (self.log)(&format!("speed: {}: GPU skipped: {e}", prepared.name));
                    self.skipped.push(Skipped {
                        mesh: prepared.name.clone(),
                        renderer: "gpu",
                        reason: e.to_string(),
                    });
                }
            }
        }
        Ok(rows)
    }
}

/// Runs the study, writing its plots and tables into `out`.
pub fn run(
    options: &SpeedOptions,
    out: &mut OutputDir,
    log: &dyn Fn(&str),
) -> Result<SpeedSummary, StudyError> {
    if options.frames == 0 || options.methods.is_empty() || options.size.0 * options.size.1 == 0 {
        return Err(StudyError::Option(
            "speed: needs at least one frame, one method and a non-empty image".into(),
        ));
    }
    if let Some(m) = options.methods.iter().find(|m| !m.has_gpu_kernel()) {
        return Err(StudyError::Option(format!(
            "speed: {m} is an f64 reference with no GPU kernel; time the renderers' methods"
        )));
    }
    let mut notes = vec![
        "projection: tetray-project's cell projection (adaptive transfer-function sampling, \
         MPVONC sort), timed by wall clock over sort and draw"
            .to_string(),
        "gpu: the ray caster timed by wall clock from submission to completion, like the \
         projection (lavapipe's timestamp queries misread compute passes once a render pass \
         has run on the device)"
            .to_string(),
    ];
    let gpu = if options.gpu {
        match GpuRig::new() {
            Ok(rig) => {
                if rig.ctx.is_cpu() {
                    notes.push(format!(
                        "the GPU adapter {} is a CPU implementation of the API: its times are \
                         not those of a graphics card",
                        rig.ctx.adapter_name()
                    ));
                }
                Some(rig)
            }
            Err(e) => {
                notes.push(format!("GPU ray caster not timed: {e}"));
                None
            }
        }
    } else {
        notes.push("GPU ray caster not requested".into());
        None
    };
    let gpu_adapter = gpu.as_ref().map(|g| g.ctx.adapter_name());
    let mut run = Run {
        options,
        gpu,
        skipped: Vec::new(),
        log,
    };

    // Tables 6.3 / 6.4.
    let mut table = Vec::new();
    let mut resolution = Vec::new();
    for (k, dataset) in DATASETS.iter().enumerate() {
        let prepared = load_dataset(&options.data_dir, dataset, options.size)?;
        log(&format!(
            "speed: {} ({} tetrahedra) loaded in {:.2} s",
            dataset.name,
            prepared.scene().tet_count(),
            prepared.load_s + prepared.scene_s
        ));
        table.extend(run.measure(
            &prepared,
            &prepared.setup.camera,
            &options.methods,
            options.size,
        )?);
        // Fig. 6.3 on the first dataset, with the default method.
        if k == 0 {
            let (lo, hi) = prepared.scene().bounds();
            let mut square = Camera::default();
            square.reset(lo, hi, 1.0)?;
            for &edge in &options.resolutions {
                resolution.extend(run.measure(&prepared, &square, &[Method::Ppi], (edge, edge))?);
            }
            log("speed: resolution sweep done");
        }
    }

    // Generated meshes.
    let mut scaling = Vec::new();
    let mut generated = Vec::new();
    for &target in &options.scaling_tets {
        let prepared = generated_box(cells_for(target), options.size)?;
        let tets = prepared.scene().tet_count();
        log(&format!(
            "speed: {} ({tets} tetrahedra) built in {:.2} s",
            prepared.name,
            prepared.load_s + prepared.scene_s
        ));
        generated.push(Generated {
            tets,
            build_s: prepared.load_s,
            scene_s: prepared.scene_s,
        });
        scaling.extend(run.measure(
            &prepared,
            &prepared.setup.camera,
            &[Method::Ppi],
            options.size,
        )?);
    }

    let cpu = format!(
        "cpu ray caster (rayon, {} threads)",
        rayon::current_num_threads()
    );
    let checks = checks(&table, &resolution);
    let summary = SpeedSummary {
        cpu,
        gpu_adapter,
        notes,
        table,
        resolution,
        scaling,
        generated,
        skipped: run.skipped,
        checks,
    };
    write(&summary, options, out)?;
    Ok(summary)
}

/// Every measurement rendered something; both renderers walked the same
/// segments (they share the walk and the exit rule); larger images walk
/// more segments. No check reads a clock.
fn checks(table: &[Row], resolution: &[Row]) -> Vec<Check> {
    let mut checks = Vec::new();
    let empty: Vec<String> = table
        .iter()
        .chain(resolution)
        .filter(|r| !(r.fps > 0.0 && r.segments_per_frame > 0.0))
        .map(|r| format!("{} {} {}", r.mesh, r.renderer, r.method))
        .collect();
    checks.push(Check::new(
        "every frame was timed and integrated segments",
        empty.is_empty(),
        empty.join("; "),
    ));
    for cpu in table.iter().filter(|r| r.renderer == "cpu") {
        let gpu = table
            .iter()
            .find(|r| r.renderer == "gpu" && r.mesh == cpu.mesh && r.method == cpu.method);
        if let Some(gpu) = gpu {
            let ratio = gpu.segments_per_frame / cpu.segments_per_frame;
            checks.push(Check::new(
                format!(
                    "{} {}: GPU and CPU walk the same segments",
                    cpu.mesh, cpu.method
                ),
                (ratio - 1.0).abs() < 1e-3,
                format!("{} vs {}", gpu.segments_per_frame, cpu.segments_per_frame),
            ));
        }
    }
    // Frame times are measured, not checked: on a shared machine one
    // wall-clock sample of each size says nothing reliable (speed belongs in
    // the benchmarks). What cannot depend on load is the work: a ray caster
    // integrates a segment per pixel per cell crossed, so an image of 64x
    // the pixels walks more segments.
    for renderer in ["cpu", "gpu"] {
        let rows: Vec<&Row> = resolution
            .iter()
            .filter(|r| r.renderer == renderer)
            .collect();
        if let (Some(first), Some(last)) = (rows.first(), rows.last())
            && last.width * last.height >= 64 * first.width * first.height
        {
            checks.push(Check::new(
                format!("{renderer}: a frame of 64x the pixels walks more segments"),
                last.segments_per_frame > first.segments_per_frame,
                format!(
                    "{}x{} {:.0} segments, {}x{} {:.0} segments",
                    first.width,
                    first.height,
                    first.segments_per_frame,
                    last.width,
                    last.height,
                    last.segments_per_frame
                ),
            ));
        }
    }
    checks
}

fn csv_of(rows: &[Row]) -> Csv {
    let mut csv = Csv::new(&[
        "mesh",
        "tets",
        "renderer",
        "method",
        "width",
        "height",
        "ms_per_frame",
        "fps",
        "tets_per_s",
        "segments_per_frame",
        "segments_per_s",
        "clock",
    ]);
    for r in rows {
        csv.row(&cells![
            r.mesh.as_str(),
            r.tets,
            r.renderer,
            r.method,
            r.width as usize,
            r.height as usize,
            r.ms_per_frame,
            r.fps,
            r.tets_per_s,
            r.segments_per_frame,
            r.segments_per_s,
            r.clock
        ]);
    }
    csv
}

/// "1.23 M"-style numbers for the tables.
fn si(v: f64) -> String {
    if v >= 1e9 {
        format!("{:.2} G", v / 1e9)
    } else if v >= 1e6 {
        format!("{:.2} M", v / 1e6)
    } else if v >= 1e3 {
        format!("{:.1} K", v / 1e3)
    } else {
        format!("{v:.1}")
    }
}

fn write(
    summary: &SpeedSummary,
    options: &SpeedOptions,
    out: &mut OutputDir,
) -> Result<(), StudyError> {
    out.csv("speed_table.csv", &csv_of(&summary.table))?;
    out.csv("speed_resolution.csv", &csv_of(&summary.resolution))?;
    out.csv("speed_scaling.csv", &csv_of(&summary.scaling))?;
    out.json("speed.json", summary)?;

    let header = [
        "mesh",
        "tets",
        "renderer",
        "method",
        "ms/frame",
        "frames/s",
        "tets/s",
        "segments/s",
    ];
    let rows: Vec<Vec<String>> = summary
        .table
        .iter()
        .map(|r| {
            vec![
                r.mesh.clone(),
                r.tets.to_string(),
                r.renderer.to_string(),
                r.method.to_string(),
                format!("{:.2}", r.ms_per_frame),
                format!("{:.3}", r.fps),
                si(r.tets_per_s),
                si(r.segments_per_s),
            ]
        })
        .collect();
    let gpu = summary.gpu_adapter.as_deref().unwrap_or("none");
    let title = format!(
        "Frame rates at {}x{} (tables 6.3, 6.4); GPU: {gpu}",
        options.size.0, options.size.1
    );
    out.write("speed_table.svg", &table_figure(&title, &header, &rows))?;
    let mut md = format!(
        "{title}\n\n| {} |\n|{}\n",
        header.join(" | "),
        " --- |".repeat(header.len())
    );
    for row in &rows {
        md.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    for note in &summary.notes {
        md.push_str(&format!("\n- {note}"));
    }
    out.write("speed_table.md", &(md + "\n"))?;

    let by_renderer = |rows: &[Row], x: &dyn Fn(&Row) -> f64, y: &dyn Fn(&Row) -> f64| {
        ["cpu", "gpu", "projection"]
            .iter()
            .enumerate()
            .filter(|(_, name)| rows.iter().any(|r| r.renderer == **name))
            .map(|(c, &name)| {
                let points = rows
                    .iter()
                    .filter(|r| r.renderer == name)
                    .map(|r| (x(r), y(r)))
                    .collect();
                let label = match name {
                    "projection" => "cell projection (gpu)".to_string(),
                    _ => format!("{name} ray caster"),
                };
                Series::new(label, c, points).with_markers()
            })
            .collect::<Vec<_>>()
    };
    let pixels = |r: &Row| f64::from(r.width) * f64::from(r.height);
    let resolution_mesh = summary.resolution.first().map_or("", |r| r.mesh.as_str());
    let svg = line_figure(
        &format!("Frame rate against image size, {resolution_mesh}, ppi (fig. 6.3)"),
        &[
            LinePanel {
                title: "frames per second".into(),
                x: Axis::log("pixels"),
                y: Axis::log("frames/s"),
                series: by_renderer(&summary.resolution, &pixels, &|r| r.fps),
            },
            LinePanel {
                title: "rays per second".into(),
                x: Axis::log("pixels"),
                y: Axis::log("rays/s"),
                series: by_renderer(&summary.resolution, &pixels, &|r| pixels(r) * r.fps),
            },
        ],
        2,
    );
    out.write("speed_resolution.svg", &svg)?;

    let tets = |r: &Row| r.tets as f64;
    let build = Series::new(
        "topology + scene (cpu)",
        2,
        summary
            .generated
            .iter()
            .map(|g| (g.tets as f64, g.build_s + g.scene_s))
            .collect(),
    )
    .with_markers();
    let svg = line_figure(
        &format!(
            "Generated boxes (5 tetrahedra per hexahedron) at {}x{}, ppi",
            options.size.0, options.size.1
        ),
        &[
            LinePanel {
                title: "frames per second".into(),
                x: Axis::log("tetrahedra"),
                y: Axis::log("frames/s"),
                series: by_renderer(&summary.scaling, &tets, &|r| r.fps),
            },
            LinePanel {
                title: "tetrahedra per second (tets x frames/s)".into(),
                x: Axis::log("tetrahedra"),
                y: Axis::log("tets/s"),
                series: by_renderer(&summary.scaling, &tets, &|r| r.tets_per_s),
            },
            LinePanel {
                title: "time to build the mesh's topology and scene".into(),
                x: Axis::log("tetrahedra"),
                y: Axis::log("seconds"),
                series: vec![build],
            },
        ],
        3,
    );
    out.write("speed_scaling.svg", &svg)?;
    Ok(())
}
