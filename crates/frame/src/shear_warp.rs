//! `--renderer shear-warp`: a `.vti` / STRUCTURED_POINTS file read as the
//! regular grid it is and rendered by `tetray-shearwarp` with the field,
//! transfer function, unit distance, camera and opacity mode the
//! tetrahedral renderers would take, so that the same flags give the same
//! view. `render` and `bench` read the grid alone ([`prepare_grid`]: no
//! tetrahedra, topology or BVH); `compare`, whose reference is the
//! tetrahedral ray caster, reads the file again as a grid for each
//! shear-warp method. `--integrator riemann` post-classifies (the seed's
//! baseline: the front sample constant over each slab); every other
//! integrator pre-integrates with the full table.

use std::path::Path;
use std::time::Instant;

use glam::{DVec3, Vec3};
use tetray_core::Camera;
use tetray_integrate::Method;
use tetray_io::vtk::ImageGrid;
use tetray_mesh::{centring_origin, mean_tet_chord};
use tetray_shearwarp::{Classification, ClassifyOptions, RegularGrid, ShearWarp, ShearWarpOptions};

use crate::engine::{Frame, FrameStats};
use crate::error::{bail, Context, FrameError};
use crate::mesh::{plural, MeshOptions, EMBEDDED_NAME};
use crate::options::Log;
use crate::setup::{self, FrameOptions, Setup, SOLID};

/// The classification `--integrator` asks of shear-warp.
pub fn classification(method: Method) -> Classification {
    Classification::for_method(method)
}

/// Reads the file of `mesh` as its regular grid alone (no tetrahedra, no
/// topology or BVH) and makes the camera, transfer function and integrator
/// options as [`setup::prepare`] would for its tetrahedra: ParaView's unit
/// distance from the grid's cells, the first varying field, the bounds fit.
pub fn prepare_grid(
    mesh: &MeshOptions,
    options: &FrameOptions,
    log: Log<'_>,
) -> Result<Setup, FrameError> {
    let (args, camera_args, size) = (&options.integrator, &options.camera, options.size);
    let start = Instant::now();
    let Some(path) = mesh.mesh.as_deref() else {
        bail!("{}", not_embedded());
    };
    if !path.is_file() {
        return Err(FrameError::NoSuchFile(path.display().to_string()));
    }
    if mesh.q.is_some() || mesh.time_step.is_some() || mesh.time.is_some() || mesh.block.is_some() {
        bail!(
            "--q, --time-step, --time and --block do not apply to --renderer shear-warp \
             (a .vti or STRUCTURED_POINTS file)"
        );
    }
    let name = path.display().to_string();
    let mut image = read_image(path)?;
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
    let field = pick_field(&image, args.scalar.as_deref(), &name)?;
    let values = match image.fields.iter().position(|f| f.name == field) {
        Some(k) => image.fields.swap_remove(k).values,
        None => {
            (log.warn)(format!(
                "{name} has no point scalar field: rendering it as a uniform volume"
            ));
            vec![0.0; nx * ny * nz]
        }
    };
    let scene_start = Instant::now();
    let lo = DVec3::from(image.origin);
    let spacing = DVec3::from(image.spacing);
    let hi = lo + spacing * DVec3::new((nx - 1) as f64, (ny - 1) as f64, (nz - 1) as f64);
    let origin = centring_origin(lo, hi);
    let grid = RegularGrid::new(
        image.dims,
        (lo - origin).as_vec3(),
        spacing.as_vec3(),
        values,
    )
    .with_context(|| format!("{name}: not a grid shear-warp can render"))?;
    let scene_time = scene_start.elapsed();
    let bounds = grid.bounds();
    let camera = setup::build_camera(camera_args, bounds, size, origin)?;
    setup::warn_if_inside(&camera, bounds, log);
    // ParaView's default (see `LoadedMesh::paraview_unit_distance`).
    let diagonal = (hi - lo).length() / (cells.max(1) as f64).cbrt();
    let paraview_u = if diagonal > 0.0 && diagonal.is_finite() {
        diagonal as f32
    } else {
        1.0
    };
    let unit_distance = args.unit_distance.unwrap_or(paraview_u);
    let range = grid.value_range();
    let tf = setup::transfer_function(args, &field, range, bounds, unit_distance, log)?;
    // One cell split as the tetrahedral readers split it: their mean chord.
    let cell = RegularGrid::new([2; 3], Vec3::ZERO, spacing.as_vec3(), vec![0.0; 8])
        .context("a grid cell")?;
    let chord = mean_tet_chord(&cell.to_tet_mesh("cell"));
    let options = setup::integrator_options(args, unit_distance, chord, range);
    let (integrator, integrator_time) = setup::integrator(args, &tf, &options, &field, log)?;
    Ok(Setup {
        mesh_name: name,
        scene: None,
        grid: Some(grid),
        origin,
        camera,
        integrator,
        method: args.method,
        tf,
        integrator_options: options,
        unit_distance,
        load_time,
        scene_time,
        integrator_time,
    })
}

/// The field to render: the one named, else the first that varies, else
/// the first; [`SOLID`] for a grid without fields.
fn pick_field(image: &ImageGrid, scalar: Option<&str>, name: &str) -> Result<String, FrameError> {
    let fields = &image.fields;
    if let Some(wanted) = scalar {
        if fields.iter().any(|f| f.name == wanted) {
            return Ok(wanted.to_string());
        }
        let names: Vec<String> = fields.iter().map(|f| format!("{:?}", f.name)).collect();
        bail!(
            "--scalar {wanted:?}: {name} has no such point field; it has {}",
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        );
    }
    let varies = |f: &&tetray_mesh::ScalarField| {
        let (lo, hi) = tetray_mesh::value_range(&f.values);
        lo < hi
    };
    Ok(fields
        .iter()
        .find(varies)
        .or_else(|| fields.first())
        .map_or_else(|| SOLID.to_string(), |f| f.name.clone()))
}

fn not_embedded() -> &'static str {
    "--renderer shear-warp renders regular grids (.vti or legacy STRUCTURED_POINTS files); \
     the embedded Blunt Fin is curvilinear"
}

fn read_image(path: &Path) -> Result<ImageGrid, FrameError> {
    tetray_io::vtk::read_image_grid(path).context("--renderer shear-warp needs a uniform grid")
}

/// The setup's regular grid: the one [`prepare_grid`] read, or (where the
/// tetrahedra were loaded for other methods) the file read again as its
/// grid, with the scene's field.
fn grid_of(setup: &Setup) -> Result<RegularGrid, FrameError> {
    if let Some(grid) = &setup.grid {
        return Ok(grid.clone());
    }
    if setup.mesh_name == EMBEDDED_NAME {
        bail!("{}", not_embedded());
    }
    let path = Path::new(&setup.mesh_name);
    let image = read_image(path)?;
    let field = setup.scene()?.field.as_str();
    let values = image
        .fields
        .into_iter()
        .find(|f| f.name == field)
        .map(|f| f.values)
        .ok_or_else(|| {
            FrameError::Options(format!(
                "{}: no point field {field:?} in the image",
                path.display()
            ))
        })?;
    let origin = (DVec3::from(image.origin) - setup.origin).as_vec3();
    let spacing = DVec3::from(image.spacing).as_vec3();
    RegularGrid::new(image.dims, origin, spacing, values)
        .with_context(|| format!("{}: not a grid shear-warp can render", path.display()))
}

/// The setup's regular grid with its transfer function classified.
pub fn engine(setup: &Setup, log: &dyn Fn(String)) -> Result<ShearWarp, FrameError> {
    let grid = grid_of(setup)?;
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
) -> Result<Frame, FrameError> {
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
            counters: tetray_core::WalkCounters {
                rays: u64::from(width) * u64::from(height),
                rays_hit,
                segments: out.stats.slabs_composited,
                ..tetray_core::WalkCounters::default()
            },
            elapsed: out.stats.elapsed,
            ..FrameStats::default()
        },
    })
}
