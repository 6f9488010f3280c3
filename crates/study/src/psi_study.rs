//! `psi`: the Psi function over its whole domain (dissertation fig. 5.3),
//! the error of the table against f64 Psi for nearest-node and bilinear
//! lookup at several table sizes and both node spacings (fig. 5.4a), and
//! the worst cumulative error of that lookup through 100 cells (fig. 5.4b).
//!
//! Errors are measured at a grid of (gamma_b, gamma_f) points that falls
//! between the table nodes (offsets by the golden ratio), against f64 Psi
//! at the same f32 gammas the lookup sees, so only the table is measured.

use std::time::Instant;

use rayon::prelude::*;
use serde::Serialize;
use tetray_integrate::psi::psi;
use tetray_integrate::{GammaSpacing, PsiTable};

use crate::cells;
use crate::output::{Csv, OutputDir};
use crate::svg::heat::{ColourScale, HeatPanel, heat_figure};
use crate::svg::line::{LinePanel, Series, line_figure};
use crate::svg::{Axis, Scale};
use crate::{Check, StudyError};

/// Sizes of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct PsiOptions {
    /// Table nodes per axis, one error map each.
    pub table_sizes: Vec<usize>,
    /// Evaluation points per gamma axis.
    pub grid: usize,
    /// Cells behind each other for the cumulative error (fig. 5.4b: 100).
    pub cells: u32,
}

impl Default for PsiOptions {
    fn default() -> Self {
        PsiOptions {
            table_sizes: vec![64, 256, 1024],
            grid: 200,
            cells: 100,
        }
    }
}

/// How the table is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Lookup {
    Nearest,
    Bilinear,
}

impl Lookup {
    pub fn name(self) -> &'static str {
        match self {
            Lookup::Nearest => "nearest",
            Lookup::Bilinear => "bilinear",
        }
    }
}

/// The error of one table read one way.
#[derive(Debug, Clone, Serialize)]
pub struct TableError {
    pub spacing: &'static str,
    pub lookup: Lookup,
    pub size: usize,
    pub build_s: f64,
    pub max_error: f64,
    pub mean_error: f64,
    /// Where the largest error is.
    pub max_at_gamma: (f64, f64),
    /// Largest worst-case cumulative error through `cells` cells.
    pub max_cumulative: f64,
}

/// What the study found.
#[derive(Debug, Clone, Serialize)]
pub struct PsiSummary {
    pub grid: usize,
    pub cells: u32,
    pub tables: Vec<TableError>,
    pub checks: Vec<Check>,
}

const GOLDEN: f64 = 0.618_033_988_749_895;
const SPACINGS: [GammaSpacing; 2] = [GammaSpacing::Uniform, GammaSpacing::Quadratic];
const LOOKUPS: [Lookup; 2] = [Lookup::Nearest, Lookup::Bilinear];

/// `tau D` of gamma (eq. 5.9 inverted), infinite at 1.
fn tau_d(gamma: f64) -> f64 {
    if gamma >= 1.0 {
        f64::INFINITY
    } else {
        gamma / (1.0 - gamma)
    }
}

/// Runs the study, writing its plots and tables into `out`.
pub fn run(
    options: &PsiOptions,
    out: &mut OutputDir,
    log: &dyn Fn(&str),
) -> Result<PsiSummary, StudyError> {
    if options.grid < 2 || options.table_sizes.is_empty() || options.cells == 0 {
        return Err(StudyError::Option(
            "psi: needs a grid of at least 2 points, a table size and at least one cell".into(),
        ));
    }
    let n = options.grid;
    // f32 gammas between the nodes; the f64 reference at exactly those.
    let gammas: Vec<f32> = (0..n)
        .map(|i| ((i as f64 + GOLDEN) / n as f64) as f32)
        .collect();
    let points: Vec<(f32, f32)> = (0..n * n).map(|k| (gammas[k % n], gammas[k / n])).collect();
    let reference: Vec<f64> = points
        .par_iter()
        .map(|&(b, f)| psi(tau_d(f64::from(b)), tau_d(f64::from(f))))
        .collect();
    // Transmittance of one cell at each point, for the cumulative error.
    let zeta: Vec<f64> = points
        .iter()
        .map(|&(b, f)| (-0.5 * (tau_d(f64::from(b)) + tau_d(f64::from(f)))).exp())
        .collect();
    let attenuation_sum = |z: f64| {
        if z >= 1.0 {
            f64::from(options.cells)
        } else {
            (1.0 - z.powi(options.cells as i32)) / (1.0 - z)
        }
    };
    // Point i lies in the i-th of n equal cells of [0, 1].
    let range = (0.0, 1.0);
    let panel = |title: String, values: Vec<f64>| HeatPanel {
        title,
        x_label: "gamma_b (back)".into(),
        y_label: "gamma_f (front)".into(),
        x_range: range,
        y_range: range,
        nx: n,
        ny: n,
        values,
    };

    let mut maps: Vec<(GammaSpacing, Lookup, usize, Vec<f64>)> = Vec::new();
    let mut tables = Vec::new();
    for spacing in SPACINGS {
        for &size in &options.table_sizes {
            let start = Instant::now();
            let table = PsiTable::build(size, spacing)?;
            let build_s = start.elapsed().as_secs_f64();
            log(&format!(
                "psi: {} table {size}x{size} built in {build_s:.2} s",
                spacing.name()
            ));
            for lookup in LOOKUPS {
                let errors: Vec<f64> = points
                    .par_iter()
                    .zip(&reference)
                    .map(|(&(b, f), &want)| {
                        let got = match lookup {
                            Lookup::Nearest => table.lookup_gamma_nearest(b, f),
                            Lookup::Bilinear => table.lookup_gamma(b, f),
                        };
                        (f64::from(got) - want).abs()
                    })
                    .collect();
                let (k_max, max_error) = errors
                    .iter()
                    .copied()
                    .enumerate()
                    .fold((0, 0.0), |a, (k, e)| if e > a.1 { (k, e) } else { a });
                let max_cumulative = errors
                    .iter()
                    .zip(&zeta)
                    .map(|(e, &z)| e * attenuation_sum(z))
                    .fold(0.0, f64::max);
                tables.push(TableError {
                    spacing: spacing.name(),
                    lookup,
                    size,
                    build_s,
                    max_error,
                    mean_error: errors.iter().sum::<f64>() / errors.len() as f64,
                    max_at_gamma: (f64::from(points[k_max].0), f64::from(points[k_max].1)),
                    max_cumulative,
                });
                maps.push((spacing, lookup, size, errors));
            }
        }
    }

    // The surface (fig. 5.3).
    let surface = heat_figure(
        "Psi(gamma_b, gamma_f), eq. 5.10 (f64 quadrature)",
        &[panel("Psi".into(), reference.clone())],
        1,
        ColourScale {
            scale: Scale::Linear,
            lo: 0.0,
            hi: 1.0,
        },
        "Psi",
    )?;
    out.write("psi_surface.svg", &surface)?;

    // Error maps (fig. 5.4a), one figure per spacing and lookup, one panel
    // per size, on one colour scale.
    let error_scale = ColourScale::log_fit(maps.iter().flat_map(|m| m.3.iter().copied()), 8);
    for spacing in SPACINGS {
        for lookup in LOOKUPS {
            let panels: Vec<HeatPanel> = maps
                .iter()
                .filter(|m| m.0 == spacing && m.1 == lookup)
                .map(|m| panel(format!("{0} x {0} table", m.2), m.3.clone()))
                .collect();
            let svg = heat_figure(
                &format!(
                    "|table - Psi|, {} lookup, nodes {} in gamma (fig. 5.4a)",
                    lookup.name(),
                    spacing_words(spacing)
                ),
                &panels,
                panels.len(),
                error_scale,
                "absolute error of Psi",
            )?;
            out.write(
                &format!("psi_error_{}_{}.svg", spacing.name(), lookup.name()),
                &svg,
            )?;
        }
    }

    // Cumulative error through the cells (fig. 5.4b), at the largest size.
    let largest = *options.table_sizes.iter().max().expect("checked non-empty");
    let cumulative: Vec<HeatPanel> = maps
        .iter()
        .filter(|m| m.2 == largest)
        .map(|m| {
            let values = m.3.iter().zip(&zeta).map(|(e, &z)| e * attenuation_sum(z));
            panel(
                format!("{} nodes, {}", m.0.name(), m.1.name()),
                values.collect(),
            )
        })
        .collect();
    let cumulative_scale =
        ColourScale::log_fit(cumulative.iter().flat_map(|p| p.values.iter().copied()), 8);
    let svg = heat_figure(
        &format!(
            "Worst error through {} equal cells, L_b - L_f = 1, {largest} x {largest} table (fig. 5.4b)",
            options.cells
        ),
        &cumulative,
        2,
        cumulative_scale,
        "cumulative absolute error of I",
    )?;
    out.write("psi_cumulative.svg", &svg)?;

    // Error against table size.
    let mut series = Vec::new();
    for (c, (spacing, lookup)) in SPACINGS
        .iter()
        .flat_map(|&s| LOOKUPS.map(|l| (s, l)))
        .enumerate()
    {
        let of = |t: &&TableError| t.spacing == spacing.name() && t.lookup == lookup;
        let label = format!("{} {}", spacing.name(), lookup.name());
        let max: Vec<(f64, f64)> = tables
            .iter()
            .filter(of)
            .map(|t| (t.size as f64, t.max_error))
            .collect();
        let mean = tables
            .iter()
            .filter(of)
            .map(|t| (t.size as f64, t.mean_error))
            .collect();
        series.push(Series::new(format!("{label}, max"), c, max).with_markers());
        series.push(Series::new(format!("{label}, mean"), c, mean).dashed());
    }
    let chart = line_figure(
        "Psi table error against table size",
        &[LinePanel {
            title: format!("over {n} x {n} points between the nodes"),
            x: Axis::log("table nodes per axis"),
            y: Axis::log("absolute error of Psi"),
            series,
        }],
        1,
    );
    out.write("psi_error_by_size.svg", &chart)?;

    let mut summary_csv = Csv::new(&[
        "spacing",
        "lookup",
        "size",
        "build_s",
        "max_error",
        "mean_error",
        "max_at_gamma_b",
        "max_at_gamma_f",
        "max_cumulative",
    ]);
    for t in &tables {
        summary_csv.row(&cells![
            t.spacing,
            t.lookup.name(),
            t.size,
            t.build_s,
            t.max_error,
            t.mean_error,
            t.max_at_gamma.0,
            t.max_at_gamma.1,
            t.max_cumulative
        ]);
    }
    out.csv("psi_errors.csv", &summary_csv)?;
    let mut header = vec!["gamma_b".to_string(), "gamma_f".into(), "psi".into()];
    header.extend(
        maps.iter()
            .map(|m| format!("error_{}_{}_{}", m.0.name(), m.1.name(), m.2)),
    );
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut grid_csv = Csv::new(&header);
    for (k, &(b, f)) in points.iter().enumerate() {
        let mut row = cells![b, f, reference[k]].to_vec();
        row.extend(maps.iter().map(|m| m.3[k].into()));
        grid_csv.row(&row);
    }
    out.csv("psi_grid.csv", &grid_csv)?;

    let checks = checks(&tables);
    let summary = PsiSummary {
        grid: n,
        cells: options.cells,
        tables,
        checks,
    };
    out.json("psi.json", &summary)?;
    Ok(summary)
}

fn spacing_words(spacing: GammaSpacing) -> &'static str {
    match spacing {
        GammaSpacing::Uniform => "uniform (the dissertation's)",
        GammaSpacing::Quadratic => "quadratic (the default)",
    }
}

/// Bilinear beats nearest for every table; the quadratic nodes beat the
/// uniform ones under bilinear lookup from 64 nodes up (where the sqrt
/// behaviour near gamma_b = 1 dominates the uniform table's error).
fn checks(tables: &[TableError]) -> Vec<Check> {
    let find = |spacing: &str, lookup: Lookup, size: usize| {
        tables
            .iter()
            .find(|t| t.spacing == spacing && t.lookup == lookup && t.size == size)
            .map(|t| t.max_error)
    };
    let mut checks = Vec::new();
    for t in tables.iter().filter(|t| t.lookup == Lookup::Bilinear) {
        if let Some(nearest) = find(t.spacing, Lookup::Nearest, t.size) {
            checks.push(Check::new(
                format!("{} {}: bilinear below nearest", t.spacing, t.size),
                t.max_error < nearest,
                format!("{:.3e} vs {nearest:.3e}", t.max_error),
            ));
        }
        if t.spacing == "quadratic"
            && t.size >= 64
            && let Some(uniform) = find("uniform", Lookup::Bilinear, t.size)
        {
            checks.push(Check::new(
                format!("{}: quadratic nodes below uniform (bilinear)", t.size),
                t.max_error < uniform,
                format!("{:.3e} vs {uniform:.3e}", t.max_error),
            ));
        }
    }
    checks
}
