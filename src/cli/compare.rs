//! `tetray compare`: one view rendered by several renderer / integrator /
//! sort combinations, each measured against the exact f64 CPU reference
//! (`--integrator reference` on the CPU ray caster): a labelled sheet,
//! absolute-error and FLIP-like heat maps, and a table (JSON, Markdown).

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_integrate::Method;
use tetray_project::SortKind;

use super::args::{
    parse_bvh_preset, parse_method, parse_rgb, parse_size, CameraArgs, IntegratorArgs, MeshArgs,
    RendererArg, WalkArgs,
};
use super::renderer::{Engine, Frame};
use super::scene::{self, Setup};

/// One combination to compare: `RENDERER[:INTEGRATOR][:SORT]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MethodSpec {
    pub renderer: RendererArg,
    /// None: --integrator.
    pub method: Option<Method>,
    /// None: mpvonc (project only).
    pub sort: Option<SortKind>,
}

#[derive(Debug, Clone, Args)]
pub struct CompareArgs {
    #[command(flatten)]
    pub mesh: MeshArgs,
    #[command(flatten)]
    pub integrator: IntegratorArgs,
    #[command(flatten)]
    pub camera: CameraArgs,
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
        value_parser = parse_spec,
        default_value = "gpu,project:centroid,project:mpvo,project:mpvonc"
    )]
    pub methods: Vec<MethodSpec>,
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
    pub distributed: super::distributed::DistributedArgs,
}

/// A combination by name: "gpu", "cpu:exact", "project:ppi:mpvo".
pub fn parse_spec(text: &str) -> Result<MethodSpec, String> {
    let mut parts = text.trim().split(':');
    let renderer = match parts.next().map(str::to_ascii_lowercase).as_deref() {
        Some("cpu") => RendererArg::Cpu,
        Some("gpu") => RendererArg::Gpu,
        Some("project") => RendererArg::Project,
        Some("shear-warp") => RendererArg::ShearWarp,
        _ => {
            return Err(format!(
                "{text:?}: the renderer must be cpu, gpu, project or shear-warp"
            ))
        }
    };
    let mut spec = MethodSpec {
        renderer,
        method: None,
        sort: None,
    };
    for part in parts {
        if let Ok(sort) = part.parse::<SortKind>() {
            if renderer != RendererArg::Project || spec.sort.is_some() {
                return Err(format!("{text:?}: one sort, and only for project"));
            }
            spec.sort = Some(sort);
        } else if let Ok(method) = parse_method(part) {
            if spec.method.replace(method).is_some() {
                return Err(format!("{text:?}: one integrator"));
            }
        } else {
            return Err(format!(
                "{text:?}: {part:?} is neither an integrator nor a sort (centroid, mpvo, mpvonc)"
            ));
        }
    }
    Ok(spec)
}

pub fn run(args: &CompareArgs) -> anyhow::Result<()> {
    #[cfg(feature = "mpi")]
    if let Some(done) = super::distributed::compare(args) {
        return done;
    }
    scene::configure_threads(args.threads)?;
    let log = |line: String| println!("{line}");
    // No early termination: every method integrates every ray to its end,
    // as the reference does.
    let walk = WalkArgs {
        renderer: RendererArg::Cpu,
        early_termination: 1.0,
        max_steps: None,
        threads: args.threads,
        bvh_preset: Some(args.bvh_preset),
        sort: SortKind::Mpvonc,
        no_adaptive_tf: args.no_adaptive_tf,
    };
    let frame = scene::FrameArgs {
        mesh: &args.mesh,
        integrator: &args.integrator,
        camera: &args.camera,
        walk: &walk,
        size: args.size,
    };
    let mut setup = scene::prepare(frame, &log)?;
    let reference_spec = MethodSpec {
        renderer: RendererArg::Cpu,
        method: Some(Method::Reference),
        sort: None,
    };
    let reference = render_method(&mut setup, &reference_spec, args, &walk, &log)?;
    let methods = args
        .methods
        .iter()
        .map(|spec| render_method(&mut setup, spec, args, &walk, &log))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let title = format!("{} ({} tetrahedra)", setup.mesh_name, setup.tet_count());
    let report = tetray_compare::compare(&title, reference, methods)?;
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

/// Renders one combination: a warm-up frame on the GPU, then `--frames`
/// timed frames, the median reported.
fn render_method(
    setup: &mut Setup,
    spec: &MethodSpec,
    args: &CompareArgs,
    walk: &WalkArgs,
    log: &dyn Fn(String),
) -> anyhow::Result<tetray_compare::Method> {
    let method = spec.method.unwrap_or(args.integrator.integrator);
    setup.use_method(method)?;
    let setup: &Setup = setup;
    let walk = WalkArgs {
        renderer: spec.renderer,
        sort: spec.sort.unwrap_or(walk.sort),
        ..walk.clone()
    };
    let engine = Engine::new(spec.renderer, setup, log)?;
    let label = match spec.renderer {
        RendererArg::Project if walk.no_adaptive_tf => {
            format!("project {method} {} vertex-tf", walk.sort)
        }
        RendererArg::Project => format!("project {method} {}", walk.sort),
        RendererArg::ShearWarp => format!(
            "shear-warp {}",
            super::shear_warp::classification(method).name()
        ),
        _ => format!("{} {method}", engine.name()),
    };
    let render = || {
        engine
            .render(setup, &setup.camera, &walk, args.size, None)
            .with_context(|| format!("{label}: rendering"))
    };
    if !matches!(engine, Engine::Cpu | Engine::ShearWarp(_)) {
        render()?;
    }
    let mut frames: Vec<Frame> = (0..args.frames)
        .map(|_| render())
        .collect::<anyhow::Result<_>>()?;
    frames.sort_by_key(|f| f.stats.elapsed);
    let frame = frames.swap_remove(frames.len() / 2);
    let seconds = frame.stats.elapsed.as_secs_f64().max(1e-9);
    log(format!(
        "{label}: {:.1} ms on {}",
        seconds * 1e3,
        engine.adapter()
    ));
    Ok(tetray_compare::Method {
        label,
        renderer: engine.name().to_string(),
        integrator: method.name().to_string(),
        sort: (spec.renderer == RendererArg::Project).then(|| walk.sort.name().to_string()),
        adaptive_tf: frame.stats.project.map(|p| p.adaptive_tf),
        speed: tetray_compare::Speed {
            ms_per_frame: seconds * 1e3,
            tets_per_s: setup.tet_count() as f64 / seconds,
            segments_per_s: frame.stats.counters.segments as f64 / seconds,
        },
        image: frame.image,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_name_a_renderer_then_an_integrator_and_a_sort() {
        let spec = parse_spec("project:exact:mpvo").unwrap();
        assert_eq!(spec.renderer, RendererArg::Project);
        assert_eq!(spec.method, Some(Method::Exact));
        assert_eq!(spec.sort, Some(SortKind::Mpvo));
        assert_eq!(parse_spec("gpu").unwrap().method, None);
        assert_eq!(
            parse_spec("project:centroid").unwrap().sort,
            Some(SortKind::Centroid)
        );
        assert!(parse_spec("gpu:mpvo").is_err(), "a sort is for project");
        assert!(parse_spec("auto").is_err());
        assert_eq!(
            parse_spec("shear-warp:riemann").unwrap().renderer,
            RendererArg::ShearWarp
        );
        assert!(parse_spec("cpu:simpson").unwrap_err().contains("neither"));
        assert!(parse_spec("cpu:ppi:exact").is_err());
    }
}
