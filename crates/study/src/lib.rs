//! Method studies after Moreland, *Fast High Accuracy Volume Rendering*
//! (2004), chapters 5 and 6, from this project's own code: each study
//! writes SVG plots, CSV tables and a JSON summary into a folder.
//!
//! | study | what | dissertation |
//! | --- | --- | --- |
//! | [`psi_study`] | Psi over its domain; table error, nearest and bilinear, both node spacings; cumulative error through 100 cells | figs. 5.3, 5.4 |
//! | [`accuracy`] | per-segment error of every method against the f64 reference of its model, on the CPU and through the GPU kernel | figs. 6.5-6.11 |
//! | [`smoothness`] | intensity across a slab of constant thickness, and its centre-surround response (Mach bands) | figs. 6.12-6.19 |
//! | [`sampling`] | shear-warp on regular grids: error against the exact ray caster over the slice distance, pre-integrated vs post-classified, on a high-frequency transfer function | Schulze et al. 2003, sec. 2.3-2.4 |
//! | [`speed`] | frames/s, tets/s, segments/s per renderer and method on the datasets; resolution and mesh-size sweeps | tables 6.3, 6.4, fig. 6.3 |

pub mod accuracy;
mod error;
pub mod gpu_segments;
pub mod output;
pub mod psi_study;
pub mod sampling;
pub mod smoothness;
pub mod speed;
pub mod svg;

pub use error::StudyError;
pub use output::OutputDir;

use serde::Serialize;

/// A sanity check a study makes of its own numbers (recorded in its JSON;
/// the CLI reports failures).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    pub name: String,
    pub passed: bool,
    pub detail: String,
}

impl Check {
    pub fn new(name: impl Into<String>, passed: bool, detail: impl Into<String>) -> Check {
        Check {
            name: name.into(),
            passed,
            detail: detail.into(),
        }
    }
}

/// The checks that failed.
pub fn failed(checks: &[Check]) -> Vec<&Check> {
    checks.iter().filter(|c| !c.passed).collect()
}
