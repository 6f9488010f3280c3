//! `tetray compare`: one view rendered by several renderer / integrator /
//! sort combinations, each measured against the exact f64 CPU reference
//! (`--integrator reference` on the CPU ray caster): a labelled sheet,
//! absolute-error and FLIP-like heat maps, and a table (JSON, Markdown).

use std::path::PathBuf;

use clap::Args;
use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_project::SortKind;

use super::args::{FrameFlags, RendererArg, WalkArgs};
use super::parse::{parse_bvh_preset, parse_rgb, parse_size};
use super::scene;

#[derive(Debug, Clone, Args)]
pub struct CompareArgs {
    #[command(flatten)]
    pub frame: FrameFlags,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "256x256")]
    pub size: (u32, u32),
    /// Folder for sheet.png, abs_*.png, flip_*.png, table.json, table.md.
    #[arg(short, long, value_name = "DIR", default_value = "compare")]
    pub output: PathBuf,
    /// Background of the rendered images in the sheet (the errors are of
    /// the premultiplied images, whatever the background).
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, default_value = "0,0,0", allow_hyphen_values = true)]
    pub background: Vec3,
    /// What to compare with the reference, comma separated, each
    /// RENDERER[:INTEGRATOR][:SORT]: renderer cpu, gpu, project or
    /// shear-warp (uniform grids; `shear-warp:riemann` post-classifies); the
    /// integrator defaults to --integrator; the sort (project only)
    /// centroid, mpvo or mpvonc (default mpvonc).
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        value_parser = tetray_compare::parse_spec,
        default_value = "gpu,project:centroid,project:mpvo,project:mpvonc"
    )]
    pub methods: Vec<tetray_compare::Spec>,
    /// Timed frames per method; the table has the median. GPU renderers
    /// draw one untimed warm-up frame first.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// The projection draws each cell once instead of once per knot
    /// interval (see `render --no-adaptive-tf`).
    #[arg(long)]
    pub no_adaptive_tf: bool,
    /// Boundary BVH build preset (see `render --bvh-preset`).
    #[arg(long, value_name = "PRESET", default_value = "very-slow", value_parser = parse_bvh_preset)]
    pub bvh_preset: BuildPreset,
    /// Worker threads of the CPU ray caster (default: all cores).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    #[cfg(feature = "mpi")]
    #[command(flatten)]
    pub distributed: super::args::DistributedArgs,
}

impl CompareArgs {
    /// The walk of every combination: the CPU ray caster's options (the
    /// reference's), no early termination, so every method integrates every
    /// ray to its end.
    pub fn walk(&self) -> WalkArgs {
        WalkArgs {
            renderer: RendererArg::Cpu,
            early_termination: 1.0,
            max_steps: None,
            threads: self.threads,
            bvh_preset: Some(self.bvh_preset),
            sort: SortKind::Mpvonc,
            no_adaptive_tf: self.no_adaptive_tf,
        }
    }
}

pub fn run(args: &CompareArgs) -> anyhow::Result<()> {
    scene::configure_threads(args.threads)?;
    let log = |line: String| println!("{line}");
    let walk = args.walk();
    let frame = scene::FrameArgs {
        flags: &args.frame,
        walk: &walk,
        size: args.size,
    };
    let mut options = frame.options(scene::read_tf(&args.frame.integrator)?);
    // Shear-warp needs the regular grid of image data besides the
    // tetrahedra the others walk.
    if args
        .methods
        .iter()
        .any(|m| m.renderer == tetray_engine::RendererChoice::ShearWarp)
    {
        options.representation = tetray_engine::Representation::Both;
    }
    let mut setup = scene::prepare_with(&args.frame.mesh, &options, &log)?;
    let run = tetray_compare::RunOptions {
        size: args.size,
        frames: args.frames,
        adaptive_tf: !args.no_adaptive_tf,
    };
    let report = tetray_compare::run(&mut setup, &args.methods, run, &log)?;
    let written = report.write(&args.output, args.background)?;
    print!("{}", report.markdown());
    println!(
        "wrote {} files to {}",
        written.len(),
        std::path::absolute(&args.output)
            .unwrap_or_else(|_| args.output.clone())
            .display()
    );
    Ok(())
}
