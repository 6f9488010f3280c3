//! `--renderer shear-warp`: the mesh file read again as the regular grid it
//! is (`.vti` / STRUCTURED_POINTS) and rendered by `tetray-shearwarp` with
//! the scene's field, transfer function, unit distance and opacity mode, so
//! that the same flags give the same view as the tetrahedral renderers.
//! `--integrator riemann` post-classifies (the seed's baseline: the front
//! sample constant over each slab); every other integrator pre-integrates
//! with the full table.

use std::path::Path;

use anyhow::{bail, Context};
use glam::Vec3;
use tetray_integrate::Method;
use tetray_raycast::Camera;
use tetray_shearwarp::{Classification, ClassifyOptions, RegularGrid, ShearWarp, ShearWarpOptions};

use super::renderer::{Frame, FrameStats};
use super::scene::{Setup, EMBEDDED_NAME};

/// The classification `--integrator` asks of shear-warp.
pub fn classification(method: Method) -> Classification {
    if method == Method::Riemann {
        Classification::PostClassified
    } else {
        Classification::PreIntegrated
    }
}

/// Reads the setup's file as a regular grid and classifies its transfer
/// function.
pub fn engine(setup: &Setup, log: &dyn Fn(String)) -> anyhow::Result<ShearWarp> {
    if setup.mesh_name == EMBEDDED_NAME {
        bail!(
            "--renderer shear-warp renders regular grids (.vti or legacy STRUCTURED_POINTS \
             files); the embedded Blunt Fin is curvilinear"
        );
    }
    let path = Path::new(&setup.mesh_name);
    let image = tetray_mesh::vtk::read_image_grid(path)
        .with_context(|| "--renderer shear-warp needs a uniform grid")?;
    let field = setup.scene.field.as_str();
    let values = image
        .fields
        .iter()
        .find(|f| f.name == field)
        .map(|f| f.values.clone())
        .with_context(|| format!("{}: no point field {field:?} in the image", path.display()))?;
    let f32s = |v: [f64; 3]| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
    let grid = RegularGrid::new(image.dims, f32s(image.origin), f32s(image.spacing), values)
        .with_context(|| format!("{}: not a grid shear-warp can render", path.display()))?;
    let options = ClassifyOptions {
        classification: classification(setup.method),
        unit_distance: setup.unit_distance,
        opacity_mode: setup.integrator_options.opacity_mode,
        table_size: setup.integrator_options.preintegration_table_size,
    };
    let sw = ShearWarp::new(grid, &setup.tf, &options).context("classifying for shear-warp")?;
    sw.prepare_all_axes();
    let [nx, ny, nz] = sw.grid().dims();
    log(format!(
        "renderer: shear-warp, {}, on the {nx}x{ny}x{nz} grid{}",
        options.classification.name(),
        sw.table()
            .map(|t| format!(" (table {0}x{0} at length {1})", t.size(), t.length()))
            .unwrap_or_default()
    ));
    Ok(sw)
}

/// One frame; empty space is always skipped (it never changes the image).
pub fn render(
    sw: &ShearWarp,
    camera: &Camera,
    early_termination: f32,
    (width, height): (u32, u32),
) -> anyhow::Result<Frame> {
    let options = ShearWarpOptions {
        width,
        height,
        early_termination,
        skip_empty: true,
    };
    let out = sw.render(camera, &options).context("shear-warp")?;
    let rays_hit = out.image.rgba.iter().filter(|p| p[3] > 0.0).count() as u64;
    Ok(Frame {
        image: out.image,
        stats: FrameStats {
            rays: u64::from(width) * u64::from(height),
            rays_hit,
            segments: out.stats.slabs_composited,
            elapsed: out.stats.elapsed,
            ..FrameStats::default()
        },
    })
}
