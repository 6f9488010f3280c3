//! From command-line options to what the renderers need: the loaded mesh,
//! the scene (topology, boundary BVH, active scalar), the integrator and the
//! camera. Shared by `render`, `bench` and `compare`; `info` uses the loader
//! only. With `--renderer shear-warp` the file is read as its regular grid
//! alone instead (`shear_warp::prepare_grid`).

use std::time::{Duration, Instant};

use anyhow::{bail, Context};
use glam::{DVec3, Vec3};
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityPoint, ScalarIntegrator, TransferFunction,
};
use tetray_mesh::{default_field, mean_tet_chord, value_range, LoadedMesh, ScalarField};
use tetray_raycast::{relative_to_origin, Camera, Scene};

use super::args::{CameraArgs, IntegratorArgs, MeshArgs, RendererArg, WalkArgs};

/// The embedded default dataset: NASA's Blunt Fin, PLOT3D big-endian.
const BLUNT_FIN_XYZ: &[u8] = include_bytes!("../../data/plot3d/bluntfinxyz.bin");
const BLUNT_FIN_Q: &[u8] = include_bytes!("../../data/plot3d/bluntfinq.bin");
pub const EMBEDDED_NAME: &str = "embedded Blunt Fin";

/// A mesh as loaded, with what it took.
pub struct MeshInput {
    /// The file name, or [`EMBEDDED_NAME`].
    pub name: String,
    pub loaded: LoadedMesh,
    pub load_time: Duration,
}

impl MeshInput {
    /// Cells of the dataset as read (see [`LoadedMesh::input_cells`]).
    pub fn input_cells(&self) -> usize {
        self.loaded.input_cells()
    }

    /// ParaView's default opacity unit distance (see
    /// [`LoadedMesh::paraview_unit_distance`]).
    pub fn paraview_unit_distance(&self) -> f32 {
        self.loaded.paraview_unit_distance()
    }

    /// One line: what was loaded.
    pub fn describe(&self) -> String {
        let (mesh, report) = (&self.loaded.mesh, &self.loaded.report);
        let split = if report.cells_split > 0 {
            let per_type: Vec<String> = report
                .subdivided
                .iter()
                .map(|s| format!("{} {} (type {})", s.cells, s.name, s.type_id))
                .collect();
            let detail = if per_type.is_empty() {
                String::new()
            } else {
                format!(
                    ", among them {}; {} points added",
                    per_type.join(", "),
                    report.points_added
                )
            };
            format!(
                " ({} cells split into {}{detail})",
                report.cells_split, report.tets_from_split
            )
        } else {
            String::new()
        };
        let p = &report.pieces;
        let pieces = if p.pieces > 0 {
            format!(
                " from {} pieces ({} points welded, {} ghost cells dropped)",
                p.pieces, p.welded_points, p.ghost_cells_dropped
            )
        } else {
            String::new()
        };
        format!(
            "loaded {} ({}{pieces}): {} points, {} tetrahedra{split}, {} boundary faces, {} component{} in {:.3} s",
            self.name,
            report.format,
            mesh.points.len(),
            mesh.tets.len(),
            self.loaded.topology.boundary_faces.len(),
            report.validation.components,
            plural(report.validation.components),
            self.load_time.as_secs_f64()
        )
    }
}

/// Loads the mesh the options name, or the embedded default.
pub fn load_mesh(args: &MeshArgs) -> anyhow::Result<MeshInput> {
    let start = Instant::now();
    let (name, loaded) = match &args.mesh {
        None => {
            if args.q.is_some() {
                bail!("--q needs a PLOT3D grid file (the embedded dataset has its own)");
            }
            if args.time_step.is_some() || args.time.is_some() {
                bail!("--time-step and --time need an Exodus II file");
            }
            let loaded =
                tetray_io::load_plot3d_bytes(BLUNT_FIN_XYZ, Some(BLUNT_FIN_Q), EMBEDDED_NAME)?;
            (EMBEDDED_NAME.to_string(), loaded)
        }
        Some(path) => {
            if !path.is_file() {
                bail!("{}: no such file", path.display());
            }
            if let Some(q) = args.q.as_deref().filter(|q| !q.is_file()) {
                bail!("--q {}: no such file", q.display());
            }
            let options = tetray_io::LoadOptions {
                plot3d_q: args.q.clone(),
                time_step: args.time_step,
                time: args.time,
                block: args.block.clone(),
                linearize: args.linearize.into(),
            };
            let loaded = tetray_io::load(path, &options)?;
            let timed = args.time_step.is_some() || args.time.is_some();
            if timed && loaded.report.format != "Exodus II" {
                bail!(
                    "{}: --time-step and --time apply to Exodus II files, this is {}",
                    path.display(),
                    loaded.report.format
                );
            }
            (path.display().to_string(), loaded)
        }
    };
    Ok(MeshInput {
        name,
        loaded,
        load_time: start.elapsed(),
    })
}

/// Everything a frame needs, and how long each part took to make.
pub struct Setup {
    pub mesh_name: String,
    /// The tetrahedra, their topology, boundary BVH and active field;
    /// `None` when only shear-warp renders (the file read as its regular
    /// grid alone, see `shear_warp::prepare_grid`).
    pub scene: Option<Scene>,
    /// The file as its regular grid (points relative to `origin`), when only
    /// shear-warp renders.
    pub grid: Option<tetray_shearwarp::RegularGrid>,
    /// The file's coordinates are `origin + point` (see
    /// [`tetray_mesh::centring_origin`]).
    pub origin: DVec3,
    pub camera: Camera,
    pub integrator: ScalarIntegrator,
    pub method: Method,
    /// What the integrator was made from, to make another method's.
    pub tf: TransferFunction,
    pub integrator_options: IntegratorOptions,
    pub unit_distance: f32,
    pub load_time: Duration,
    pub scene_time: Duration,
    pub integrator_time: Duration,
}

impl Setup {
    /// The tetrahedral scene, which every renderer but shear-warp needs.
    pub fn scene(&self) -> anyhow::Result<&Scene> {
        self.scene.as_ref().context(
            "the file was read as a regular grid only (for --renderer shear-warp): no tetrahedra",
        )
    }

    /// Tetrahedra in the scene (0 for a regular grid read alone).
    pub fn tet_count(&self) -> usize {
        self.scene.as_ref().map_or(0, Scene::tet_count)
    }

    /// Switches to `method` with the same transfer function and options.
    pub fn use_method(&mut self, method: Method) -> anyhow::Result<()> {
        if method != self.method {
            self.integrator = ScalarIntegrator::new(method, &self.tf, &self.integrator_options)
                .with_context(|| format!("setting up the {method} integrator"))?;
            self.integrator_time = self.integrator.setup_time();
            self.method = method;
        }
        Ok(())
    }
}

/// What [`prepare`] makes a frame of.
#[derive(Clone, Copy)]
pub struct FrameArgs<'a> {
    pub mesh: &'a MeshArgs,
    pub integrator: &'a IntegratorArgs,
    pub camera: &'a CameraArgs,
    pub walk: &'a WalkArgs,
    pub size: (u32, u32),
}

/// Loads the mesh, builds the scene, the camera (before the integrator's
/// tables, so a bad camera fails fast) and the integrator, reporting each
/// step through `log` and warnings on stderr.
pub fn prepare(frame: FrameArgs<'_>, log: &dyn Fn(String)) -> anyhow::Result<Setup> {
    let FrameArgs {
        mesh: mesh_args,
        integrator: args,
        camera: camera_args,
        walk,
        size,
    } = frame;
    // Read before the (possibly long) mesh load, so a bad path fails at once.
    let tf_text = match &args.tf {
        Some(path) => Some(
            std::fs::read_to_string(path)
                .with_context(|| format!("--tf {}: cannot read", path.display()))?,
        ),
        None => None,
    };
    if walk.renderer == RendererArg::ShearWarp {
        return super::shear_warp::prepare_grid(frame, tf_text.as_deref(), log);
    }
    let input = load_mesh(mesh_args)?;
    log(input.describe());
    if let Some(changes) = input.loaded.report.changes() {
        log(changes);
    }
    let origin = input.loaded.origin();
    for warning in &input.loaded.report.warnings {
        eprintln!("warning: {warning}");
    }
    let field = pick_field(&input, args.scalar.as_deref())?;
    let paraview_u = input.paraview_unit_distance();
    let MeshInput {
        name,
        mut loaded,
        load_time,
    } = input;
    let field = field.unwrap_or_else(|| {
        eprintln!(
            "warning: {name} has no point scalar field (for PLOT3D, give the solution file with \
             --q): rendering it as a uniform volume"
        );
        loaded.mesh.fields.push(ScalarField {
            name: SOLID.into(),
            values: vec![0.0; loaded.mesh.points.len()],
        });
        SOLID.to_string()
    });

    let start = Instant::now();
    let preset = super::args::bvh_preset_for(walk.bvh_preset, loaded.topology.boundary_faces.len());
    let scene = Scene::new(loaded.mesh, loaded.topology, &field, preset)
        .with_context(|| format!("{name}: preparing the mesh for ray casting"))?;
    let scene_time = start.elapsed();
    let bvh = scene.bvh.stats();
    log(format!(
        "boundary BVH ({}): {} faces, {} nodes, depth {}, built in {:.3} s (scene ready in {:.3} s)",
        bvh.preset,
        bvh.faces,
        bvh.nodes,
        bvh.max_depth,
        bvh.build_time.as_secs_f64(),
        scene_time.as_secs_f64()
    ));

    let camera = build_camera(camera_args, scene.bounds(), size, origin)?;
    warn_if_inside(&camera, scene.bounds());

    let (lo, hi) = value_range(&scene.scalar);
    let unit_distance = args.unit_distance.unwrap_or(paraview_u);
    let tf = transfer_function(
        args,
        tf_text.as_deref(),
        &field,
        (lo, hi),
        scene.bounds(),
        unit_distance,
    )?;
    let chord = mean_tet_chord(&scene.mesh);
    let options = integrator_options(args, unit_distance, chord, (lo, hi));
    let (integrator, integrator_time) = integrator(args, &tf, &options, &field, log)?;
    Ok(Setup {
        mesh_name: name,
        scene: Some(scene),
        grid: None,
        origin,
        camera,
        integrator,
        method: args.integrator,
        tf,
        integrator_options: options,
        unit_distance,
        load_time,
        scene_time,
        integrator_time,
    })
}

/// The transfer function: the `--tf` file (`tf_text`, rescaled to the
/// field's range `(lo, hi)` unless `--no-rescale`), a uniform volume for a
/// constant field (whose opacity lets 30% of the light through the
/// `bounds` diagonal), else the default ramp over the range.
pub(super) fn transfer_function(
    args: &IntegratorArgs,
    tf_text: Option<&str>,
    field: &str,
    (lo, hi): (f32, f32),
    bounds: (Vec3, Vec3),
    unit_distance: f32,
) -> anyhow::Result<TransferFunction> {
    Ok(match (&args.tf, tf_text) {
        (Some(path), Some(text)) => {
            let rescale = (!args.no_rescale).then_some((lo, hi));
            TransferFunction::from_paraview_json(text, args.tf_name.as_deref(), rescale)
                .with_context(|| format!("--tf {}", path.display()))?
        }
        // A constant field (the Oxygen Post's density is 1 everywhere) would
        // get no opacity from the default ramp: an empty image.
        _ if lo == hi => {
            let (lo_b, hi_b) = bounds;
            let unit_lengths = (hi_b - lo_b).length() / unit_distance;
            let alpha = solid_alpha(unit_lengths);
            if field != SOLID {
                eprintln!(
                    "warning: field {field:?} is constant ({lo}): rendering a uniform volume \
                     (ParaView's Solid Color) of opacity {alpha} per unit distance; pick another \
                     field with --scalar (`tetray info` lists them)"
                );
            }
            solid_color(lo, alpha)
        }
        _ => TransferFunction::default_for_range(lo, hi),
    })
}

/// The integrator's options; `chord` is the typical segment (a
/// tetrahedron's mean chord).
pub(super) fn integrator_options(
    args: &IntegratorArgs,
    unit_distance: f32,
    chord: f32,
    (lo, hi): (f32, f32),
) -> IntegratorOptions {
    IntegratorOptions {
        unit_distance,
        opacity_mode: args.opacity_mode.into(),
        psi_table_size: args.psi_size,
        riemann_step: args.riemann_step.unwrap_or(chord / 4.0),
        preintegration_table_size: args.preintegration_size,
        // The table is exact at this length and corrected for others: the
        // typical segment, a tetrahedron's mean chord.
        preintegration_length: chord,
        scalar_range: Some((lo, hi)),
        split_at_knots: !args.no_knot_split,
        ..IntegratorOptions::default()
    }
}

/// The `--integrator` of `tf` and `options`, logged, and its setup time.
pub(super) fn integrator(
    args: &IntegratorArgs,
    tf: &TransferFunction,
    options: &IntegratorOptions,
    field: &str,
    log: &dyn Fn(String),
) -> anyhow::Result<(ScalarIntegrator, Duration)> {
    let method = args.integrator;
    let integrator = ScalarIntegrator::new(method, tf, options)
        .with_context(|| format!("setting up the {method} integrator"))?;
    let integrator_time = integrator.setup_time();
    let source = if args.unit_distance.is_some() {
        "given"
    } else {
        "ParaView's default"
    };
    let (lo, hi) = options.scalar_range.unwrap_or((0.0, 0.0));
    log(format!(
        "integrator {method}{}: {field} in [{lo}, {hi}], unit distance {} ({source}), \
         opacity mode {}, set up in {:.3} s",
        table_note(&integrator, options),
        options.unit_distance,
        args.opacity_mode.name(),
        integrator_time.as_secs_f64()
    ));
    Ok((integrator, integrator_time))
}

/// The name of the field added to a mesh without fields.
pub(super) const SOLID: &str = "solid";

/// The field to render: the one named, else the first that is not constant
/// (see [`default_field`]); `None` for a mesh without fields.
fn pick_field(input: &MeshInput, scalar: Option<&str>) -> anyhow::Result<Option<String>> {
    let fields = &input.loaded.mesh.fields;
    let names = || {
        fields
            .iter()
            .map(|f| format!("{:?}", f.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match scalar {
        None => Ok(default_field(&input.loaded.mesh).map(|f| f.name.clone())),
        Some(name) if fields.iter().any(|f| f.name == name) => Ok(Some(name.to_string())),
        Some(name) if fields.is_empty() => {
            bail!(
                "--scalar {name:?}: {} has no point scalar field",
                input.name
            )
        }
        Some(name) => bail!(
            "--scalar {name:?}: {} has no such field; it has {}",
            input.name,
            names()
        ),
    }
}

/// Opacity per unit distance of a uniform volume: a ray along the bounds
/// diagonal (`unit_lengths` unit distances long) keeps 30% of the light
/// behind it, so the whole volume shows, translucent.
fn solid_alpha(unit_lengths: f32) -> f32 {
    let n = if unit_lengths.is_finite() && unit_lengths > 0.0 {
        unit_lengths
    } else {
        1.0
    };
    (1.0 - 0.3f32.powf(1.0 / n)).clamp(0.01, 1.0)
}

/// ParaView's "Solid Color": one colour and one opacity for every value.
fn solid_color(value: f32, alpha: f32) -> TransferFunction {
    let gray = Vec3::splat(0.865);
    let color = [value, value + 1.0].map(|scalar| ColorPoint { scalar, rgb: gray });
    let opacity = [value, value + 1.0].map(|scalar| OpacityPoint { scalar, alpha });
    TransferFunction::new(color.to_vec(), opacity.to_vec())
        .expect("a two-point uniform transfer function is valid")
}

fn table_note(integrator: &ScalarIntegrator, options: &IntegratorOptions) -> String {
    if let Some(psi) = integrator.psi_table() {
        format!(" (Psi table {0}x{0})", psi.size())
    } else if integrator.preintegration_table().is_some() {
        format!(
            " (table {0}x{0} at length {1})",
            options.preintegration_table_size, options.preintegration_length
        )
    } else if integrator.method() == Method::Riemann {
        format!(" (step {})", options.riemann_step)
    } else {
        String::new()
    }
}

/// The camera: VTK's ResetCamera fit of `bounds` for a `width x height`
/// image (looking down -z, or along the given position and focal point),
/// the given values, then azimuth, elevation (the oblique default when no
/// camera flag is given) and OrthogonalizeViewUp. A
/// given position and focal point are in the file's coordinates: the
/// mesh's `origin` is subtracted (in f64).
pub(super) fn build_camera(
    args: &CameraArgs,
    (lo, hi): (Vec3, Vec3),
    (width, height): (u32, u32),
    origin: DVec3,
) -> anyhow::Result<Camera> {
    let position = args.camera_position.map(|p| relative_to_origin(p, origin));
    let focal_point = args.focal_point.map(|p| relative_to_origin(p, origin));
    let mut camera = Camera {
        view_angle: args.view_angle,
        parallel_scale: args.parallel_scale,
        ..Camera::default()
    };
    if let Some(up) = args.view_up {
        camera.view_up = up;
    }
    match (position, focal_point) {
        (Some(position), Some(focal_point)) => {
            camera.position = position;
            camera.focal_point = focal_point;
        }
        (position, focal_point) => {
            camera
                .reset(lo, hi, width as f32 / height as f32)
                .context("bad camera: cannot fit the mesh bounds")?;
            if let Some(s) = args.parallel_scale {
                camera.parallel_scale = Some(s);
            }
            if let Some(p) = position {
                camera.position = p;
            }
            if let Some(f) = focal_point {
                camera.focal_point = f;
            }
        }
    }
    camera.basis().context("bad camera")?;
    let (azimuth, elevation) = args.rotation();
    camera.azimuth(azimuth).context("bad camera")?;
    camera.elevation(elevation).context("bad camera")?;
    camera.orthogonalize_view_up().context("bad camera")?;
    Ok(camera)
}

/// Warns when rays start inside the mesh bounds (the renderer integrates
/// from the eye, which is rarely what was meant).
pub(super) fn warn_if_inside(camera: &Camera, (lo, hi): (Vec3, Vec3)) {
    if camera.is_inside_bounds(lo, hi) {
        let p = camera.position;
        eprintln!(
            "warning: the camera at {},{},{} is inside the mesh bounds; rendering from the eye",
            p.x, p.y, p.z
        );
    }
}

/// Sets the size of rayon's global pool, before any parallel work.
pub fn configure_threads(threads: Option<u16>) -> anyhow::Result<()> {
    if let Some(threads) = threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(usize::from(threads))
            .build_global()
            .with_context(|| format!("--threads {threads}: cannot start the thread pool"))?;
    }
    Ok(())
}

pub fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
