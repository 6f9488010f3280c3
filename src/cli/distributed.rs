//! `render`, `bench` and `compare` distributed over MPI ranks (feature
//! `mpi`): each rank loads its part of the mesh (a run of a parallel
//! file's pieces, or a spatial slab of a single file's tetrahedra), the
//! ranks agree on what the whole mesh gives the single-process render
//! (origin, bounds, field and range, unit distance, mean chord), each casts
//! every pixel's ray through its part into per-interval fragments, and the
//! fragments are composited on the ranks owning their pixels
//! (`tetray_distributed`). Rank 0 writes the image and the report.
//!
//! Distributed when started by `mpirun` with more than one rank, or with
//! `--distributed` (then also on one rank); otherwise the commands run in
//! one process as without the feature, and MPI is not initialised.

use std::time::Instant;

use anyhow::{Context, bail};
use serde::Serialize;
use tetray_core::{Camera, Image};
use tetray_distributed::mpi::topology::SimpleCommunicator;
use tetray_distributed::mpi::traits::*;
use tetray_distributed::{DistributedFrame, FrameReport, Part, prepare_part, render_setup};
use tetray_raycast::RenderOptions;

use super::args::{RendererArg, WalkArgs};
use super::scene;

/// Runs `work` on the world communicator; an error on any rank is printed
/// with the rank and aborts every rank (a rank left waiting in a
/// collective would hang).
fn with_world(work: impl FnOnce(&SimpleCommunicator) -> anyhow::Result<()>) -> anyhow::Result<()> {
    let Some(universe) = tetray_distributed::mpi::initialize() else {
        bail!("MPI was already initialised");
    };
    let world = universe.world();
    if let Err(e) = work(&world) {
        let message = format!("{e:#}");
        eprintln!(
            "error: rank {}: {}",
            world.rank(),
            message.split_whitespace().collect::<Vec<_>>().join(" ")
        );
        world.abort(1);
    }
    Ok(())
}

/// This rank's part through `tetray_distributed::prepare_part` (the
/// engine's setup of the part, from what the ranks agree on). Progress
/// lines go to stdout, or to stderr with `quiet` (the bench's stdout holds
/// only its JSON); rank 0 alone writes them.
fn prepare<C: Communicator>(
    comm: &C,
    frame: scene::FrameArgs<'_>,
    quiet: bool,
) -> anyhow::Result<Part> {
    let rank0 = comm.rank() == 0;
    let log = |line: String| match (rank0, quiet) {
        (false, _) => {}
        (true, false) => println!("{line}"),
        (true, true) => eprintln!("{line}"),
    };
    if !matches!(frame.walk.renderer, RendererArg::Auto | RendererArg::Cpu) {
        bail!("a distributed render uses the CPU ray caster: --renderer auto or cpu");
    }
    if frame.walk.early_termination != 1.0 {
        bail!(
            "a distributed render does not terminate rays early (a rank cannot know the light \
             in front of its fragments): leave --early-termination at 1"
        );
    }
    let options = frame.options(scene::read_tf(&frame.flags.integrator)?);
    let warn = |line: String| {
        if rank0 {
            scene::warn(line);
        }
    };
    let log = tetray_engine::Log {
        info: &log,
        warn: &warn,
    };
    Ok(prepare_part(
        comm,
        frame.flags.mesh.source()?,
        &options,
        log,
    )?)
}

fn render_options(walk: &WalkArgs, (width, height): (u32, u32)) -> RenderOptions {
    RenderOptions {
        width,
        height,
        early_termination: 1.0,
        max_steps_per_ray: walk.max_steps,
        threads: None,
    }
}

fn frame<C: Communicator>(
    comm: &C,
    part: &Part,
    camera: &Camera,
    opts: &RenderOptions,
    tile: u32,
) -> anyhow::Result<Option<DistributedFrame>> {
    Ok(render_setup(comm, &part.setup, camera, opts, tile)?)
}

/// `tetray render`, distributed.
pub fn render(args: &super::args::RenderArgs) -> anyhow::Result<()> {
    let output = &args.output.output;
    let format = super::render::image_format(output)?;
    scene::configure_threads(args.walk.threads)?;
    with_world(|world| {
        let input = scene::FrameArgs {
            flags: &args.frame,
            walk: &args.walk,
            size: args.output.size,
        };
        let part = prepare(world, input, false)?;
        let opts = render_options(&args.walk, args.output.size);
        let start = Instant::now();
        let Some(frame) = frame(
            world,
            &part,
            &part.setup.camera,
            &opts,
            args.distributed.tile,
        )?
        else {
            return Ok(());
        };
        let (w, h) = args.output.size;
        println!(
            "rendered {w}x{h} in {:.3} s: {} segments in all",
            start.elapsed().as_secs_f64(),
            frame.report.sum(|r| r.segments)
        );
        println!("{}", frame.report.describe());
        super::render::write_image(&frame.image, output, format, args.output.background)?;
        let shown = std::path::absolute(output).unwrap_or_else(|_| output.clone());
        println!("wrote {}", shown.display());
        Ok(())
    })
}

/// The bench's JSON: medians over the frames of the slowest rank's stage
/// times, and the per-fragment and per-byte costs the README's model of
/// larger runs uses.
#[derive(Debug, Serialize)]
struct BenchJson {
    renderer: &'static str,
    ranks: usize,
    threads_per_rank: usize,
    mesh: String,
    tets: u64,
    size: String,
    integrator: &'static str,
    field: String,
    frames: u32,
    tile: u32,
    ms_per_frame_median: f64,
    trace_ms_max_median: f64,
    trace_ms_mean_median: f64,
    fragments_per_frame: f64,
    fragments_per_pixel: f64,
    bytes_exchanged_per_frame: f64,
    bytes_gathered_per_frame: f64,
    wait_ms_median: f64,
    exchange_ms_median: f64,
    sort_ms_median: f64,
    blend_ms_median: f64,
    gather_ms_median: f64,
    /// Sort and blend time per fragment received, on the slowest rank.
    sort_ns_per_fragment: f64,
    blend_ns_per_fragment: f64,
    /// Exchange time per byte a rank sent (inverse bandwidth with latency).
    exchange_ns_per_byte: f64,
    load_s: f64,
    setup_s: f64,
}

/// `tetray bench`, distributed: timed frames as JSON on rank 0.
pub fn bench(args: &super::bench::BenchArgs) -> anyhow::Result<()> {
    scene::configure_threads(args.walk.threads)?;
    with_world(|world| {
        let input = scene::FrameArgs {
            flags: &args.frame,
            walk: &args.walk,
            size: args.size,
        };
        let part = prepare(world, input, true)?;
        let opts = render_options(&args.walk, args.size);
        let tile = args.distributed.tile;
        let mut camera = part.setup.camera;
        let orbit_step = args.orbit_step.unwrap_or(360.0 / args.frames as f32);
        frame(world, &part, &camera, &opts, tile).context("warm-up frame")?;
        let mut times = Vec::new();
        let mut reports: Vec<FrameReport> = Vec::new();
        for _ in 0..args.frames {
            world.barrier();
            let start = Instant::now();
            let out = frame(world, &part, &camera, &opts, tile)?;
            times.push(start.elapsed().as_secs_f64() * 1e3);
            reports.extend(out.map(|f| f.report));
            camera.azimuth(orbit_step).context("orbiting the camera")?;
            camera
                .orthogonalize_view_up()
                .context("orbiting the camera")?;
        }
        if world.rank() != 0 {
            return Ok(());
        }
        let med = |f: &dyn Fn(&FrameReport) -> f64| {
            tetray_engine::median(&reports.iter().map(f).collect::<Vec<_>>())
        };
        let ms = 1e3;
        let received_max = med(&|r| r.max(|x| x.fragments_received)).max(1.0);
        let sent_max = med(&|r| r.max(|x| x.bytes_exchanged)).max(1.0);
        let json = BenchJson {
            renderer: "cpu-distributed",
            ranks: world.size() as usize,
            threads_per_rank: rayon::current_num_threads(),
            mesh: part.setup.name().to_string(),
            tets: part.tets_total,
            size: format!("{}x{}", args.size.0, args.size.1),
            integrator: part.setup.method.name(),
            field: part.setup.extent.field.clone(),
            frames: args.frames,
            tile,
            ms_per_frame_median: tetray_engine::median(&times),
            trace_ms_max_median: med(&|r| r.max(|x| x.trace_s)) * ms,
            trace_ms_mean_median: med(&|r| r.mean(|x| x.trace_s)) * ms,
            fragments_per_frame: med(&|r| r.sum(|x| x.fragments_sent)),
            fragments_per_pixel: med(&|r| r.fragments_per_pixel()),
            bytes_exchanged_per_frame: med(&|r| r.sum(|x| x.bytes_exchanged)),
            bytes_gathered_per_frame: med(&|r| r.sum(|x| x.bytes_gathered)),
            wait_ms_median: med(&|r| r.max(|x| x.wait_s)) * ms,
            exchange_ms_median: med(&|r| r.max(|x| x.exchange_s)) * ms,
            sort_ms_median: med(&|r| r.max(|x| x.sort_s)) * ms,
            blend_ms_median: med(&|r| r.max(|x| x.blend_s)) * ms,
            gather_ms_median: med(&|r| r.max(|x| x.gather_s)) * ms,
            sort_ns_per_fragment: med(&|r| r.max(|x| x.sort_s)) * 1e9 / received_max,
            blend_ns_per_fragment: med(&|r| r.max(|x| x.blend_s)) * 1e9 / received_max,
            exchange_ns_per_byte: med(&|r| r.max(|x| x.exchange_s)) * 1e9 / sent_max,
            load_s: part.load_time.as_secs_f64(),
            setup_s: part.setup_time.as_secs_f64(),
        };
        println!("{}", serde_json::to_string_pretty(&json)?);
        Ok(())
    })
}

#[derive(Debug, Serialize)]
struct CompareJson {
    ranks: usize,
    mesh: String,
    size: String,
    integrator: &'static str,
    /// Largest absolute difference over premultiplied RGBA.
    max_abs_error: f32,
    mean_abs_error: f64,
    /// Pixels with a channel differing by more than 1e-5.
    pixels_over_1e5: usize,
    pixels_lit: usize,
    distributed_ms: f64,
    single_ms: f64,
}

/// `tetray compare`, distributed: the composited image against the
/// single-process CPU render of the whole mesh (rank 0 renders it too).
pub fn compare(args: &super::compare::CompareArgs) -> anyhow::Result<()> {
    scene::configure_threads(args.threads)?;
    let walk = args.walk();
    with_world(|world| {
        let input = scene::FrameArgs {
            flags: &args.frame,
            walk: &walk,
            size: args.size,
        };
        let part = prepare(world, input, false)?;
        let opts = render_options(&walk, args.size);
        let start = Instant::now();
        let out = frame(
            world,
            &part,
            &part.setup.camera,
            &opts,
            args.distributed.tile,
        )?;
        let distributed_ms = start.elapsed().as_secs_f64() * 1e3;
        let Some(out) = out else { return Ok(()) };
        println!("{}", out.report.describe());
        let frame_args = scene::FrameArgs {
            flags: &args.frame,
            walk: &walk,
            size: args.size,
        };
        let setup = scene::prepare(frame_args, &|line| println!("single process: {line}"))?;
        let start = Instant::now();
        let single =
            tetray_engine::Engine::Cpu.render(&setup, &setup.camera, &walk, args.size, None)?;
        let single_ms = start.elapsed().as_secs_f64() * 1e3;
        let json = difference(
            &out.image,
            &single.image,
            world.size() as usize,
            &part,
            args,
        );
        let json = CompareJson {
            distributed_ms,
            single_ms,
            ..json
        };
        std::fs::create_dir_all(&args.output)
            .with_context(|| format!("-o {}: cannot create", args.output.display()))?;
        out.image.write_exr(&args.output.join("distributed.exr"))?;
        single.image.write_exr(&args.output.join("single.exr"))?;
        let text = serde_json::to_string_pretty(&json)?;
        std::fs::write(args.output.join("table.json"), &text)
            .with_context(|| format!("writing {}", args.output.display()))?;
        println!("{text}");
        Ok(())
    })
}

fn difference(
    a: &Image,
    b: &Image,
    ranks: usize,
    part: &Part,
    args: &super::compare::CompareArgs,
) -> CompareJson {
    let mut max = 0.0f32;
    let (mut sum, mut over, mut lit) = (0.0f64, 0, 0);
    for (p, q) in a.rgba.iter().zip(&b.rgba) {
        let d = (0..4).map(|c| (p[c] - q[c]).abs()).fold(0.0f32, f32::max);
        max = max.max(d);
        sum += f64::from(d);
        over += usize::from(d > 1e-5);
        lit += usize::from(q[3] > 0.0);
    }
    CompareJson {
        ranks,
        mesh: part.setup.name().to_string(),
        size: format!("{}x{}", args.size.0, args.size.1),
        integrator: part.setup.method.name(),
        max_abs_error: max,
        mean_abs_error: sum / a.rgba.len().max(1) as f64,
        pixels_over_1e5: over,
        pixels_lit: lit,
        distributed_ms: 0.0,
        single_ms: 0.0,
    }
}
