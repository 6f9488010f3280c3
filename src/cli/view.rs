//! `tetray view`: the interactive viewer (crates/viewer) on a mesh or the
//! embedded dataset.

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Context;
use clap::Args;
use glam::DVec3;
use tetray_integrate::{Method, TransferFunction};
use tetray_viewer::{Dataset, GridVolume, ViewerOptions};

use super::args::{parse_method, parse_positive, MeshArgs, OpacityModeArg};
use super::scene::load_mesh;
use tetray_mesh::value_range;

/// `tetray view`.
#[derive(Debug, Clone, Args)]
pub struct ViewArgs {
    #[command(flatten)]
    pub mesh: MeshArgs,
    /// Point scalar field to show first (default: the first that is not
    /// constant; the viewer lists them all).
    #[arg(long, value_name = "NAME")]
    pub scalar: Option<String>,
    /// Integration method to start with (see `tetray render --help`).
    #[arg(long, value_name = "NAME", default_value = "ppi", value_parser = parse_method)]
    pub integrator: Method,
    /// ParaView colour-map preset JSON to start with.
    #[arg(long, value_name = "FILE")]
    pub tf: Option<PathBuf>,
    /// Preset name when the JSON holds several (default: the first).
    #[arg(long, value_name = "NAME", requires = "tf")]
    pub tf_name: Option<String>,
    /// Keep the preset's scalar values instead of rescaling them to the
    /// data range.
    #[arg(long, requires = "tf")]
    pub no_rescale: bool,
    /// Opacity unit distance (default: ParaView's, as for `render`).
    #[arg(long, value_name = "U", value_parser = parse_positive, allow_hyphen_values = true)]
    pub unit_distance: Option<f32>,
    /// How opacity becomes attenuation.
    #[arg(long, value_enum, default_value_t = OpacityModeArg::Exact)]
    pub opacity_mode: OpacityModeArg,
    /// Rendered pixels per display pixel, per side, in (0, 2]. Default: 1
    /// on a GPU, 0.25 on a CPU implementation such as lavapipe.
    #[arg(long, value_name = "S", value_parser = parse_image_scale, allow_hyphen_values = true)]
    pub image_scale: Option<f32>,
    /// Ray casting one display frame may take, in milliseconds: a slower
    /// frame is shown as a preview while the view changes, then refined a
    /// few rows per display frame.
    #[arg(long, value_name = "MS", default_value_t = 40, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub budget_ms: u32,
    /// Stop a ray once its opacity reaches A, in (0, 1]; 1 disables.
    #[arg(long, value_name = "A", default_value_t = 1.0, value_parser = parse_alpha, allow_hyphen_values = true)]
    pub early_termination: f32,
}

pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    let tf_text = match &args.tf {
        Some(path) => Some(
            std::fs::read_to_string(path)
                .with_context(|| format!("--tf {}: cannot read", path.display()))?,
        ),
        None => None,
    };
    let input = load_mesh(&args.mesh)?;
    println!("{}", input.describe());
    let fields = &input.loaded.mesh.fields;
    let field = match &args.scalar {
        Some(name) => fields
            .iter()
            .find(|f| &f.name == name)
            .with_context(|| format!("--scalar {name:?}: {} has no such field", input.name))?,
        None => tetray_mesh::default_field(&input.loaded.mesh)
            .with_context(|| format!("{} has no point scalar field to view", input.name))?,
    };
    let (lo, hi) = value_range(&field.values);
    let tf = match (&args.tf, &tf_text) {
        (Some(path), Some(text)) => {
            let rescale = (!args.no_rescale).then_some((lo, hi));
            Some(
                TransferFunction::from_paraview_json(text, args.tf_name.as_deref(), rescale)
                    .with_context(|| format!("--tf {}", path.display()))?,
            )
        }
        _ => None,
    };
    let options = ViewerOptions {
        field: Some(field.name.clone()),
        tf,
        method: args.integrator,
        unit_distance: args.unit_distance,
        opacity_mode: args.opacity_mode.into(),
        image_scale: args.image_scale,
        budget: Duration::from_millis(u64::from(args.budget_ms)),
        early_termination: args.early_termination,
    };
    let origin = input.loaded.origin();
    let mut dataset = Dataset::from_loaded(input.name, input.loaded);
    if let Some(grid) = args
        .mesh
        .mesh
        .as_deref()
        .and_then(|p| image_grid(p, origin))
    {
        dataset = dataset.with_grid(grid);
        println!("image data: the shear-warp renderer is available in the Renderer menu");
    }
    tetray_viewer::run(dataset, options)
}

/// The file's regular grid, in the mesh's coordinates (relative to
/// `origin`), when it is image data: `.vti`, or a legacy `.vtk` whose
/// header names STRUCTURED_POINTS. Anything else is no grid, and a grid
/// that fails to read is a warning (the tetrahedra still render).
fn image_grid(path: &Path, origin: DVec3) -> Option<GridVolume> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    let image_data = match ext.as_str() {
        "vti" => true,
        "vtk" => {
            let mut head = vec![0u8; 1024];
            let n = std::fs::File::open(path)
                .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
                .ok()?;
            String::from_utf8_lossy(&head[..n]).contains("STRUCTURED_POINTS")
        }
        _ => false,
    };
    if !image_data {
        return None;
    }
    match tetray_io::vtk::read_image_grid(path) {
        Ok(image) => Some(GridVolume {
            dims: image.dims,
            origin: (DVec3::from(image.origin) - origin).as_vec3(),
            spacing: DVec3::from(image.spacing).as_vec3(),
            fields: image
                .fields
                .into_iter()
                .map(|f| (f.name, f.values))
                .collect(),
        }),
        Err(e) => {
            eprintln!("warning: {e}: shear-warp is not available in the viewer");
            None
        }
    }
}

fn parse_image_scale(text: &str) -> Result<f32, String> {
    let v = parse_positive(text)?;
    if v <= 2.0 {
        Ok(v)
    } else {
        Err(format!("{v} is outside (0, 2]"))
    }
}

fn parse_alpha(text: &str) -> Result<f32, String> {
    let v = parse_positive(text)?;
    if v <= 1.0 {
        Ok(v)
    } else {
        Err(format!(
            "{v} is outside (0, 1] (1 disables early termination)"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::super::args::MeshArgs;
    use super::super::scene::load_mesh;
    use super::*;
    use tetray_mesh::mean_tet_chord;

    /// The viewer derives the unit distance and the tables' length as
    /// `render` does, so the same flags give the same image.
    #[test]
    fn the_viewer_defaults_match_render() {
        let input = load_mesh(&MeshArgs::default()).expect("embedded dataset");
        let unit = input.paraview_unit_distance();
        let chord = mean_tet_chord(&input.loaded.mesh);
        let dataset = Dataset::from_loaded(input.name, input.loaded);
        assert_eq!(dataset.unit_distance, unit);
        assert_eq!(dataset.chord, chord);
    }

    #[test]
    fn scales_outside_their_ranges_are_refused() {
        assert_eq!(parse_image_scale("0.5"), Ok(0.5));
        assert!(parse_image_scale("3").is_err());
        assert!(parse_image_scale("0").is_err());
        assert!(parse_alpha("1.5").is_err());
        assert_eq!(parse_alpha("0.95"), Ok(0.95));
    }
}
