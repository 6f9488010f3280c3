//! Image data as the regular grid it is, for shear-warp: read alone (no
//! tetrahedra, topology or BVH) when only shear-warp renders, with the
//! field, transfer function, unit distance, camera and opacity mode the
//! tetrahedral renderers would take, so that the same options give the
//! same view. The Riemann sum post-classifies (the front sample constant
//! over each slab); every other method pre-integrates with the full table.

use std::time::Instant;

use glam::{DVec3, Vec3};
use tetray_core::{Camera, WalkCounters};
use tetray_integrate::{Method, OpacityMode, TransferFunction};
use tetray_io::ImageGrid;
use tetray_mesh::{centring_origin, default_field_of, mean_tet_chord};
use tetray_shearwarp::{Classification, ClassifyOptions, RegularGrid, ShearWarp, ShearWarpOptions};

use crate::error::{Context, EngineError, bail};
use crate::fields::{SOLID, unknown_field};
use crate::frame::{Frame, FrameStats};
use crate::options::{FrameOptions, Log};
use crate::setup::{Extent, Setup, Volume};
use crate::source::{Source, check_file, plural};

/// Reads the image data of `source` as its regular grid alone and makes
/// the camera, transfer function and integrator options as
/// [`crate::prepare`] would for its tetrahedra: ParaView's unit distance
/// from the grid's cells, the first varying field, the bounds fit.
pub(crate) fn prepare_grid(
    source: Source,
    options: &FrameOptions,
    log: Log<'_>,
) -> Result<Setup, EngineError> {
    let start = Instant::now();
    let (path, load) = match &source {
        Source::File {
            path,
            options: load,
        } => {
            if load.plot3d_q.is_some() || load.block.is_some() {
                bail!(
                    "{}: a PLOT3D solution or a block do not apply to a regular grid (a .vti, \
                     STRUCTURED_POINTS or VTKHDF ImageData file)",
                    path.display()
                );
            }
            (path, load)
        }
        _ => bail!("{}", not_image_data(&source.name())),
    };
    check_file(path)?;
    let name = path.display().to_string();
    let mut image = tetray_io::load_image_grid(path, load)
        .with_context(|| format!("{name}: shear-warp needs a uniform grid"))?;
    let load_time = start.elapsed();
    for warning in &image.warnings {
        (log.warn)(warning.clone());
    }
    let [nx, ny, nz] = image.dims;
    let cells = (nx - 1) * (ny - 1) * (nz - 1);
    (log.info)(format!(
        "loaded {name} as its regular grid (no tetrahedra): {nx}x{ny}x{nz} points, {cells} \
         cells, {} point field{} in {:.3} s",
        image.fields.len(),
        plural(image.fields.len()),
        load_time.as_secs_f64()
    ));
    let scene_start = Instant::now();
    let field = match &options.integrator.scalar {
        Some(wanted) if image.fields.iter().any(|f| &f.name == wanted) => wanted.clone(),
        Some(wanted) => return Err(unknown_field(wanted, &name, &image.fields)),
        None => match default_field_of(&image.fields) {
            Some(f) => f.name.clone(),
            None => {
                (log.warn)(format!(
                    "{name} has no point scalar field: rendering it as a uniform volume"
                ));
                image.fields.push(tetray_mesh::ScalarField {
                    name: SOLID.into(),
                    values: vec![0.0; nx * ny * nz],
                });
                SOLID.to_string()
            }
        },
    };
    let lo = DVec3::from(image.origin);
    let spacing = DVec3::from(image.spacing);
    let hi = lo + spacing * DVec3::new((nx - 1) as f64, (ny - 1) as f64, (nz - 1) as f64);
    let origin = centring_origin(lo, hi);
    let grid = regular_grid(&image, &field, origin)
        .with_context(|| format!("{name}: not a grid shear-warp can render"))?;
    let scene_time = scene_start.elapsed();
    // One cell split as the tetrahedral readers split it: their mean chord.
    let cell = RegularGrid::new([2; 3], Vec3::ZERO, spacing.as_vec3(), vec![0.0; 8])
        .context("a grid cell")?;
    let extent = Extent {
        name,
        origin,
        bounds: grid.bounds(),
        field,
        range: grid.value_range(),
        // ParaView's default (see `LoadedMesh::paraview_unit_distance`).
        paraview_unit_distance: tetray_core::defaults::unit_distance(
            (hi - lo).length(),
            cells as f64,
        ),
        mean_chord: mean_tet_chord(&cell.to_tet_mesh("cell")),
    };
    let volume = Volume::ImageData {
        image,
        tetrahedra: None,
    };
    Setup::new(volume, extent, options, log, (load_time, scene_time))
}

/// The regular grid of `image` with `field` as its values, its points
/// relative to `origin`.
fn regular_grid(image: &ImageGrid, field: &str, origin: DVec3) -> Result<RegularGrid, EngineError> {
    let values = match image.fields.iter().find(|f| f.name == field) {
        Some(f) => f.values.clone(),
        None => return Err(unknown_field(field, "the image", &image.fields)),
    };
    let corner = (DVec3::from(image.origin) - origin).as_vec3();
    let spacing = DVec3::from(image.spacing).as_vec3();
    RegularGrid::new(image.dims, corner, spacing, values)
        .context("not a grid shear-warp can render")
}

fn not_image_data(name: &str) -> String {
    format!(
        "{name} is not image data: shear-warp renders regular grids (.vti or legacy \
         STRUCTURED_POINTS files)"
    )
}

impl Setup {
    /// The regular grid with the active field, when the volume is image
    /// data.
    pub fn regular_grid(&self) -> Result<RegularGrid, EngineError> {
        match self.image() {
            Some(image) => regular_grid(image, &self.extent.field, self.extent.origin)
                .with_context(|| self.extent.name.clone()),
            None => bail!("{}", not_image_data(&self.extent.name)),
        }
    }

    /// Shear-warp of the regular grid, classified for `method` with `tf`,
    /// the unit distance and the opacity mode (the setup's own for
    /// [`crate::Engine`]; a viewer's edits for its views).
    pub fn shear_warp(
        &self,
        method: Method,
        tf: &TransferFunction,
        unit_distance: f32,
        opacity_mode: OpacityMode,
    ) -> Result<ShearWarp, EngineError> {
        let options = ClassifyOptions {
            classification: Classification::for_method(method),
            unit_distance,
            opacity_mode,
            table_size: self.integrator_options.preintegration_table_size,
        };
        let sw = ShearWarp::new(self.regular_grid()?, tf, &options)
            .context("classifying for shear-warp")?;
        sw.prepare_all_axes();
        Ok(sw)
    }
}

/// One line: what shear-warp renders.
pub(crate) fn describe(sw: &ShearWarp) -> String {
    let [nx, ny, nz] = sw.grid().dims();
    format!(
        "renderer: shear-warp, {}, on the {nx}x{ny}x{nz} grid{}",
        sw.classification().name(),
        sw.table()
            .map(|t| format!(" (table {0}x{0} at length {1})", t.size(), t.length()))
            .unwrap_or_default()
    )
}

/// One frame; empty space is always skipped (it never changes the image).
pub(crate) fn render(
    sw: &ShearWarp,
    camera: &Camera,
    early_termination: f32,
    (width, height): (u32, u32),
) -> Result<Frame, EngineError> {
    let options = ShearWarpOptions {
        width,
        height,
        early_termination,
        skip_empty: true,
    };
    let out = sw.render(camera, &options).context("shear-warp")?;
    Ok(Frame {
        stats: FrameStats {
            counters: WalkCounters::of_image(&out.image, out.stats.slabs_composited, 0),
            elapsed: out.stats.elapsed,
            ..FrameStats::default()
        },
        image: out.image,
    })
}
