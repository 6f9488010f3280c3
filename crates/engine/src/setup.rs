//! From data and options to everything a frame needs ([`Setup`]): the
//! volume (tetrahedra made ready for walking, a regular grid, or both for
//! image data; a process's part of a distributed mesh), the camera, the
//! transfer function and the integrator, with the defaults derived from the
//! whole volume ([`Extent`]).

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::{DVec3, Vec3};
use tetray_core::Camera;
use tetray_integrate::{
    IntegratorOptions, Method, OpacityMode, ScalarIntegrator, TransferFunction,
};
use tetray_io::ImageGrid;
use tetray_mesh::{LoadedMesh, ScalarField, default_field, mean_tet_chord, value_range};
use tetray_scene::Scene;

use crate::camera::{build_camera, warn_if_inside};
use crate::error::{Context, EngineError, bail};
use crate::fields::{SOLID, unknown_field};
use crate::options::{CameraOptions, FrameOptions, IntegratorChoice, Log, bvh_preset_for};
use crate::source::MeshInput;
use crate::tf;

/// What a frame is rendered from.
pub enum Volume {
    /// Tetrahedra with their topology and boundary BVH: every renderer but
    /// shear-warp.
    Tetrahedra(Arc<Scene>),
    /// Image data: its regular grid (every point field, in the file's
    /// coordinates), and its tetrahedra when they were made too.
    ImageData {
        image: ImageGrid,
        tetrahedra: Option<Arc<Scene>>,
    },
    /// This process's part of a mesh split over processes (none: the part
    /// is empty); the frame's defaults come from the whole mesh.
    Part(Option<Arc<Scene>>),
}

/// The whole volume, which the defaults derive from (for a process's part
/// of a distributed mesh: what the processes agreed on).
#[derive(Debug, Clone, PartialEq)]
pub struct Extent {
    pub name: String,
    /// The file's coordinates are `origin + point` (see
    /// [`tetray_mesh::centring_origin`]).
    pub origin: DVec3,
    pub bounds: (Vec3, Vec3),
    /// The active point field and its range.
    pub field: String,
    pub range: (f32, f32),
    /// ParaView's default opacity unit distance.
    pub paraview_unit_distance: f32,
    /// The mean tetrahedron chord: the typical segment, which sizes the
    /// pre-integration table and the Riemann step.
    pub mean_chord: f32,
}

/// Everything a frame needs, and how long each part took to make.
pub struct Setup {
    pub volume: Volume,
    pub extent: Extent,
    pub camera: Camera,
    pub integrator: ScalarIntegrator,
    pub method: Method,
    /// What the integrator was made from, to make another method's.
    pub tf: TransferFunction,
    pub integrator_options: IntegratorOptions,
    pub unit_distance: f32,
    /// The choices the integrator was made from.
    pub choice: IntegratorChoice,
    pub load_time: Duration,
    pub scene_time: Duration,
    pub integrator_time: Duration,
}

/// [`prepare`](crate::prepare()) for a mesh already loaded (with its image
/// grid when it is image data).
pub fn prepare_mesh(
    input: MeshInput,
    image: Option<ImageGrid>,
    options: &FrameOptions,
    log: Log<'_>,
) -> Result<Setup, EngineError> {
    (log.info)(input.describe());
    if let Some(changes) = input.loaded.report.changes() {
        (log.info)(changes);
    }
    for warning in &input.loaded.report.warnings {
        (log.warn)(warning.clone());
    }
    let origin = input.loaded.origin();
    let paraview_unit_distance = input.paraview_unit_distance();
    let field = pick_field(&input, options.integrator.scalar.as_deref())?;
    let MeshInput {
        name,
        mut loaded,
        load_time,
    } = input;
    let field = field.unwrap_or_else(|| {
        (log.warn)(format!(
            "{name} has no point scalar field (for PLOT3D, give the solution file): \
             rendering it as a uniform volume"
        ));
        loaded.mesh.fields.push(ScalarField {
            name: SOLID.into(),
            values: vec![0.0; loaded.mesh.points.len()],
        });
        SOLID.to_string()
    });

    let start = Instant::now();
    let preset = bvh_preset_for(options.bvh_preset, loaded.topology.boundary_faces.len());
    let scene = Scene::from_loaded(loaded, &field, preset)
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
    let extent = Extent {
        name,
        origin,
        bounds: scene.bounds(),
        field,
        range: value_range(&scene.scalar),
        paraview_unit_distance,
        mean_chord: mean_tet_chord(&scene.mesh),
    };
    let scene = Arc::new(scene);
    let volume = match image {
        Some(image) => Volume::ImageData {
            image,
            tetrahedra: Some(scene),
        },
        None => Volume::Tetrahedra(scene),
    };
    Setup::new(volume, extent, options, log, (load_time, scene_time))
}

/// A process's part of a mesh split over processes: its tetrahedra (none:
/// the part is empty) made ready with `extent.field` active (a zero field
/// added when the whole mesh has none, [`SOLID`]), and the frame's defaults
/// from the whole mesh's `extent`.
pub fn prepare_part(
    part: Option<LoadedMesh>,
    extent: Extent,
    options: &FrameOptions,
    log: Log<'_>,
    load_time: Duration,
) -> Result<Setup, EngineError> {
    let start = Instant::now();
    let scene = match part {
        Some(mut l) => {
            if l.mesh.field(&extent.field).is_none() && extent.field == SOLID {
                l.mesh.fields.push(ScalarField {
                    name: SOLID.into(),
                    values: vec![0.0; l.mesh.points.len()],
                });
            }
            let preset = bvh_preset_for(options.bvh_preset, l.topology.boundary_faces.len());
            let scene = Scene::new(l.mesh, l.topology, &extent.field, preset)
                .with_context(|| format!("{}: preparing this process's part", extent.name))?;
            Some(Arc::new(scene))
        }
        None => None,
    };
    let scene_time = start.elapsed();
    Setup::new(
        Volume::Part(scene),
        extent,
        options,
        log,
        (load_time, scene_time),
    )
}

impl Setup {
    /// The camera, transfer function and integrator of `volume` from
    /// `options`, with the defaults of `extent`; `(load, scene)` are the
    /// times it took to make the volume.
    pub fn new(
        volume: Volume,
        extent: Extent,
        options: &FrameOptions,
        log: Log<'_>,
        (load_time, scene_time): (Duration, Duration),
    ) -> Result<Setup, EngineError> {
        let choice = options.integrator.clone();
        let camera = build_camera(&options.camera, extent.bounds, options.size, extent.origin)?;
        warn_if_inside(&camera, extent.bounds, log);
        let unit_distance = choice
            .unit_distance
            .unwrap_or(extent.paraview_unit_distance);
        let Tables {
            tf,
            options: integrator_options,
            integrator,
            time: integrator_time,
        } = tables(&choice, choice.method, &extent, unit_distance, log)?;
        (log.info)(tf::describe_integrator(
            &integrator,
            &integrator_options,
            &extent.field,
            choice.unit_distance.is_some(),
        ));
        Ok(Setup {
            volume,
            camera,
            integrator,
            method: choice.method,
            tf,
            integrator_options,
            unit_distance,
            choice,
            extent,
            load_time,
            scene_time,
            integrator_time,
        })
    }

    /// The data's name (a file name, the embedded dataset's, or the name
    /// in-memory data was given).
    pub fn name(&self) -> &str {
        &self.extent.name
    }

    /// The tetrahedral scene, which every renderer but shear-warp needs.
    pub fn scene(&self) -> Result<&Scene, EngineError> {
        self.scene_arc().map(|s| &**s).ok_or_else(|| {
            EngineError::Options(match &self.volume {
                Volume::Part(None) => "this process's part of the mesh is empty".to_string(),
                _ => format!(
                    "{} was read as its regular grid alone (for shear-warp): no tetrahedra",
                    self.extent.name
                ),
            })
        })
    }

    /// The tetrahedral scene, shared.
    pub fn scene_arc(&self) -> Option<&Arc<Scene>> {
        match &self.volume {
            Volume::Tetrahedra(scene)
            | Volume::ImageData {
                tetrahedra: Some(scene),
                ..
            }
            | Volume::Part(Some(scene)) => Some(scene),
            _ => None,
        }
    }

    /// The regular grid of image data.
    pub fn image(&self) -> Option<&ImageGrid> {
        match &self.volume {
            Volume::ImageData { image, .. } => Some(image),
            _ => None,
        }
    }

    /// Tetrahedra in the scene (0 for a regular grid read alone).
    pub fn tet_count(&self) -> usize {
        self.scene_arc().map_or(0, |s| s.tet_count())
    }

    /// Boundary faces of the scene (0 for a regular grid read alone).
    pub fn boundary_faces(&self) -> usize {
        self.scene_arc()
            .map_or(0, |s| s.topology.boundary_faces.len())
    }

    /// Switches to `method` with the same transfer function and options.
    pub fn use_method(&mut self, method: Method) -> Result<(), EngineError> {
        if method != self.method {
            let (integrator, time) = tf::integrator(method, &self.tf, &self.integrator_options)?;
            self.integrator = integrator;
            self.integrator_time = time;
            self.method = method;
        }
        Ok(())
    }

    /// The camera of `options` for this volume at `size`.
    pub fn camera_for(
        &self,
        options: &CameraOptions,
        size: (u32, u32),
    ) -> Result<Camera, EngineError> {
        build_camera(options, self.extent.bounds, size, self.extent.origin)
    }

    /// The integrator of `method` with `tf`, unit distance and opacity mode,
    /// the tables sized as this setup's (for a front end that edits them).
    pub fn integrator_with(
        &self,
        method: Method,
        tf: &TransferFunction,
        unit_distance: f32,
        opacity_mode: OpacityMode,
    ) -> Result<ScalarIntegrator, EngineError> {
        let choice = IntegratorChoice {
            opacity_mode,
            ..self.choice.clone()
        };
        let options = tf::integrator_options(
            &choice,
            unit_distance,
            self.extent.mean_chord,
            self.choice.tf_range(self.extent.range),
        );
        Ok(tf::integrator(method, tf, &options)?.0)
    }

    /// Makes `field` the active point field: the scene keeps its topology
    /// and BVH, the transfer function is made again for the field's range
    /// from the same choice, and the integrator with it.
    pub fn set_field(&mut self, field: &str, log: Log<'_>) -> Result<(), EngineError> {
        if field == self.extent.field {
            return Ok(());
        }
        let name = &self.extent.name;
        let grid_values = match self.image() {
            Some(image) => match image.fields.iter().find(|f| f.name == field) {
                Some(f) => Some(&f.values),
                None => return Err(unknown_field(field, name, &image.fields)),
            },
            None => None,
        };
        let scene = match self.scene_arc() {
            Some(scene) => Some(
                scene
                    .with_field(field)
                    .with_context(|| format!("{name}: field {field:?}"))?,
            ),
            None => None,
        };
        let range = match (&scene, grid_values) {
            (Some(scene), _) => value_range(&scene.scalar),
            (None, Some(values)) => value_range(values),
            (None, None) => bail!("this process's part of the mesh is empty"),
        };
        let mut extent = self.extent.clone();
        extent.field = field.to_string();
        extent.range = range;
        let tables = tables(&self.choice, self.method, &extent, self.unit_distance, log)?;
        if let (Some(slot), Some(scene)) = (self.scene_slot(), scene) {
            *slot = Arc::new(scene);
        }
        self.extent = extent;
        self.use_tables(tables);
        Ok(())
    }

    /// Takes `fields`, the point fields of another time step of the same
    /// points and tetrahedra (in the numbering they were read in): the
    /// topology, BVH and walk records stay, the transfer function and
    /// integrator are made again for the field's range (kept under a fixed
    /// range). The caller vouches that the geometry is this setup's (see
    /// [`crate::TimeSteps`], which compares it as read). On an error the
    /// setup is unchanged.
    pub fn take_fields(
        &mut self,
        mut fields: Vec<ScalarField>,
        log: Log<'_>,
    ) -> Result<(), EngineError> {
        let name = self.extent.name.clone();
        let field = self.extent.field.clone();
        let Some(points) = self.scene_arc().map(|s| s.mesh.points.len()) else {
            bail!("{name}: a time step's fields need the tetrahedra (this setup has none)");
        };
        if field == SOLID && !fields.iter().any(|f| f.name == SOLID) {
            fields.push(ScalarField {
                name: SOLID.into(),
                values: vec![0.0; points],
            });
        }
        // The tables first: the scene changes last, once nothing can fail.
        let mut extent = self.extent.clone();
        let active = fields.iter().find(|f| f.name == field);
        let tables = match (active, self.choice.range) {
            (Some(active), None) => {
                extent.range = value_range(&active.values);
                Some(tables(
                    &self.choice,
                    self.method,
                    &extent,
                    self.unit_distance,
                    log,
                )?)
            }
            (Some(active), Some(_)) => {
                extent.range = value_range(&active.values);
                None
            }
            (None, _) => None,
        };
        let Some(slot) = self.scene_slot() else {
            unreachable!("the scene was found above");
        };
        match Arc::get_mut(slot) {
            Some(scene) => scene.set_input_fields(fields),
            None => {
                let mut scene = Scene::clone(slot);
                scene
                    .set_input_fields(fields)
                    .map(|()| *slot = Arc::new(scene))
            }
        }
        .with_context(|| format!("{name}: field {field:?}"))?;
        self.extent = extent;
        match tables {
            Some(tables) => self.use_tables(tables),
            // The integrator of the fixed range is kept: nothing was made.
            None => self.integrator_time = Duration::ZERO,
        }
        Ok(())
    }

    fn use_tables(&mut self, tables: Tables) {
        self.tf = tables.tf;
        self.integrator_options = tables.options;
        self.integrator = tables.integrator;
        self.integrator_time = tables.time;
    }

    fn scene_slot(&mut self) -> Option<&mut Arc<Scene>> {
        match &mut self.volume {
            Volume::Tetrahedra(scene)
            | Volume::ImageData {
                tetrahedra: Some(scene),
                ..
            }
            | Volume::Part(Some(scene)) => Some(scene),
            _ => None,
        }
    }
}

/// The field to render: the one named, else the first that varies (see
/// [`default_field`]); `None` for a mesh without fields.
fn pick_field(input: &MeshInput, scalar: Option<&str>) -> Result<Option<String>, EngineError> {
    let fields = &input.loaded.mesh.fields;
    match scalar {
        None => Ok(default_field(&input.loaded.mesh).map(|f| f.name.clone())),
        Some(name) if fields.iter().any(|f| f.name == name) => Ok(Some(name.to_string())),
        Some(name) => Err(unknown_field(name, &input.name, fields)),
    }
}

/// A transfer function and the integrator made with it, and the time it
/// took.
struct Tables {
    tf: TransferFunction,
    options: IntegratorOptions,
    integrator: ScalarIntegrator,
    time: Duration,
}

/// The transfer function of `choice` for `extent`'s field over the range
/// the choice gives for the field's (`IntegratorChoice::tf_range`), and
/// the integrator of `method` with it.
fn tables(
    choice: &IntegratorChoice,
    method: Method,
    extent: &Extent,
    unit_distance: f32,
    log: Log<'_>,
) -> Result<Tables, EngineError> {
    let range = choice.tf_range(extent.range);
    let tf = tf::transfer_function(
        &choice.tf,
        &extent.field,
        range,
        extent.bounds,
        unit_distance,
        log,
    )?;
    let options = tf::integrator_options(choice, unit_distance, extent.mean_chord, range);
    let (integrator, time) = tf::integrator(method, &tf, &options)?;
    Ok(Tables {
        tf,
        options,
        integrator,
        time,
    })
}
