//! `tetray animate`: frames over a file's time steps, over an orbit of the
//! camera, or both, written as a folder of PNG frames, an animated GIF, or
//! an MP4 (through `ffmpeg`). Every frame is the image `tetray render`
//! makes of that step from that view: the same renderers and integrators,
//! and one transfer-function range for all the frames (the field's range
//! over every step rendered, unless `--clim` fixes it), so a colour means
//! the same value in every frame.

use std::path::PathBuf;

use anyhow::{Context, bail};
use clap::Args;
use glam::Vec3;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::args::{FrameFlags, WalkArgs};
use super::parse::{parse_finite, parse_rgb, parse_size};
use super::scene;
use tetray_core::Movie;
use tetray_engine::{Engine, StepCost, TimeSteps};

#[derive(Debug, Clone, Args)]
pub struct AnimateArgs {
    #[command(flatten)]
    pub frame: FrameFlags,
    #[command(flatten)]
    pub walk: WalkArgs,
    /// Frame size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "512x512")]
    pub size: (u32, u32),
    /// Output: .gif (animated), .mp4 (through ffmpeg on PATH), or a folder
    /// of PNG frames frame_0000.png ... (a path ending in / or an existing
    /// folder).
    #[arg(short, long, value_name = "PATH")]
    pub output: PathBuf,
    /// Background colour r,g,b (or one grey value) behind the volume.
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, default_value = "0,0,0", allow_hyphen_values = true)]
    pub background: Vec3,
    /// Time steps to animate, counted from 0: all, A:B (both included) or
    /// a list 0,2,5. Default: all the steps of a file that has several.
    #[arg(long, value_name = "STEPS")]
    pub times: Option<String>,
    /// Degrees the camera turns about its view-up over the whole
    /// animation (360: one orbit), from the view the camera flags give.
    #[arg(long, value_name = "DEGREES", value_parser = parse_finite, allow_hyphen_values = true)]
    pub orbit: Option<f32>,
    /// Frames of an orbit of one time step (default 36); with time steps
    /// there is one frame per step.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// Frames per second of the GIF or MP4.
    #[arg(long, value_name = "N", default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub fps: u32,
}

pub fn run(args: &AnimateArgs) -> anyhow::Result<()> {
    let mesh = &args.frame.mesh;
    if mesh.time_step.is_some() || mesh.time.is_some() {
        bail!("animate takes its time steps from --times, not --time-step or --time");
    }
    scene::configure_threads(args.walk.threads)?;
    let mut series = mesh
        .mesh
        .as_ref()
        .map(|path| TimeSteps::new(path, load_options(args)));
    let (steps, times) = steps(args, series.as_ref())?;
    let count = if steps.is_empty() {
        if args.orbit.is_none() {
            bail!(
                "nothing to animate: {} has no time steps to go through; give --orbit DEGREES",
                mesh.mesh
                    .as_deref()
                    .map_or("the embedded dataset".into(), |p| p.display().to_string())
            );
        }
        args.frames.unwrap_or(36) as usize
    } else {
        steps.len()
    };
    // The output first: a path that cannot be written fails before the
    // steps are read.
    let mut movie = Movie::create(&args.output, args.size, args.fps, args.background)?;
    let mut flags = args.frame.clone();
    if let (None, Some(series)) = (&flags.integrator.clim, &series)
        && !steps.is_empty()
        && let Some(range) = series.range(&steps, flags.integrator.scalar.as_deref())?
    {
        println!(
            "colour range [{}, {}]: the field over the {} steps rendered",
            range.0,
            range.1,
            steps.len()
        );
        flags.integrator.clim = Some(range);
    }
    let frame = scene::FrameArgs {
        flags: &flags,
        walk: &args.walk,
        size: args.size,
    };
    let options = frame.options(scene::read_tf(&flags.integrator)?);
    let log = tetray_engine::Log {
        info: &say,
        warn: &scene::warn,
    };
    let quiet = tetray_engine::Log {
        info: &quiet_line,
        warn: &scene::warn,
    };
    let mut setup = match (&mut series, steps.first()) {
        (Some(series), Some(&first)) => series.prepare(Some(first), &options, log)?,
        _ => scene::prepare_with(mesh, &options, &say)?,
    };
    if steps.len() < 2 {
        // Nothing more is read: the load's freed blocks go back. (Over
        // time steps they are kept for the next step's read, which would
        // otherwise fault every page of them in again.)
        super::ALLOCATOR.release();
    }
    let mut engine = Engine::new(args.walk.renderer, &setup, &say)?;
    let mut cost = StepCost {
        load: setup.load_time,
        scene: setup.scene_time,
        kept: false,
        topology_kept: false,
    };

    let bar = ProgressBar::with_draw_target(Some(count as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("animating [{bar:40}] {pos}/{len} frames, {eta} left")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    for index in 0..count {
        let step = steps.get(index).copied();
        let loaded = index == 0 || step != steps.get(index - 1).copied();
        if let (true, false, Some(series), Some(step)) = (loaded, index == 0, &mut series, step) {
            // The steps share one view: the camera stays, and a step whose
            // mesh is the one held only brings its fields.
            cost = series.advance(&mut setup, step, &options, quiet)?;
            if cost.kept {
                engine.take_fields(&setup, &quiet_line)?;
            } else {
                engine = Engine::new(args.walk.renderer, &setup, &quiet_line)?;
            }
        }
        let mut camera = setup.camera;
        if let Some(orbit) = args.orbit {
            camera
                .azimuth(orbit * index as f32 / count as f32)
                .and_then(|()| camera.orthogonalize_view_up())
                .context("orbiting the camera")?;
        }
        let frame = engine.render(&setup, &camera, &args.walk, args.size, None)?;
        super::render::warn_about(&frame.stats.counters);
        if let (true, Some(step)) = (loaded, step) {
            // What each step costs: its file, its scene (kept from the step
            // before when the cells and points are the same), its frame.
            let scene = match (cost.kept, cost.topology_kept) {
                (true, _) => "scene kept",
                (false, true) => "scene (topology kept)",
                (false, false) => "scene",
            };
            bar.suspend(|| {
                println!(
                    "step {step}: load {:.3} s, {scene} {:.3} s, integrator {:.3} s, frame {:.3} s",
                    cost.load.as_secs_f64(),
                    cost.scene.as_secs_f64(),
                    setup.integrator_time.as_secs_f64(),
                    frame.stats.elapsed.as_secs_f64()
                );
            });
        }
        movie.add(&frame.image)?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    movie.finish()?;
    let what = match (&times, args.orbit) {
        (Some(t), Some(o)) => format!("{} time steps ({t}) turning {o} degrees", steps.len()),
        (Some(t), None) => format!("{} time steps ({t})", steps.len()),
        (None, o) => format!("an orbit of {} degrees", o.unwrap_or(0.0)),
    };
    let shown = std::path::absolute(&args.output).unwrap_or_else(|_| args.output.clone());
    println!("wrote {count} frames of {what} to {}", shown.display());
    Ok(())
}

/// The steps to render and a description of their times; none for a file
/// with one step (or none) when `--times` is not given.
fn steps(
    args: &AnimateArgs,
    series: Option<&TimeSteps>,
) -> anyhow::Result<(Vec<usize>, Option<String>)> {
    let Some(series) = series else {
        if args.times.is_some() {
            bail!("--times needs a file with time steps");
        }
        return Ok((Vec::new(), None));
    };
    let times = series.times()?;
    let steps: Vec<usize> = match args.times.as_deref() {
        None if times.len() > 1 => (0..times.len()).collect(),
        None => return Ok((Vec::new(), None)),
        Some(text) => parse_steps(text, times.len())?,
    };
    let at = |s: usize| times.get(s).copied().unwrap_or(f64::NAN);
    let described = match (steps.first(), steps.last()) {
        (Some(&a), Some(&b)) => format!("times {} to {}", at(a), at(b)),
        _ => String::new(),
    };
    Ok((steps, Some(described)))
}

/// `all`, `A:B` or `a,b,c` over `count` steps.
fn parse_steps(text: &str, count: usize) -> anyhow::Result<Vec<usize>> {
    if count == 0 {
        bail!("--times {text}: the file stores no time steps");
    }
    let number = |s: &str| -> anyhow::Result<usize> {
        let n: usize = s
            .trim()
            .parse()
            .with_context(|| format!("--times {text}: {s:?} is not a step number"))?;
        if n >= count {
            bail!(
                "--times {text}: step {n} is out of range: the file stores {count} time steps (0..={})",
                count - 1
            );
        }
        Ok(n)
    };
    let steps = if text.trim() == "all" {
        (0..count).collect()
    } else if let Some((a, b)) = text.split_once(':') {
        let (a, b) = (number(a)?, number(b)?);
        if a > b {
            bail!("--times {text}: the first step is after the last");
        }
        (a..=b).collect()
    } else {
        text.split(',')
            .map(number)
            .collect::<anyhow::Result<Vec<_>>>()?
    };
    Ok(steps)
}

fn load_options(args: &AnimateArgs) -> tetray_io::LoadOptions {
    let mesh = &args.frame.mesh;
    tetray_io::LoadOptions {
        plot3d_q: mesh.q.clone(),
        time_step: None,
        time: None,
        block: mesh.block.clone(),
        linearize: mesh.linearize.into(),
    }
}

fn say(line: String) {
    println!("{line}");
}

fn quiet_line(_: String) {}
