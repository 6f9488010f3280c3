//! `tetray generate`: large test meshes for scaling measurements, at a
//! requested tetrahedron count. `plot3d` refines a PLOT3D dataset (every
//! hexahedron cut into smaller ones) and writes PLOT3D files; `solid`
//! writes a thick torus shell with analytic scalars as `.vtu`. Prints a
//! JSON summary.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use clap::{Args, Subcommand, ValueEnum};
use serde::Serialize;
use tetray_io::generate::pieces::write_pvtu;
use tetray_io::generate::solid::{FIELDS, TorusShell};
use tetray_io::generate::{Refinement, RefinementPlan};
use tetray_io::plot3d::{plot3d_split_counts, read_plot3d_grid_files};
use tetray_io::plot3d_q_sibling;

/// `tetray generate`.
#[derive(Debug, Clone, Args)]
pub struct GenerateArgs {
    #[command(subcommand)]
    pub what: GenerateCommand,
}

#[derive(Debug, Clone, Subcommand)]
pub enum GenerateCommand {
    /// A PLOT3D dataset refined (each hexahedron cut into 8 per level, or
    /// near-uniform factors for --tets), written as <name>xyz.bin + <name>q.bin.
    Plot3d(Plot3dArgs),
    /// A thick torus shell (nonconvex, genus 1 boundaries) with the analytic
    /// point scalars "wave" and "linear", written as .vtu.
    Solid(SolidArgs),
    /// A uniform grid over [-1, 1]^3 with the analytic point scalar "bump",
    /// written as .vti (for --renderer shear-warp and the tetrahedral ones).
    Grid(super::generate_grid::GridArgs),
}

/// The NASA datasets of the repository's data folder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Dataset {
    Bluntfin,
    Post,
    Comb,
}

impl Dataset {
    fn name(self) -> &'static str {
        match self {
            Dataset::Bluntfin => "bluntfin",
            Dataset::Post => "post",
            Dataset::Comb => "comb",
        }
    }
}

/// `tetray generate plot3d`.
#[derive(Debug, Clone, Args)]
pub struct Plot3dArgs {
    /// Dataset to refine, read from --data-dir.
    #[arg(
        long,
        value_enum,
        required_unless_present = "grid",
        conflicts_with = "grid"
    )]
    pub dataset: Option<Dataset>,
    /// Or any single-grid PLOT3D file (a refined one too); its solution is
    /// the q sibling (postxyz.bin -> postq.bin) or --q.
    #[arg(long, value_name = "FILE")]
    pub grid: Option<PathBuf>,
    /// Solution file of --grid.
    #[arg(long, value_name = "FILE", requires = "grid")]
    pub q: Option<PathBuf>,
    /// Folder of the datasets. Default: $TETRAY_DATA_DIR, else
    /// data/plot3d in the current directory or above the executable.
    #[arg(long, value_name = "DIR")]
    pub data_dir: Option<PathBuf>,
    /// Tetrahedra wanted (at least): 1M, 10M, 40M or a whole number (k, M,
    /// G: thousands, millions, billions). The smallest near-uniform
    /// refinement reaching it is used.
    #[arg(long, value_name = "N", value_parser = parse_tet_count, required_unless_present = "level")]
    pub tets: Option<usize>,
    /// Or levels of doubling: each level cuts every hexahedron into 8.
    #[arg(long, value_name = "L", conflicts_with = "tets", value_parser = clap::value_parser!(u32).range(0..=16))]
    pub level: Option<u32>,
    /// Output folder (created if missing).
    #[arg(short, long, value_name = "DIR")]
    pub output: PathBuf,
}

/// `tetray generate solid`.
#[derive(Debug, Clone, Args)]
pub struct SolidArgs {
    /// Tetrahedra wanted (at least): 1M, 10M, 40M or a whole number (k, M,
    /// G: thousands, millions, billions).
    #[arg(long, value_name = "N", value_parser = parse_tet_count)]
    pub tets: usize,
    /// Output file: .vtu, or .pvtu for a partitioned file whose pieces go
    /// to the folder <stem>/ beside it.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
    /// Piece files of a .pvtu output (slabs around the torus axis, joined
    /// on load by welding their shared points).
    #[arg(long, value_name = "N", default_value_t = 4)]
    pub pieces: usize,
    /// Write a time series of N steps sharing the points and cells: the
    /// output is a .series file naming <stem>_0000.vtu ... beside it, at
    /// times k / N; "wave" travels, sin(3x + 2 pi t) cos 3y + sin(6z) / 2,
    /// and "linear" grows, (1 + t)(x + 2y + 3z).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub steps: Option<u32>,
}

#[derive(Debug, Serialize)]
struct FileJson {
    path: String,
    bytes: u64,
}

#[derive(Debug, Serialize)]
struct Plot3dJson {
    kind: &'static str,
    source: String,
    source_dims: [usize; 3],
    source_tets: usize,
    requested_tets: Option<usize>,
    level: Option<u32>,
    factors: [usize; 3],
    dims: [usize; 3],
    points: usize,
    hexahedra: usize,
    blanked_hexahedra: usize,
    degenerate_dropped: usize,
    /// Flat tetrahedra with four distinct corners (see `SplitCounts`).
    thin: usize,
    reoriented: usize,
    diagonal_parity: usize,
    /// Source cells refined on their tetrahedra (a corner where the
    /// trilinear map inverts).
    folded_cells: usize,
    tets: usize,
    files: Vec<FileJson>,
    bytes: u64,
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct SolidJson {
    kind: &'static str,
    shape: &'static str,
    major_radius: f64,
    inner_radius: f64,
    outer_radius: f64,
    /// Around the axis, around the tube, across the wall.
    cells: [usize; 3],
    requested_tets: usize,
    points: usize,
    tets: usize,
    fields: [&'static str; 2],
    files: Vec<FileJson>,
    bytes: u64,
    seconds: f64,
}

pub fn run(args: &GenerateArgs) -> anyhow::Result<()> {
    match &args.what {
        GenerateCommand::Plot3d(args) => plot3d(args),
        GenerateCommand::Solid(args) => solid(args),
        GenerateCommand::Grid(args) => super::generate_grid::grid(args),
    }
}

fn plot3d(args: &Plot3dArgs) -> anyhow::Result<()> {
    let start = Instant::now();
    let (xyz, q) = source_files(args)?;
    let file_name = |path: &Path| -> anyhow::Result<PathBuf> {
        let name = path.file_name().context("a file name is needed")?;
        Ok(args.output.join(name))
    };
    let (out_xyz, out_q) = (file_name(&xyz)?, q.as_deref().map(file_name).transpose()?);
    for (input, output) in [(Some(&xyz), Some(&out_xyz)), (q.as_ref(), out_q.as_ref())] {
        if let (Some(input), Some(output)) = (input, output)
            && same_file(input, output)
        {
            bail!(
                "{}: the output would overwrite the input; choose another -o folder",
                output.display()
            );
        }
    }
    let source = read_plot3d_grid_files(&xyz, q.as_deref())?;
    let plan = match (args.tets, args.level) {
        (Some(tets), _) => RefinementPlan::for_tets(&source, tets)?,
        (None, Some(level)) => RefinementPlan::for_level(&source, level)?,
        (None, None) => bail!("give --tets or --level"),
    };
    if let Some(defect) = plan.defect() {
        eprintln!(
            "warning: refining by {:?}: {defect}; the mesh will not validate (--tets avoids \
             such factors)",
            plan.factors
        );
    }
    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("{}: cannot create the folder", args.output.display()))?;
    let (xyz_bytes, q_bytes) = plan.write(&source, &out_xyz, out_q.as_deref())?;
    let mut files = vec![FileJson {
        path: out_xyz.display().to_string(),
        bytes: xyz_bytes,
    }];
    if let (Some(path), Some(bytes)) = (&out_q, q_bytes) {
        files.push(FileJson {
            path: path.display().to_string(),
            bytes,
        });
    }
    let counts = plan.counts;
    let json = Plot3dJson {
        kind: "plot3d",
        source: xyz.display().to_string(),
        source_dims: source.dims,
        source_tets: plot3d_split_counts(&source).tets,
        requested_tets: args.tets,
        level: args.level,
        factors: plan.factors,
        dims: plan.dims,
        points: plan.dims.iter().product(),
        hexahedra: counts.hexahedra,
        blanked_hexahedra: counts.blanked_hexahedra,
        degenerate_dropped: counts.degenerate_dropped,
        thin: counts.thin,
        reoriented: counts.reoriented,
        diagonal_parity: counts.diagonal_parity,
        folded_cells: Refinement::new(&source, plan.factors)?.folded_cells(),
        tets: counts.tets,
        bytes: files.iter().map(|f| f.bytes).sum(),
        files,
        seconds: start.elapsed().as_secs_f64(),
    };
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}

/// The grid and solution files to refine.
fn source_files(args: &Plot3dArgs) -> anyhow::Result<(PathBuf, Option<PathBuf>)> {
    if let Some(grid) = &args.grid {
        let q = match &args.q {
            Some(q) => Some(q.clone()),
            None => plot3d_q_sibling(grid).filter(|q| q.is_file()),
        };
        return Ok((grid.clone(), q));
    }
    let Some(dataset) = args.dataset else {
        bail!("give --dataset or --grid");
    };
    let dir = super::datasets::plot3d_dir(args.data_dir.as_deref(), "--data-dir")?;
    let xyz = dir.join(format!("{}xyz.bin", dataset.name()));
    let q = dir.join(format!("{}q.bin", dataset.name()));
    for file in [&xyz, &q] {
        if !file.is_file() {
            bail!(
                "{}: dataset file not found (set --data-dir or TETRAY_DATA_DIR)",
                file.display()
            );
        }
    }
    Ok((xyz, Some(q)))
}

/// Whether two paths name the same existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

fn solid(args: &SolidArgs) -> anyhow::Result<()> {
    let start = Instant::now();
    let extension = args
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase());
    let partitioned = match (extension.as_deref(), args.steps) {
        (Some("series"), Some(_)) | (Some("vtu"), None) => false,
        (Some("pvtu"), None) => true,
        (_, Some(_)) => bail!(
            "{}: --steps writes a time series: give a .series output",
            args.output.display()
        ),
        _ => bail!(
            "{}: the output must be a .vtu or .pvtu file",
            args.output.display()
        ),
    };
    let shell = TorusShell::with_tets(args.tets)?;
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create the folder", dir.display()))?;
    }
    let files: Vec<FileJson> = if let Some(steps) = args.steps {
        write_series(&shell, &args.output, steps)?
    } else if partitioned {
        write_pvtu(&shell, &args.output, args.pieces)?
            .into_iter()
            .map(|(path, bytes)| FileJson {
                path: path.display().to_string(),
                bytes,
            })
            .collect()
    } else {
        vec![FileJson {
            path: args.output.display().to_string(),
            bytes: shell.write_vtu(&args.output)?,
        }]
    };
    let bytes = files.iter().map(|f| f.bytes).sum();
    let json = SolidJson {
        kind: "solid",
        shape: "torus shell",
        major_radius: shell.major_radius,
        inner_radius: shell.inner_radius,
        outer_radius: shell.outer_radius,
        cells: shell.cells,
        requested_tets: args.tets,
        points: shell.point_count(),
        tets: shell.tet_count(),
        fields: FIELDS,
        files,
        bytes,
        seconds: start.elapsed().as_secs_f64(),
    };
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}

/// The steps of a time series beside `output` (`<stem>_0000.vtu` ...) and
/// the `.series` file naming them, at times k / steps.
fn write_series(shell: &TorusShell, output: &Path, steps: u32) -> anyhow::Result<Vec<FileJson>> {
    let stem = output
        .file_stem()
        .map_or_else(|| "series".into(), |s| s.to_string_lossy().into_owned());
    let folder = output.parent().unwrap_or(Path::new(""));
    let mut files = Vec::new();
    let mut entries = Vec::new();
    for k in 0..steps {
        let name = format!("{stem}_{k:04}.vtu");
        let path = folder.join(&name);
        let time = f64::from(k) / f64::from(steps);
        let bytes = shell.write_vtu_at(&path, time)?;
        files.push(FileJson {
            path: path.display().to_string(),
            bytes,
        });
        entries.push(serde_json::json!({ "name": name, "time": time }));
    }
    let series = serde_json::json!({ "file-series-version": "1.0", "files": entries });
    let text = serde_json::to_string_pretty(&series)?;
    std::fs::write(output, &text).with_context(|| format!("{}: cannot write", output.display()))?;
    files.push(FileJson {
        path: output.display().to_string(),
        bytes: text.len() as u64,
    });
    Ok(files)
}

/// A tetrahedron count: a whole number, or a number with the suffix k, M
/// or G (thousands, millions, billions: `1M`, `2.5M`, `40M`); `_` may
/// group digits.
pub fn parse_tet_count(text: &str) -> Result<usize, String> {
    let t = text.trim().replace('_', "");
    let (number, scale) = match t.chars().last() {
        Some('k' | 'K') => (&t[..t.len() - 1], 1e3),
        Some('m' | 'M') => (&t[..t.len() - 1], 1e6),
        Some('g' | 'G') => (&t[..t.len() - 1], 1e9),
        _ => (t.as_str(), 1.0),
    };
    let bad = || format!("expected a count such as 20000, 1M, 10M or 40M, got {text:?}");
    let count = if scale == 1.0 {
        number.parse::<usize>().map_err(|_| bad())?
    } else {
        let v = number.parse::<f64>().map_err(|_| bad())? * scale;
        if !v.is_finite() || v < 0.0 || v >= usize::MAX as f64 {
            return Err(bad());
        }
        v.round() as usize
    };
    if count == 0 {
        return Err(format!("{text:?}: at least 1 tetrahedron"));
    }
    Ok(count)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tet_counts_parse() {
        assert_eq!(parse_tet_count("20000"), Ok(20_000));
        assert_eq!(parse_tet_count("1M"), Ok(1_000_000));
        assert_eq!(parse_tet_count("10m"), Ok(10_000_000));
        assert_eq!(parse_tet_count("40M"), Ok(40_000_000));
        assert_eq!(parse_tet_count("2.5M"), Ok(2_500_000));
        assert_eq!(parse_tet_count("500k"), Ok(500_000));
        assert_eq!(parse_tet_count("1G"), Ok(1_000_000_000));
        assert_eq!(parse_tet_count("1_000_000"), Ok(1_000_000));
        for bad in ["", "M", "ten", "-5", "1.5", "1e3", "nanM", "-1M"] {
            assert!(parse_tet_count(bad).is_err(), "{bad:?}");
        }
        assert!(parse_tet_count("0").unwrap_err().contains("at least 1"));
    }
}
