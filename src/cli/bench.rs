//! `tetray bench`: frame times over an orbit of the camera, as JSON.

use super::args::{FrameFlags, WalkArgs};
use super::parse::{parse_finite, parse_size};
use super::{render, scene};
use clap::Args;
use serde::Serialize;
use tetray_engine::Engine;

/// `tetray bench`.
#[derive(Debug, Clone, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    pub frame: FrameFlags,
    #[command(flatten)]
    pub walk: WalkArgs,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "512x512")]
    pub size: (u32, u32),
    /// Frames to time, after one untimed warm-up frame.
    #[arg(long, value_name = "N", default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// Degrees of azimuth between frames, about the focal point. Default:
    /// 360 / frames, one full orbit; 0 times a single view.
    #[arg(long, value_name = "DEGREES", value_parser = parse_finite, allow_hyphen_values = true)]
    pub orbit_step: Option<f32>,
    #[cfg(feature = "mpi")]
    #[command(flatten)]
    pub distributed: super::args::DistributedArgs,
}

#[derive(Debug, Serialize)]
struct BenchJson {
    renderer: &'static str,
    adapter: String,
    /// How frame times were measured.
    timing: &'static str,
    threads: usize,
    mesh: String,
    tets: usize,
    boundary_faces: usize,
    size: String,
    width: u32,
    height: u32,
    integrator: &'static str,
    unit_distance: f32,
    early_termination: f32,
    frames: u32,
    orbit_step_degrees: f32,
    ms_per_frame_median: f64,
    ms_per_frame_min: f64,
    ms_per_frame_max: f64,
    /// Median absolute deviation of the frame times.
    ms_per_frame_mad: f64,
    rays_per_s: f64,
    segments_per_s: f64,
    segments_per_frame: f64,
    /// Mesh tetrahedra times frames per second (the dissertation's tets/s).
    tets_per_s: f64,
    /// Tetrahedra the rays walked through, per second.
    tet_steps_per_s: f64,
    steps_bound_hits: u64,
    walk_failures: u64,
    /// Frames whose rays took their boundary entries from per-pixel lists
    /// (CPU ray caster) rather than BVH queries.
    entry_lists_frames: u32,
    load_s: f64,
    scene_s: f64,
    integrator_setup_s: f64,
    /// --renderer project: its stages apart (ms_per_frame_* is their sum).
    #[serde(skip_serializing_if = "Option::is_none")]
    projection: Option<ProjectionJson>,
}

#[derive(Debug, Serialize)]
struct ProjectionJson {
    sort: &'static str,
    adaptive_tf: bool,
    /// Visibility sort on the CPU (rayon).
    sort_ms_median: f64,
    /// Sorted cells to draws (pieces ordered within cells), CPU.
    draw_list_ms_median: f64,
    /// The render pass, by `draw_timing`.
    draw_ms_median: f64,
    draw_timing: &'static str,
    /// Submission to read-back, all of it.
    wall_ms_median: f64,
    draws_per_frame: f64,
    extra_draws_per_frame: f64,
    /// Extra draws of adaptive sampling over one per cell, in percent.
    extra_draws_percent: f64,
    cycle_breaks: usize,
}

pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    scene::configure_threads(args.walk.threads)?;
    let frame = scene::FrameArgs {
        flags: &args.frame,
        walk: &args.walk,
        size: args.size,
    };
    // Progress goes to stderr; stdout holds only the JSON.
    let setup = scene::prepare(frame, &|line| eprintln!("{line}"))?;
    let engine = Engine::new(args.walk.renderer, &setup, &|line| eprintln!("{line}"))?;
    let orbit_step = args.orbit_step.unwrap_or(360.0 / args.frames as f32);
    let timing = tetray_engine::Timing {
        frames: args.frames,
        orbit_step,
        warm_up: true,
    };
    let walk = tetray_engine::WalkOptions::from(&args.walk);
    let measured = tetray_engine::measure(&engine, &setup, &setup.camera, walk, args.size, timing)?;
    let times_ms = measured.times_ms();
    let stages: Vec<tetray_project::ProjectStats> =
        measured.frames.iter().filter_map(|s| s.project).collect();
    let total = measured.total;
    let entry_lists_frames = measured.frames.iter().filter(|s| s.entry_lists).count() as u32;
    render::warn_about(&total);

    let total_s = times_ms.iter().sum::<f64>() / 1e3;
    let per_s = |count: f64| count / total_s.max(1e-12);
    let median = tetray_engine::median(&times_ms);
    let deviations: Vec<f64> = times_ms.iter().map(|t| (t - median).abs()).collect();
    let threads = rayon::current_num_threads();
    let frames = f64::from(args.frames);
    let tets = setup.tet_count();
    let json = BenchJson {
        renderer: engine.name(),
        adapter: engine.adapter(),
        timing: if engine.gpu_timestamps() {
            "gpu timestamp queries"
        } else {
            "wall clock"
        },
        threads,
        mesh: setup.name().to_string(),
        tets,
        boundary_faces: setup.boundary_faces(),
        size: format!("{}x{}", args.size.0, args.size.1),
        width: args.size.0,
        height: args.size.1,
        integrator: setup.method.name(),
        unit_distance: setup.unit_distance,
        early_termination: args.walk.early_termination,
        frames: args.frames,
        orbit_step_degrees: orbit_step,
        ms_per_frame_median: median,
        ms_per_frame_min: times_ms.iter().copied().fold(f64::INFINITY, f64::min),
        ms_per_frame_max: times_ms.iter().copied().fold(0.0, f64::max),
        ms_per_frame_mad: tetray_engine::median(&deviations),
        rays_per_s: per_s(total.rays as f64),
        segments_per_s: per_s(total.segments as f64),
        segments_per_frame: total.segments as f64 / frames,
        tets_per_s: per_s(tets as f64 * frames),
        tet_steps_per_s: per_s(total.steps as f64),
        steps_bound_hits: total.steps_bound_hits,
        walk_failures: total.walk_failures,
        entry_lists_frames,
        load_s: setup.load_time.as_secs_f64(),
        scene_s: setup.scene_time.as_secs_f64(),
        integrator_setup_s: setup.integrator_time.as_secs_f64(),
        projection: (!stages.is_empty()).then(|| projection_json(&stages, &args.walk)),
    };
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}

/// Medians of the projection's stages over the frames.
fn projection_json(stages: &[tetray_project::ProjectStats], walk: &WalkArgs) -> ProjectionJson {
    let ms = |f: &dyn Fn(&tetray_project::ProjectStats) -> std::time::Duration| {
        tetray_engine::median(
            &stages
                .iter()
                .map(|s| f(s).as_secs_f64() * 1e3)
                .collect::<Vec<_>>(),
        )
    };
    let mean = |f: &dyn Fn(&tetray_project::ProjectStats) -> usize| {
        stages.iter().map(f).sum::<usize>() as f64 / stages.len() as f64
    };
    let (draws, extra, tets) = (
        mean(&|s| s.draws),
        mean(&|s| s.extra_draws),
        mean(&|s| s.tets),
    );
    ProjectionJson {
        sort: walk.sort.name(),
        adaptive_tf: stages[0].adaptive_tf,
        sort_ms_median: ms(&|s| s.sort_time),
        draw_list_ms_median: ms(&|s| s.expand_time),
        draw_ms_median: ms(&|s| s.draw_time),
        draw_timing: if stages[0].draw_timed_on_gpu {
            "gpu timestamp queries"
        } else {
            "wall clock"
        },
        wall_ms_median: ms(&|s| s.wall_time),
        draws_per_frame: draws,
        extra_draws_per_frame: extra,
        extra_draws_percent: 100.0 * extra / tets.max(1.0),
        cycle_breaks: stages.iter().map(|s| s.cycle_breaks).max().unwrap_or(0),
    }
}
