//! `tetray render`: one image of a mesh.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::bail;
use glam::Vec3;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use tetray_core::{Image, WalkCounters};

use super::args::RenderArgs;
use super::scene;
use tetray_engine::{Engine, FrameStats};

/// Renders slower than this get a progress bar (on a terminal).
const PROGRESS_AFTER: Duration = Duration::from_millis(500);

/// The image formats, by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ImageFormat {
    Png,
    Exr,
    /// NumPy's `.npy`: the EXR's float RGBA as a (height, width, 4) array.
    Npy,
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let output = &args.output.output;
    let format = image_format(output)?;
    scene::configure_threads(args.walk.threads)?;
    let size = args.output.size;
    let frame = scene::FrameArgs {
        flags: &args.frame,
        walk: &args.walk,
        size,
    };
    let setup = scene::prepare(frame, &|line| println!("{line}"))?;
    let engine = Engine::new(args.walk.renderer, &setup, &|line| println!("{line}"))?;

    let bar = ProgressBar::with_draw_target(Some(u64::from(size.1)), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("rendering [{bar:40}] {pos}/{len} rows, {eta} left")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    let start = Instant::now();
    let progress = |rows_done: usize, _rows: usize| {
        if bar.is_hidden() && start.elapsed() > PROGRESS_AFTER {
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.set_position(rows_done as u64);
    };
    let frame = engine.render(&setup, &setup.camera, &args.walk, size, Some(&progress))?;
    bar.finish_and_clear();

    println!(
        "{} on {}",
        describe_stats(&frame.stats, size),
        engine.adapter()
    );
    if let Some(project) = &frame.stats.project {
        println!("{}", describe_projection(project, args.walk.sort.name()));
    }
    warn_about(&frame.stats.counters);
    write_image(&frame.image, output, format, args.output.background)?;
    let shown = std::path::absolute(output).unwrap_or_else(|_| output.clone());
    println!("wrote {}", shown.display());
    Ok(())
}

/// One line of frame statistics.
pub fn describe_stats(stats: &FrameStats, (width, height): (u32, u32)) -> String {
    let seconds = stats.elapsed.as_secs_f64();
    format!(
        "rendered {width}x{height} in {seconds:.3} s: {} rays, {} hit the mesh, {} segments, \
         {} tetrahedra visited, {} boundary entries{} ({:.2} M segments/s)",
        stats.counters.rays,
        stats.counters.rays_hit,
        stats.counters.segments,
        stats.counters.steps,
        stats.counters.entries,
        if stats.entry_lists {
            " from per-pixel lists"
        } else {
            ""
        },
        stats.counters.segments as f64 / seconds.max(1e-12) / 1e6
    ) + &if stats.counters.overlap_segments > 0 {
        format!(
            "; {} segments of left-out cells composited in their holes",
            stats.counters.overlap_segments
        )
    } else {
        String::new()
    }
}

/// One line of the projection's stages.
pub fn describe_projection(stats: &tetray_project::ProjectStats, sort: &str) -> String {
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    format!(
        "projection: {sort} sort {:.1} ms, draw list {:.1} ms, render pass {:.1} ms ({}); \
         {} draws for {} tetrahedra ({} extra for adaptive sampling, +{:.1}%), {} cycle breaks",
        ms(stats.sort_time),
        ms(stats.expand_time),
        ms(stats.draw_time),
        if stats.draw_timed_on_gpu {
            "gpu timestamps"
        } else {
            "wall clock"
        },
        stats.draws,
        stats.tets,
        stats.extra_draws,
        100.0 * stats.extra_draws as f64 / stats.tets.max(1) as f64,
        stats.cycle_breaks
    )
}

/// Warnings for rays the walk could not finish.
pub fn warn_about(counters: &WalkCounters) {
    if counters.steps_bound_hits > 0 {
        eprintln!(
            "warning: {} ray{} hit the step bound and were cut short (raise --max-steps)",
            counters.steps_bound_hits,
            scene::plural(counters.steps_bound_hits as usize)
        );
    }
    if counters.walk_failures > 0 {
        eprintln!(
            "warning: {} ray{} stopped in a tetrahedron with no exit face (a degenerate cell)",
            counters.walk_failures,
            scene::plural(counters.walk_failures as usize)
        );
    }
    if counters.overlap_overflows > 0 {
        eprintln!(
            "warning: {} ray{} crossed more than {} tetrahedra of left-out cells; those beyond \
             were not composited",
            counters.overlap_overflows,
            scene::plural(counters.overlap_overflows as usize),
            tetray_scene::MAX_OVERLAP_CROSSINGS
        );
    }
}

/// The output format from the file name, checked before rendering.
pub(super) fn image_format(path: &Path) -> anyhow::Result<ImageFormat> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("png") => ImageFormat::Png,
        Some("exr") => ImageFormat::Exr,
        Some("npy") => ImageFormat::Npy,
        _ => bail!(
            "-o {}: the output must end in .png, .exr or .npy",
            path.display()
        ),
    };
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    if let Some(dir) = parent.filter(|dir| !dir.is_dir()) {
        bail!(
            "-o {}: the folder {} does not exist",
            path.display(),
            dir.display()
        );
    }
    Ok(format)
}

pub(super) fn write_image(
    image: &Image,
    path: &Path,
    format: ImageFormat,
    background: Vec3,
) -> anyhow::Result<()> {
    match format {
        ImageFormat::Exr => image.write_exr(path)?,
        ImageFormat::Npy => image.write_npy(path)?,
        ImageFormat::Png => image.write_png(path, background)?,
    }
    Ok(())
}
