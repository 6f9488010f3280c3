//! `tetray export-html`: the scene as a web page that renders it on the
//! visitor's GPU through WebGPU (see `tetray_web`).

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_web::{Layout, Limits, PageOptions};

use super::args::{FrameFlags, WalkArgs};
use super::parse::{parse_bvh_preset, parse_rgb, parse_size};
use super::scene;

/// `tetray export-html`.
#[derive(Debug, Clone, Args)]
pub struct ExportHtmlArgs {
    #[command(flatten)]
    pub frame: FrameFlags,
    /// The page: one self-contained .html file, or with --folder a folder
    /// holding index.html and scene.js (the buffers).
    #[arg(short, long, value_name = "PATH")]
    pub output: PathBuf,
    /// Write a folder (index.html and scene.js) instead of one file.
    #[arg(long)]
    pub folder: bool,
    /// Image size in pixels of the page's view.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "512x512")]
    pub size: (u32, u32),
    /// Background colour r,g,b (or one grey value) behind the volume.
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, default_value = "1,1,1", allow_hyphen_values = true)]
    pub background: Vec3,
    /// Stop a ray once its opacity reaches A, in (0, 1]; 1 disables.
    #[arg(long, value_name = "A", default_value_t = 1.0)]
    pub early_termination: f32,
    /// Most tetrahedra one ray may visit (default: tetrahedra + 1024).
    #[arg(long, value_name = "N")]
    pub max_steps: Option<u32>,
    /// Boundary BVH build preset (as `render`).
    #[arg(long, value_name = "PRESET", value_parser = parse_bvh_preset)]
    pub bvh_preset: Option<BuildPreset>,
    /// The page runs its benchmark on opening: FRAMES frames at each of
    /// VIEWS azimuths round the camera (default 8 views), and shows
    /// segments/s and frames/s with the adapter's name.
    #[arg(long, value_name = "FRAMES[,VIEWS]", value_parser = parse_bench)]
    pub bench: Option<(u32, u32)>,
    /// Full pre-integration tables for every colour map of the page, not
    /// only the transfer function's own (2 MB each at the default size).
    #[arg(long)]
    pub preintegrate_all: bool,
}

fn parse_bench(text: &str) -> Result<(u32, u32), String> {
    let mut parts = text.split(',');
    let number = |part: Option<&str>, default: Option<u32>| -> Result<u32, String> {
        match part {
            None => default.ok_or_else(|| "expected FRAMES[,VIEWS]".to_string()),
            Some(p) => match p.trim().parse::<u32>() {
                Ok(n) if (1..=10_000).contains(&n) => Ok(n),
                _ => Err(format!("{p:?} is not a count from 1 to 10000")),
            },
        }
    };
    let frames = number(parts.next(), None)?;
    let views = number(parts.next(), Some(8))?;
    if parts.next().is_some() {
        return Err("expected FRAMES[,VIEWS]".into());
    }
    Ok((frames, views))
}

pub fn run(args: &ExportHtmlArgs) -> anyhow::Result<()> {
    if !(args.early_termination > 0.0 && args.early_termination <= 1.0) {
        anyhow::bail!(
            "--early-termination {} is outside (0, 1] (1 disables early termination)",
            args.early_termination
        );
    }
    if args.max_steps == Some(0) {
        anyhow::bail!("--max-steps must be at least 1");
    }
    let mut walk = WalkArgs::defaults();
    walk.bvh_preset = args.bvh_preset;
    let frame = scene::FrameArgs {
        flags: &args.frame,
        walk: &walk,
        size: args.size,
    };
    let setup = scene::prepare(frame, &|line| println!("{line}"))?;
    let options = PageOptions {
        size: args.size,
        background: args.background.to_array(),
        early_termination: args.early_termination,
        max_steps: args.max_steps,
        bench: args.bench,
        preintegrate_all: args.preintegrate_all,
    };
    let bundle = tetray_web::bundle(&setup, &options)?;
    let limits = Limits::of(&bundle.manifest);
    if !limits.guaranteed() {
        scene::warn(format!(
            "the page needs a WebGPU adapter that binds {} bytes per storage buffer; WebGPU \
             guarantees {} (most desktop GPUs offer more); other adapters show the numbers \
             and no image",
            limits.binding_bytes,
            tetray_web::GUARANTEED_BINDING
        ));
    }
    let layout = if args.folder {
        Layout::Folder
    } else {
        Layout::SingleFile
    };
    let files = tetray_web::page(&bundle, layout)?;
    let index = write(&args.output, &files, layout)?;
    let raw: usize = bundle.buffers.iter().map(|b| b.bytes).sum();
    let stored: usize = bundle.buffers.iter().map(|b| b.deflated.len()).sum();
    println!(
        "page: {} buffers, {:.2} MB as uploaded, {:.2} MB deflated; {:.2} MB in all; {} \
         integrators over {} colour maps",
        bundle.buffers.len(),
        raw as f64 / 1e6,
        stored as f64 / 1e6,
        files.bytes() as f64 / 1e6,
        bundle.manifest.methods.len(),
        bundle.manifest.colormaps.len(),
    );
    let shown = std::path::absolute(&index).unwrap_or(index);
    println!("wrote {}", shown.display());
    Ok(())
}

/// Writes the page; returns the HTML file's path.
fn write(output: &Path, files: &tetray_web::PageFiles, layout: Layout) -> anyhow::Result<PathBuf> {
    match layout {
        Layout::SingleFile => {
            std::fs::write(output, &files.html)
                .with_context(|| format!("{}: cannot write the page", output.display()))?;
            Ok(output.to_path_buf())
        }
        Layout::Folder => {
            std::fs::create_dir_all(output)
                .with_context(|| format!("{}: cannot make the folder", output.display()))?;
            let index = output.join("index.html");
            std::fs::write(&index, &files.html)
                .with_context(|| format!("{}: cannot write the page", index.display()))?;
            if let Some(js) = &files.scene_js {
                let path = output.join("scene.js");
                std::fs::write(&path, js)
                    .with_context(|| format!("{}: cannot write the buffers", path.display()))?;
            }
            Ok(index)
        }
    }
}
