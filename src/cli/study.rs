//! `tetray study NAME -o DIR`: the dissertation's chapter 5-6 studies from
//! our code (tetray_study), as SVG plots, CSV tables and a JSON summary.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use clap::{Args, ValueEnum};
use tetray_integrate::Method;
use tetray_study::accuracy::{self, AccuracyOptions};
use tetray_study::psi_study::{self, PsiOptions};
use tetray_study::sampling::{self, SamplingOptions};
use tetray_study::smoothness::{self, SmoothnessOptions};
use tetray_study::speed::{self, SpeedOptions};
use tetray_study::{Check, OutputDir};

use super::parse::{parse_method, parse_size};

/// Which study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum StudyName {
    /// The Psi surface, table error maps (nearest, bilinear; both node
    /// spacings; several sizes) and the error through 100 cells (fig. 5.4).
    Psi,
    /// Per-segment error of every method against the f64 reference over
    /// the dissertation's sweeps, on the CPU and the GPU (figs. 6.5-6.11).
    Accuracy,
    /// Intensity across a slab of constant thickness and its
    /// centre-surround response: Mach bands (figs. 6.12-6.19).
    Smoothness,
    /// Frame rates per renderer and method on the datasets, against image
    /// size and mesh size (tables 6.3, 6.4, fig. 6.3).
    Speed,
    /// Shear-warp on regular grids: error against the exact ray caster
    /// over the slice distance, pre-integrated vs post-classified, on a
    /// high-frequency transfer function (Schulze et al. 2003).
    Shearwarp,
    /// Every study, each in its own subfolder.
    All,
}

/// `tetray study`.
#[derive(Debug, Clone, Args)]
pub struct StudyArgs {
    pub name: StudyName,
    /// Output folder (created if needed).
    #[arg(short, long, value_name = "DIR")]
    pub out: PathBuf,
    /// Skip the GPU halves (accuracy, smoothness, speed).
    #[arg(long)]
    pub no_gpu: bool,
    /// psi: table sizes (nodes per axis).
    #[arg(long, value_name = "N,N,..", value_delimiter = ',', default_values_t = [64usize, 256, 1024])]
    pub psi_sizes: Vec<usize>,
    /// psi: evaluation points per gamma axis.
    #[arg(long, value_name = "N", default_value_t = 200)]
    pub psi_grid: usize,
    /// accuracy: sweep points per parameter.
    #[arg(long, value_name = "N", default_value_t = 41)]
    pub steps: usize,
    /// accuracy: segment lengths D.
    #[arg(long, value_name = "D,D,..", value_delimiter = ',', default_values_t = [0.001f64, 0.1, 1.0, 100.0])]
    pub lengths: Vec<f64>,
    /// smoothness: pixels across the slab.
    #[arg(long, value_name = "N", default_value_t = 600)]
    pub pixels: u32,
    /// speed: folder of the PLOT3D datasets (bluntfin, post, comb).
    /// Default: $TETRAY_DATA_DIR, else data/plot3d in the current
    /// directory or above the executable.
    #[arg(long, value_name = "DIR")]
    pub data: Option<PathBuf>,
    /// speed: the dissertation's size (800x800, 8-frame orbits, meshes
    /// of 1 M to 40 M tetrahedra); hours on a CPU.
    #[arg(long)]
    pub full: bool,
    /// speed: image size of the timing table and the mesh sweep.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// speed: timed frames per measurement, orbiting once.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
    /// speed: the methods timed (default: every method with a GPU kernel).
    #[arg(long, value_name = "NAME,..", value_delimiter = ',', value_parser = parse_method)]
    pub methods: Option<Vec<Method>>,
    /// speed: square image sizes of the resolution sweep.
    #[arg(long, value_name = "N,N,..", value_delimiter = ',')]
    pub resolutions: Option<Vec<u32>>,
    /// speed: tetrahedra of the generated meshes (250K, 1M, 40M...).
    #[arg(long, value_name = "N,N,..", value_delimiter = ',', value_parser = parse_count)]
    pub scaling_tets: Option<Vec<usize>>,
}

/// A count with an optional K or M suffix.
fn parse_count(text: &str) -> Result<usize, String> {
    let t = text.trim();
    let (digits, scale) = match t.chars().last() {
        Some('k' | 'K') => (&t[..t.len() - 1], 1e3),
        Some('m' | 'M') => (&t[..t.len() - 1], 1e6),
        _ => (t, 1.0),
    };
    match digits.parse::<f64>() {
        Ok(v) if v > 0.0 && (v * scale) <= 2e9 => Ok((v * scale).round() as usize),
        _ => Err(format!(
            "expected a count like 5000, 250K or 40M (up to 2000M), got {text:?}"
        )),
    }
}

pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    let names: &[StudyName] = match args.name {
        StudyName::All => &[
            StudyName::Psi,
            StudyName::Accuracy,
            StudyName::Smoothness,
            StudyName::Speed,
            StudyName::Shearwarp,
        ],
        _ => std::slice::from_ref(&args.name),
    };
    let mut failures = Vec::new();
    for &name in names {
        let dir = if args.name == StudyName::All {
            args.out.join(study_name(name))
        } else {
            args.out.clone()
        };
        let start = Instant::now();
        let (out, checks) = run_one(name, args, &dir)?;
        println!(
            "{}: {} files in {} ({:.1} s)",
            study_name(name),
            out.files().len(),
            dir.display(),
            start.elapsed().as_secs_f64()
        );
        for check in checks.iter().filter(|c| !c.passed) {
            failures.push(format!(
                "{}: {} ({})",
                study_name(name),
                check.name,
                check.detail
            ));
        }
        println!(
            "  checks: {} of {} passed",
            checks.iter().filter(|c| c.passed).count(),
            checks.len()
        );
    }
    if !failures.is_empty() {
        bail!(
            "{} sanity check{} failed (results written): {}",
            failures.len(),
            if failures.len() == 1 { "" } else { "s" },
            failures.join("; ")
        );
    }
    Ok(())
}

fn study_name(name: StudyName) -> &'static str {
    match name {
        StudyName::Psi => "psi",
        StudyName::Accuracy => "accuracy",
        StudyName::Smoothness => "smoothness",
        StudyName::Speed => "speed",
        StudyName::Shearwarp => "shearwarp",
        StudyName::All => "all",
    }
}

fn run_one(
    name: StudyName,
    args: &StudyArgs,
    dir: &Path,
) -> anyhow::Result<(OutputDir, Vec<Check>)> {
    let mut out = OutputDir::create(dir).with_context(|| format!("--out {}", dir.display()))?;
    let log = |line: &str| eprintln!("{line}");
    let gpu = !args.no_gpu;
    let checks = match name {
        StudyName::Psi => {
            let options = PsiOptions {
                table_sizes: args.psi_sizes.clone(),
                grid: args.psi_grid,
                ..PsiOptions::default()
            };
            let s = psi_study::run(&options, &mut out, &log)?;
            for t in &s.tables {
                println!(
                    "  {} {:>4}^2 {:<8}: max error {:.2e}, mean {:.2e}, through {} cells {:.2e}",
                    t.spacing,
                    t.size,
                    t.lookup.name(),
                    t.max_error,
                    t.mean_error,
                    s.cells,
                    t.max_cumulative
                );
            }
            s.checks
        }
        StudyName::Accuracy => {
            let options = AccuracyOptions {
                steps: args.steps,
                lengths: args.lengths.clone(),
                gpu,
            };
            let s = accuracy::run(&options, &mut out, &log)?;
            println!(
                "  gpu: {}",
                s.gpu_adapter
                    .as_deref()
                    .or(s.gpu_note.as_deref())
                    .unwrap_or("-")
            );
            for e in &s.sweeps {
                println!(
                    "  {:<11} D = {:<6} {} {:<16} max error {:.2e}",
                    e.model,
                    e.length,
                    e.device.name(),
                    e.method,
                    e.max_error
                );
            }
            s.checks
        }
        StudyName::Smoothness => {
            let options = SmoothnessOptions {
                pixels: args.pixels,
                gpu,
                ..SmoothnessOptions::default()
            };
            let s = smoothness::run(&options, &mut out, &log)?;
            for p in s
                .profiles
                .iter()
                .filter(|p| p.luminance.starts_with("L_f = 1"))
            {
                println!(
                    "  {:<20} {:<16} range {:.2e}, centre-surround peak {:.2e}",
                    p.case, p.method, p.range, p.response
                );
            }
            s.checks
        }
        StudyName::Speed => {
            let data = super::datasets::plot3d_dir(args.data.as_deref(), "--data")?;
            let base = if args.full {
                SpeedOptions::full(data)
            } else {
                SpeedOptions::small(data)
            };
            let options = SpeedOptions {
                size: args.size.unwrap_or(base.size),
                frames: args.frames.unwrap_or(base.frames),
                methods: args.methods.clone().unwrap_or(base.methods.clone()),
                resolutions: args.resolutions.clone().unwrap_or(base.resolutions.clone()),
                scaling_tets: args
                    .scaling_tets
                    .clone()
                    .unwrap_or(base.scaling_tets.clone()),
                gpu,
                data_dir: base.data_dir,
            };
            let s = speed::run(&options, &mut out, &log)?;
            println!(
                "  {}; gpu: {}",
                s.cpu,
                s.gpu_adapter.as_deref().unwrap_or("none")
            );
            for r in &s.table {
                println!(
                    "  {:<18} {} {:<16} {:>9.2} ms  {:>8.3} frames/s  {:>10.0} tets/s  {:>12.0} segments/s",
                    r.mesh,
                    r.renderer,
                    r.method,
                    r.ms_per_frame,
                    r.fps,
                    r.tets_per_s,
                    r.segments_per_s
                );
            }
            for note in &s.notes {
                println!("  note: {note}");
            }
            s.checks
        }
        StudyName::Shearwarp => {
            let s = sampling::run(&SamplingOptions::default(), &mut out, &log)?;
            for r in &s.rows {
                println!(
                    "  {:>3}^3  slice distance {:.4}  {:<16} mean error {:.2e}  max {:.2e}",
                    r.points_per_axis,
                    r.slice_distance,
                    r.classification,
                    r.mean_error,
                    r.max_error
                );
                let bins: Vec<String> = r
                    .by_chord
                    .iter()
                    .map(|b| format!("{} {:.2e} ({} px)", b.slabs, b.mean_error, b.pixels))
                    .collect();
                println!("        by chord (slice distances): {}", bins.join(", "));
            }
            s.checks
        }
        StudyName::All => unreachable!("expanded by run"),
    };
    Ok((out, checks))
}

#[cfg(test)]
mod tests {
    use super::parse_count;

    #[test]
    fn counts() {
        assert_eq!(parse_count("5000"), Ok(5000));
        assert_eq!(parse_count("250K"), Ok(250_000));
        assert_eq!(parse_count("1.5M"), Ok(1_500_000));
        assert!(parse_count("0").is_err() && parse_count("x").is_err());
    }
}
