//! From a loaded mesh and options to what the renderers need: the scene
//! (topology, boundary BVH, active scalar), the camera, the transfer
//! function and the integrator, as [`Setup`].

use std::time::{Duration, Instant};

use glam::{DVec3, Vec3};
use tetray_boundary_bvh::BuildPreset;
use tetray_core::{relative_to_origin, Camera};
use tetray_integrate::{
    ColorPoint, IntegratorOptions, Method, OpacityMode, OpacityPoint, ScalarIntegrator,
    TransferFunction,
};
use tetray_mesh::{default_field, mean_tet_chord, value_range, ScalarField};
use tetray_scene::Scene;

use crate::error::{bail, Context, FrameError};
use crate::mesh::MeshInput;
use crate::options::{bvh_preset_for, CameraOptions, IntegratorChoice, Log, TfSource};

/// What [`prepare`] makes a frame of, besides the mesh.
#[derive(Debug, Clone)]
pub struct FrameOptions {
    pub integrator: IntegratorChoice,
    pub camera: CameraOptions,
    /// `None`: see [`bvh_preset_for`].
    pub bvh_preset: Option<BuildPreset>,
    /// Width and height in pixels (the camera's fit depends on the aspect).
    pub size: (u32, u32),
}

/// Everything a frame needs, and how long each part took to make.
pub struct Setup {
    pub mesh_name: String,
    /// The tetrahedra, their topology, boundary BVH and active field;
    /// `None` when only shear-warp renders (the file read as its regular
    /// grid alone, see [`crate::shear_warp::prepare_grid`]).
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
    pub fn scene(&self) -> Result<&Scene, FrameError> {
        self.scene.as_ref().ok_or_else(|| {
            FrameError::Options(
                "the file was read as a regular grid only (for --renderer shear-warp): no \
                 tetrahedra"
                    .into(),
            )
        })
    }

    /// Tetrahedra in the scene (0 for a regular grid read alone).
    pub fn tet_count(&self) -> usize {
        self.scene.as_ref().map_or(0, Scene::tet_count)
    }

    /// Switches to `method` with the same transfer function and options.
    pub fn use_method(&mut self, method: Method) -> Result<(), FrameError> {
        if method != self.method {
            self.integrator = ScalarIntegrator::new(method, &self.tf, &self.integrator_options)
                .with_context(|| format!("setting up the {method} integrator"))?;
            self.integrator_time = self.integrator.setup_time();
            self.method = method;
        }
        Ok(())
    }

    /// The camera of `options` for this scene at `size`.
    pub fn camera_for(
        &self,
        options: &CameraOptions,
        size: (u32, u32),
    ) -> Result<Camera, FrameError> {
        let bounds = match (&self.scene, &self.grid) {
            (Some(scene), _) => scene.bounds(),
            (None, Some(grid)) => grid.bounds(),
            (None, None) => bail!("no scene to fit the camera to"),
        };
        build_camera(options, bounds, size, self.origin)
    }
}

/// The name of the field added to a mesh without fields.
pub const SOLID: &str = "solid";

/// Builds the scene of `input`, the camera (before the integrator's
/// tables, so a bad camera fails fast) and the integrator, reporting each
/// step through `log`. `tf` must already be read (so a bad path fails
/// before a long load).
pub fn prepare(
    input: MeshInput,
    options: &FrameOptions,
    log: Log<'_>,
) -> Result<Setup, FrameError> {
    let args = &options.integrator;
    (log.info)(input.describe());
    if let Some(changes) = input.loaded.report.changes() {
        (log.info)(changes);
    }
    let origin = input.loaded.origin();
    for warning in &input.loaded.report.warnings {
        (log.warn)(warning.clone());
    }
    let field = pick_field(&input, args.scalar.as_deref())?;
    let paraview_u = input.paraview_unit_distance();
    let MeshInput {
        name,
        mut loaded,
        load_time,
    } = input;
    let field = field.unwrap_or_else(|| {
        (log.warn)(format!(
            "{name} has no point scalar field (for PLOT3D, give the solution file with \
             --q): rendering it as a uniform volume"
        ));
        loaded.mesh.fields.push(ScalarField {
            name: SOLID.into(),
            values: vec![0.0; loaded.mesh.points.len()],
        });
        SOLID.to_string()
    });

    let start = Instant::now();
    let preset = bvh_preset_for(options.bvh_preset, loaded.topology.boundary_faces.len());
    let scene = Scene::new(loaded.mesh, loaded.topology, &field, preset)
        .with_context(|| format!("{name}: preparing the mesh for ray casting"))?;
    let scene_time = start.elapsed();
    let bvh = scene.bvh.stats();
    (log.info)(format!(
        "boundary BVH ({}): {} faces, {} nodes, depth {}, built in {:.3} s (scene ready in {:.3} s)",
        bvh.preset,
        bvh.faces,
        bvh.nodes,
        bvh.max_depth,
        bvh.build_time.as_secs_f64(),
        scene_time.as_secs_f64()
    ));

    let camera = build_camera(&options.camera, scene.bounds(), options.size, origin)?;
    warn_if_inside(&camera, scene.bounds(), log);

    let (lo, hi) = value_range(&scene.scalar);
    let unit_distance = args.unit_distance.unwrap_or(paraview_u);
    let tf = transfer_function(args, &field, (lo, hi), scene.bounds(), unit_distance, log)?;
    let chord = mean_tet_chord(&scene.mesh);
    let integrator_options = integrator_options(args, unit_distance, chord, (lo, hi));
    let (integrator, integrator_time) = integrator(args, &tf, &integrator_options, &field, log)?;
    Ok(Setup {
        mesh_name: name,
        scene: Some(scene),
        grid: None,
        origin,
        camera,
        integrator,
        method: args.method,
        tf,
        integrator_options,
        unit_distance,
        load_time,
        scene_time,
        integrator_time,
    })
}

/// The transfer function: a ParaView preset (rescaled to the field's range
/// `(lo, hi)` unless asked not to), normalized control points mapped onto
/// their range, a uniform volume for a constant field (whose opacity lets
/// 30% of the light through the `bounds` diagonal), else the default ramp
/// over the range.
pub fn transfer_function(
    args: &IntegratorChoice,
    field: &str,
    (lo, hi): (f32, f32),
    bounds: (Vec3, Vec3),
    unit_distance: f32,
    log: Log<'_>,
) -> Result<TransferFunction, FrameError> {
    match &args.tf {
        TfSource::ParaView {
            text,
            name,
            rescale,
            label,
        } => {
            let rescale = rescale.then_some((lo, hi));
            return TransferFunction::from_paraview_json(text, name.as_deref(), rescale)
                .context(label.clone());
        }
        TfSource::Normalized {
            color,
            opacity,
            range: Some(range),
        } => return normalized(color, opacity, *range),
        TfSource::Normalized { color, opacity, .. } if lo < hi => {
            return normalized(color, opacity, (lo, hi))
        }
        _ => {}
    }
    // A constant field (the Oxygen Post's density is 1 everywhere) would
    // get no opacity from the default ramp: an empty image.
    if lo == hi {
        let (lo_b, hi_b) = bounds;
        let unit_lengths = (hi_b - lo_b).length() / unit_distance;
        let alpha = solid_alpha(unit_lengths);
        if field != SOLID {
            (log.warn)(format!(
                "field {field:?} is constant ({lo}): rendering a uniform volume (ParaView's \
                 Solid Color) of opacity {alpha} per unit distance; pick another field with \
                 --scalar (`tetray info` lists them)"
            ));
        }
        return Ok(solid_color(lo, alpha));
    }
    Ok(TransferFunction::default_for_range(lo, hi))
}

/// Points over [0, 1] mapped onto `[lo, hi]`; none at all: the default
/// ramp over `[lo, hi]`.
fn normalized(
    color: &[ColorPoint],
    opacity: &[OpacityPoint],
    (lo, hi): (f32, f32),
) -> Result<TransferFunction, FrameError> {
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        bail!("the colour range must be two finite numbers, low < high; got ({lo}, {hi})");
    }
    if color.is_empty() && opacity.is_empty() {
        return Ok(TransferFunction::default_for_range(lo, hi));
    }
    let at = |s: f32| lo + s * (hi - lo);
    let color = color
        .iter()
        .map(|p| ColorPoint {
            scalar: at(p.scalar),
            rgb: p.rgb,
        })
        .collect();
    let opacity = opacity
        .iter()
        .map(|p| OpacityPoint {
            scalar: at(p.scalar),
            alpha: p.alpha,
        })
        .collect();
    TransferFunction::new(color, opacity).context("the transfer function")
}

/// The integrator's options; `chord` is the typical segment (a
/// tetrahedron's mean chord).
pub fn integrator_options(
    args: &IntegratorChoice,
    unit_distance: f32,
    chord: f32,
    (lo, hi): (f32, f32),
) -> IntegratorOptions {
    IntegratorOptions {
        unit_distance,
        opacity_mode: args.opacity_mode,
        psi_table_size: args.psi_size,
        riemann_step: args.riemann_step.unwrap_or(chord / 4.0),
        preintegration_table_size: args.preintegration_size,
        // The table is exact at this length and corrected for others: the
        // typical segment, a tetrahedron's mean chord.
        preintegration_length: chord,
        scalar_range: Some((lo, hi)),
        split_at_knots: args.knot_split,
        ..IntegratorOptions::default()
    }
}

/// The integrator of `tf` and `options`, logged, and its setup time.
pub fn integrator(
    args: &IntegratorChoice,
    tf: &TransferFunction,
    options: &IntegratorOptions,
    field: &str,
    log: Log<'_>,
) -> Result<(ScalarIntegrator, Duration), FrameError> {
    let method = args.method;
    let integrator = ScalarIntegrator::new(method, tf, options)
        .with_context(|| format!("setting up the {method} integrator"))?;
    let integrator_time = integrator.setup_time();
    let source = if args.unit_distance.is_some() {
        "given"
    } else {
        "ParaView's default"
    };
    let (lo, hi) = options.scalar_range.unwrap_or((0.0, 0.0));
    (log.info)(format!(
        "integrator {method}{}: {field} in [{lo}, {hi}], unit distance {} ({source}), \
         opacity mode {}, set up in {:.3} s",
        table_note(&integrator, options),
        options.unit_distance,
        opacity_mode_name(args.opacity_mode),
        integrator_time.as_secs_f64()
    ));
    Ok((integrator, integrator_time))
}

/// "exact" or "vtk", as the CLI's `--opacity-mode` spells them.
pub fn opacity_mode_name(mode: OpacityMode) -> &'static str {
    match mode {
        OpacityMode::Exact => "exact",
        OpacityMode::Vtk => "vtk",
    }
}

/// The field to render: the one named, else the first that is not constant
/// (see [`default_field`]); `None` for a mesh without fields.
fn pick_field(input: &MeshInput, scalar: Option<&str>) -> Result<Option<String>, FrameError> {
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
/// camera value is given) and OrthogonalizeViewUp. A given position and
/// focal point are in the file's coordinates: the mesh's `origin` is
/// subtracted (in f64).
pub fn build_camera(
    args: &CameraOptions,
    (lo, hi): (Vec3, Vec3),
    (width, height): (u32, u32),
    origin: DVec3,
) -> Result<Camera, FrameError> {
    if width == 0 || height == 0 {
        bail!("the image size must be at least 1x1, got {width}x{height}");
    }
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
pub fn warn_if_inside(camera: &Camera, (lo, hi): (Vec3, Vec3), log: Log<'_>) {
    if camera.is_inside_bounds(lo, hi) {
        let p = camera.position;
        (log.warn)(format!(
            "the camera at {},{},{} is inside the mesh bounds; rendering from the eye",
            p.x, p.y, p.z
        ));
    }
}
