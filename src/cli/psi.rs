//! `tetray psi`: the Psi table (dissertation section 5.2.3) at one
//! (gamma_b, gamma_f), against Psi computed in f64.

use clap::Args;
use serde::Serialize;
use tetray_integrate::PsiTable;

use super::parse::parse_unit_interval;

/// `tetray psi`.
#[derive(Debug, Clone, Args)]
pub struct PsiArgs {
    /// gamma_b = tau_b D / (1 + tau_b D), in [0, 1].
    #[arg(long, value_name = "G", value_parser = parse_unit_interval, allow_hyphen_values = true)]
    pub gamma_b: f32,
    /// gamma_f = tau_f D / (1 + tau_f D), in [0, 1].
    #[arg(long, value_name = "G", value_parser = parse_unit_interval, allow_hyphen_values = true)]
    pub gamma_f: f32,
    /// Table nodes per axis.
    #[arg(long, value_name = "N", default_value_t = tetray_core::defaults::PSI_TABLE_SIZE)]
    pub size: usize,
}

#[derive(Debug, Serialize)]
struct PsiJson {
    gamma_b: f32,
    gamma_f: f32,
    /// tau_b D = gamma_b / (1 - gamma_b); null (infinite) at gamma_b = 1.
    tau_b_d: f64,
    tau_f_d: f64,
    size: usize,
    spacing: &'static str,
    table_bilinear: f32,
    table_nearest: f32,
    f64: f64,
    error_bilinear: f64,
    error_nearest: f64,
}

pub fn run(args: &PsiArgs) -> anyhow::Result<()> {
    let table = PsiTable::shared(args.size)?;
    let at = table.at_gamma(args.gamma_b, args.gamma_f);
    let json = PsiJson {
        gamma_b: args.gamma_b,
        gamma_f: args.gamma_f,
        tau_b_d: at.tau_b_d,
        tau_f_d: at.tau_f_d,
        size: table.size(),
        spacing: table.spacing().name(),
        table_bilinear: at.bilinear,
        table_nearest: at.nearest,
        f64: at.exact,
        error_bilinear: at.error_bilinear(),
        error_nearest: at.error_nearest(),
    };
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}
