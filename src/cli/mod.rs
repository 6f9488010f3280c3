//! The command line: argument definitions and dispatch.
//!
//! The arguments' doc comments are their `--help` text, written for a
//! terminal (`<name>`, `[:SORT]`), not as rustdoc markup.
#![allow(rustdoc::invalid_html_tags, rustdoc::broken_intra_doc_links)]

mod animate;
mod args;
mod bench;
mod compare;
mod datasets;
#[cfg(feature = "mpi")]
mod distributed;
mod export_html;
mod generate;
mod generate_grid;
mod info;
mod parse;
mod psi;
mod render;
mod scene;
mod segment;
mod study;
mod view;

use clap::{Parser, Subcommand};

use args::RenderArgs;

/// Large freed blocks are kept for the next large allocation (see
/// `tetray_memory`): loading a mesh faults its memory in about once, not once
/// per stage. The setup returns them once the scene is built.
#[global_allocator]
pub(crate) static ALLOCATOR: tetray_memory::Recycling = tetray_memory::Recycling::new();

/// Volume rendering of unstructured tetrahedral meshes by walking each ray
/// cell to cell (Moreland 2004). With no command, renders the embedded
/// Blunt Fin dataset to tetray.png.
#[derive(Debug, Parser)]
#[command(name = "tetray", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a mesh to an image (.png or .exr).
    Render(Box<RenderArgs>),
    /// Print counts, bounds, scalar ranges and validation findings of a mesh.
    Info(info::InfoArgs),
    /// Render frames over a file's time steps, an orbit of the camera, or
    /// both, to a GIF, an MP4 (ffmpeg) or a folder of PNG frames.
    Animate(Box<animate::AnimateArgs>),
    /// Integrate one ray segment with any method and print JSON.
    Segment(segment::SegmentArgs),
    /// Print the Psi table's value and Psi in f64 at (gamma_b, gamma_f), as JSON.
    Psi(psi::PsiArgs),
    /// Render frames orbiting the camera and print timings as JSON.
    Bench(Box<bench::BenchArgs>),
    /// Open the interactive viewer: orbit, edit the transfer function,
    /// switch and compare methods (GPU ray caster, progressive).
    View(Box<view::ViewArgs>),
    /// Run a study of the methods (dissertation chapters 5-6): SVG plots,
    /// CSV and JSON in a folder.
    Study(Box<study::StudyArgs>),
    /// Render one view with several renderers, integrators and sorts and
    /// measure each against the f64 CPU reference: sheet, error maps, table.
    Compare(Box<compare::CompareArgs>),
    /// Write a large test mesh (a refined PLOT3D dataset or a procedural
    /// nonconvex solid) at a requested tetrahedron count; print JSON.
    Generate(generate::GenerateArgs),
    /// Write a web page that renders the mesh in the browser on the
    /// visitor's GPU (WebGPU), with the ray caster's own kernel and buffers.
    ExportHtml(Box<export_html::ExportHtmlArgs>),
}

/// Runs the parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    // Distributed over MPI ranks when asked, or when mpirun started more
    // than one.
    #[cfg(feature = "mpi")]
    match &cli.command {
        Some(Command::Render(args)) if args.distributed.wanted() => {
            return distributed::render(args);
        }
        Some(Command::Bench(args)) if args.distributed.wanted() => return distributed::bench(args),
        Some(Command::Compare(args)) if args.distributed.wanted() => {
            return distributed::compare(args);
        }
        _ => {}
    }
    match cli.command {
        None => render::run(&RenderArgs::defaults()),
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Info(args)) => info::run(&args),
        Some(Command::Animate(args)) => animate::run(&args),
        Some(Command::Segment(args)) => segment::run(&args),
        Some(Command::Psi(args)) => psi::run(&args),
        Some(Command::Bench(args)) => bench::run(&args),
        Some(Command::View(args)) => view::run(&args),
        Some(Command::Study(args)) => study::run(&args),
        Some(Command::Compare(args)) => compare::run(&args),
        Some(Command::Generate(args)) => generate::run(&args),
        Some(Command::ExportHtml(args)) => export_html::run(&args),
    }
}

/// A command-line error as one line: clap's message up to its usage notes,
/// with the lines it lists (missing arguments) joined.
pub fn one_line(error: &clap::Error) -> String {
    let text = error.to_string();
    let message = text.split("\n\n").next().unwrap_or(&text);
    let line = message.split_whitespace().collect::<Vec<_>>().join(" ");
    if line.starts_with("error:") {
        line
    } else {
        format!("error: {line}")
    }
}
