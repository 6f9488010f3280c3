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

use super::args::{FrameFlags, WalkArgs, parse_finite, parse_rgb, parse_size};
use super::scene;
use tetray_core::Movie;
use tetray_engine::Engine;

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
    let (steps, times) = steps(args)?;
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
    if flags.integrator.clim.is_none()
        && !steps.is_empty()
        && let Some(range) = range_over(args, &steps)?
    {
        println!(
            "colour range [{}, {}]: the field over the {} steps rendered",
            range.0,
            range.1,
            steps.len()
        );
        flags.integrator.clim = Some(range);
    }

    let bar = ProgressBar::with_draw_target(Some(count as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("animating [{bar:40}] {pos}/{len} frames, {eta} left")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    let mut current: Option<(Option<usize>, tetray_engine::Setup, Engine)> = None;
    for index in 0..count {
        let step = steps.get(index).copied();
        let loaded = current.as_ref().is_none_or(|(s, _, _)| *s != step);
        // What making this frame's setup cost: load, scene, whether the
        // previous step's scene was kept.
        let mut cost = (0.0, 0.0, false);
        if loaded {
            flags.mesh.time_step = step;
            let reused = match (&mut current, step, &flags.mesh.mesh) {
                (Some((at, setup, engine)), Some(k), Some(path)) => {
                    let start = std::time::Instant::now();
                    let next = tetray_io::load(path, &load_options(args, Some(k)))?;
                    cost.0 = start.elapsed().as_secs_f64();
                    let start = std::time::Instant::now();
                    let log = tetray_engine::Log {
                        info: &quiet,
                        warn: &scene::warn,
                    };
                    let kept = setup.next_step(&next, log)?;
                    if kept {
                        *engine = Engine::new(args.walk.renderer, setup, &quiet)?;
                        *at = step;
                        cost.1 = start.elapsed().as_secs_f64();
                        cost.2 = true;
                    }
                    kept
                }
                _ => false,
            };
            if !reused {
                let frame = scene::FrameArgs {
                    flags: &flags,
                    walk: &args.walk,
                    size: args.size,
                };
                // The first step's setup is described; the others repeat it.
                let log: &dyn Fn(String) = if index == 0 { &say } else { &quiet };
                let setup = scene::prepare(frame, log)?;
                let engine = Engine::new(args.walk.renderer, &setup, log)?;
                cost.0 = setup.load_time.as_secs_f64();
                cost.1 = setup.scene_time.as_secs_f64();
                current = Some((step, setup, engine));
            }
        }
        let Some((_, setup, engine)) = &current else {
            unreachable!("made above");
        };
        let mut camera = setup.camera;
        if let Some(orbit) = args.orbit {
            camera
                .azimuth(orbit * index as f32 / count as f32)
                .and_then(|()| camera.orthogonalize_view_up())
                .context("orbiting the camera")?;
        }
        let frame = engine.render(setup, &camera, &args.walk, args.size, None)?;
        super::render::warn_about(&frame.stats.counters);
        if let (true, Some(step)) = (loaded, step) {
            // What each step costs: its file, its scene (kept from the step
            // before when the cells and points are the same), its frame.
            let scene = if cost.2 { "scene kept" } else { "scene" };
            bar.suspend(|| {
                println!(
                    "step {step}: load {:.3} s, {scene} {:.3} s, integrator {:.3} s, frame {:.3} s",
                    cost.0,
                    cost.1,
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
fn steps(args: &AnimateArgs) -> anyhow::Result<(Vec<usize>, Option<String>)> {
    let Some(path) = &args.frame.mesh.mesh else {
        if args.times.is_some() {
            bail!("--times needs a file with time steps");
        }
        return Ok((Vec::new(), None));
    };
    let first = tetray_io::load(path, &load_options(args, None))?;
    let times = first.report.times.clone();
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

fn load_options(args: &AnimateArgs, step: Option<usize>) -> tetray_io::LoadOptions {
    let mesh = &args.frame.mesh;
    tetray_io::LoadOptions {
        plot3d_q: mesh.q.clone(),
        time_step: step,
        time: None,
        block: mesh.block.clone(),
        linearize: mesh.linearize.into(),
    }
}

fn say(line: String) {
    println!("{line}");
}

fn quiet(_: String) {}

/// The rendered field's range over `steps` (ParaView's "rescale over all
/// time steps"): the field `--scalar` names, else the one the first step
/// renders by default. `None` for a field constant over every step (each
/// frame then renders it as `render` does, a uniform volume).
fn range_over(args: &AnimateArgs, steps: &[usize]) -> anyhow::Result<Option<(f32, f32)>> {
    let Some(path) = &args.frame.mesh.mesh else {
        bail!("no file");
    };
    let mut name = args.frame.integrator.scalar.clone();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for &step in steps {
        let loaded = tetray_io::load(path, &load_options(args, Some(step)))?;
        let fields = &loaded.mesh.fields;
        let name = name.get_or_insert_with(|| {
            tetray_mesh::default_field(&loaded.mesh).map_or(String::new(), |f| f.name.clone())
        });
        let Some(field) = fields.iter().find(|f| &f.name == name) else {
            bail!("{}: step {step} has no field {name:?}", path.display());
        };
        let (a, b) = tetray_mesh::value_range(&field.values);
        lo = lo.min(a);
        hi = hi.max(b);
    }
    Ok((lo < hi).then_some((lo, hi)))
}
