//! `tetray view`: the interactive viewer (crates/viewer) on a mesh or the
//! embedded dataset.

use std::time::Duration;

use clap::Args;
use tetray_viewer::{TimeSeries, ViewerOptions};

use super::args::{IntegratorArgs, MeshArgs};
use super::parse::parse_positive;
use super::scene::{prepare_with, read_tf};

/// `tetray view`.
#[derive(Debug, Clone, Args)]
pub struct ViewArgs {
    #[command(flatten)]
    pub mesh: MeshArgs,
    #[command(flatten)]
    pub integrator: IntegratorArgs,
    /// Rendered pixels per display pixel, per side, in (0, 2]. Default: 1
    /// on a GPU, 0.25 on a CPU implementation such as lavapipe.
    #[arg(long, value_name = "S", value_parser = parse_image_scale, allow_hyphen_values = true)]
    pub image_scale: Option<f32>,
    /// Ray casting one display frame may take, in milliseconds: a slower
    /// frame is shown as a preview while the view changes, then refined a
    /// few rows per display frame.
    #[arg(long, value_name = "MS", default_value_t = 40, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub budget_ms: u32,
    /// Stop a ray once its opacity reaches A, in (0, 1]; 1 disables.
    #[arg(long, value_name = "A", default_value_t = 1.0, value_parser = parse_alpha, allow_hyphen_values = true)]
    pub early_termination: f32,
}

pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    // Every renderer is offered: image data keeps its regular grid for
    // shear-warp beside the tetrahedra the others walk.
    let options = tetray_engine::FrameOptions {
        integrator: args.integrator.choice(read_tf(&args.integrator)?),
        size: (1280, 800),
        representation: tetray_engine::Representation::Both,
        ..tetray_engine::FrameOptions::default()
    };
    let (setup, series) = match time_series(args, options.clone())? {
        Some((setup, series)) => (setup, Some(series)),
        None => (
            prepare_with(&args.mesh, &options, &|line| println!("{line}"))?,
            None,
        ),
    };
    if setup.image().is_some() {
        println!("image data: the shear-warp renderer is available in the Renderer menu");
    }
    let options = ViewerOptions {
        image_scale: args.image_scale,
        budget: Duration::from_millis(u64::from(args.budget_ms)),
        early_termination: args.early_termination,
    };
    tetray_viewer::run(setup, options, series)
}

/// For a file with several time steps: the setup of the step asked for
/// (`--time-step`, `--time`, else the first) and the steps for the
/// viewer's time slider, with the colour range over all the steps (unless
/// `--clim` fixes it), as `tetray animate` makes it.
fn time_series(
    args: &ViewArgs,
    mut options: tetray_engine::FrameOptions,
) -> anyhow::Result<Option<(tetray_engine::Setup, TimeSeries)>> {
    let tetray_engine::Source::File {
        path,
        options: load,
    } = args.mesh.source()?
    else {
        return Ok(None);
    };
    let mut steps = tetray_engine::TimeSteps::new(path, load.clone());
    let times = steps.times()?;
    if times.len() < 2 {
        return Ok(None);
    }
    let step = match (load.time_step, load.time) {
        (Some(step), _) => step,
        (None, Some(time)) => tetray_io::time::choose_step(&times, None, Some(time))?.unwrap_or(0),
        (None, None) => 0,
    };
    let all: Vec<usize> = (0..times.len()).collect();
    if options.integrator.range.is_none()
        && let Some(range) = steps.range(&all, options.integrator.scalar.as_deref())?
    {
        println!(
            "colour range [{}, {}]: the field over the {} time steps",
            range.0,
            range.1,
            times.len()
        );
        options.integrator.range = Some(range);
    }
    let log = tetray_engine::Log {
        info: &|line| println!("{line}"),
        warn: &super::scene::warn,
    };
    let setup = steps.prepare(Some(step), &options, log)?;
    Ok(Some((setup, TimeSeries::new(steps, options, times, step))))
}

fn parse_image_scale(text: &str) -> Result<f32, String> {
    let v = parse_positive(text)?;
    if v <= 2.0 {
        Ok(v)
    } else {
        Err(format!("{v} is outside (0, 2]"))
    }
}

fn parse_alpha(text: &str) -> Result<f32, String> {
    let v = parse_positive(text)?;
    if v <= 1.0 {
        Ok(v)
    } else {
        Err(format!(
            "{v} is outside (0, 1] (1 disables early termination)"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scales_outside_their_ranges_are_refused() {
        assert_eq!(parse_image_scale("0.5"), Ok(0.5));
        assert!(parse_image_scale("3").is_err());
        assert!(parse_image_scale("0").is_err());
        assert!(parse_alpha("1.5").is_err());
        assert_eq!(parse_alpha("0.95"), Ok(0.95));
    }
}
