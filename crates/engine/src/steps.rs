//! A file's time steps rendered one after another (`tetray animate`, the
//! viewer's time slider, Python's frames). A step is read as the reader
//! makes it; when its points, tetrahedra and cells are those of the step
//! the setup was made from, bit for bit as read, only its fields are
//! taken ([`Setup::take_fields`]): no topology, no BVH, no walk records,
//! and under a fixed colour range no integrator. A step whose mesh
//! differs is made anew, keeping the camera, so that the view holds still
//! over the animation; when only its points moved, it takes the topology
//! of the step before (from the second such step on).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glam::{DVec3, Vec3};
use tetray_core::Camera;
use tetray_io::LoadOptions;
use tetray_mesh::{KnownTopology, MeshRead, default_field, finish_reusing, value_range};

use crate::error::{EngineError, bail};
use crate::options::{FrameOptions, Log, Representation};
use crate::prepare::prepare;
use crate::setup::{Setup, prepare_mesh};
use crate::source::{MeshInput, Source, check_file};

/// The time steps of one file.
pub struct TimeSteps {
    path: PathBuf,
    options: LoadOptions,
    /// The step the last setup was made from, as read.
    held: Option<Geometry>,
    /// Once a step's points have moved over the same cells: the last
    /// step's finished tetrahedra and topology, which the next such step
    /// takes instead of building its own.
    known: Option<KnownTopology>,
}

/// What a step's setup cost to make.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepCost {
    /// Reading the file (and, for a step made from scratch, orienting,
    /// validating and building the topology).
    pub load: Duration,
    /// The scene: taking the fields, or building it.
    pub scene: Duration,
    /// Whether the setup before was kept and only the fields taken.
    pub kept: bool,
    /// For a step made anew: whether its points moved over the same
    /// tetrahedra, whose topology it took from the step before.
    pub topology_kept: bool,
}

/// A step's mesh as read, before anything is left out or oriented: what
/// decides whether two steps share their scene.
struct Geometry {
    points: Vec<Vec3>,
    tets: Vec<[u32; 4]>,
    tet_cells: Vec<u32>,
    origin: DVec3,
}

impl Geometry {
    fn of(read: &MeshRead) -> Geometry {
        Geometry {
            points: read.mesh.points.clone(),
            tets: read.mesh.tets.clone(),
            tet_cells: read.tet_cells.clone(),
            origin: read.origin,
        }
    }

    /// The same cells (the points may differ).
    fn has_cells_of(&self, read: &MeshRead) -> bool {
        self.tets == read.mesh.tets && self.tet_cells == read.tet_cells
    }

    fn is_of(&self, read: &MeshRead) -> bool {
        let bits = |p: &Vec3| p.to_array().map(f32::to_bits);
        self.origin.to_array().map(f64::to_bits) == read.origin.to_array().map(f64::to_bits)
            && self.has_cells_of(read)
            && self.points.len() == read.mesh.points.len()
            && self
                .points
                .iter()
                .zip(&read.mesh.points)
                .all(|(a, b)| bits(a) == bits(b))
    }
}

impl TimeSteps {
    /// The steps of the file at `path`, read with `options` (their time
    /// step or time choose the step when none is given).
    pub fn new(path: impl Into<PathBuf>, options: LoadOptions) -> TimeSteps {
        TimeSteps {
            path: path.into(),
            options,
            held: None,
            known: None,
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The times the file stores (none for a file of one step).
    pub fn times(&self) -> Result<Vec<f64>, EngineError> {
        Ok(self.read(None)?.times)
    }

    /// The setup of `step` (`None`: the file's default step), made from
    /// scratch.
    pub fn prepare(
        &mut self,
        step: Option<usize>,
        options: &FrameOptions,
        log: Log<'_>,
    ) -> Result<Setup, EngineError> {
        self.held = None;
        self.known = None;
        let grid = match options.representation {
            Representation::Tetrahedra => false,
            Representation::Grid => true,
            Representation::Both => Source::file(&self.path).is_image_data()?,
        };
        if grid {
            // A regular grid is read whole for each step.
            let source = Source::File {
                path: self.path.clone(),
                options: self.step_options(step),
            };
            return prepare(source, options, log);
        }
        let input = self.load(step)?;
        prepare_mesh(input, None, options, log)
    }

    /// The tetrahedra of `step` (`None`: the step the options choose),
    /// loaded as [`crate::load`] loads them; their mesh as read is held
    /// for the next [`TimeSteps::advance`] when the file has several steps.
    pub fn load(&mut self, step: Option<usize>) -> Result<MeshInput, EngineError> {
        let start = Instant::now();
        self.held = None;
        self.known = None;
        let read = self.read(step)?;
        self.input(read, start).map(|(input, _)| input)
    }

    /// Moves `setup` (made by [`TimeSteps::prepare`] or this) to `step`:
    /// only the fields when the step's mesh is the one held, else a new
    /// setup with the same camera.
    pub fn advance(
        &mut self,
        setup: &mut Setup,
        step: usize,
        options: &FrameOptions,
        log: Log<'_>,
    ) -> Result<StepCost, EngineError> {
        let start = Instant::now();
        let options = &same_view_options(setup, options);
        if self.held.is_none() {
            let before = View::of(setup);
            *setup = self.prepare(Some(step), options, log)?;
            before.keep(setup);
            return Ok(cost(setup, false));
        }
        let read = self.read(Some(step))?;
        if self.held.as_ref().is_some_and(|held| held.is_of(&read)) {
            let file = self.path.display().to_string();
            tetray_mesh::check_input(&read.mesh)
                .map_err(|e| tetray_io::IoError::from(e.in_file(&file)))?;
            let load = start.elapsed();
            let start = Instant::now();
            setup.take_fields(read.mesh.fields, log)?;
            setup.load_time = load;
            setup.scene_time = start.elapsed();
            return Ok(cost(setup, true));
        }
        let before = View::of(setup);
        let (input, topology_kept) = self.input(read, start)?;
        *setup = prepare_mesh(input, None, options, log)?;
        before.keep(setup);
        Ok(StepCost {
            topology_kept,
            ..cost(setup, false)
        })
    }

    /// The range of the field `name` (default: the one the first step
    /// renders) over `steps`, ParaView's "rescale over all time steps";
    /// `None` for a field constant over every step.
    pub fn range(
        &self,
        steps: &[usize],
        name: Option<&str>,
    ) -> Result<Option<(f32, f32)>, EngineError> {
        let mut name = name.map(str::to_string);
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for &step in steps {
            let read = self.read(Some(step))?;
            let name = name.get_or_insert_with(|| {
                default_field(&read.mesh).map_or(String::new(), |f| f.name.clone())
            });
            let Some(field) = read.mesh.fields.iter().find(|f| &f.name == name) else {
                bail!("{}: step {step} has no field {name:?}", self.path.display());
            };
            let (a, b) = value_range(&field.values);
            lo = lo.min(a);
            hi = hi.max(b);
        }
        Ok((lo < hi).then_some((lo, hi)))
    }

    /// The options, with `step` when one is given.
    fn step_options(&self, step: Option<usize>) -> LoadOptions {
        match step {
            Some(step) => LoadOptions {
                time_step: Some(step),
                time: None,
                ..self.options.clone()
            },
            None => self.options.clone(),
        }
    }

    fn read(&self, step: Option<usize>) -> Result<MeshRead, EngineError> {
        check_file(&self.path)?;
        Ok(tetray_io::read_file(&self.path, &self.step_options(step))?)
    }

    /// The input of `read`, with the topology of the step before when its
    /// points moved over the same cells (then `true`).
    fn input(&mut self, read: MeshRead, start: Instant) -> Result<(MeshInput, bool), EngineError> {
        let several = read.times.len() > 1;
        let moved = self.held.as_ref().is_some_and(|h| h.has_cells_of(&read));
        let geometry = several.then(|| Geometry::of(&read));
        let file = self.path.display().to_string();
        let known = self.known.take().filter(|_| moved);
        let loaded = finish_reusing(read, known.as_ref())
            .map_err(|e| tetray_io::IoError::from(e.in_file(&file)))?;
        let topology_kept = known.is_some_and(|k| k.tets == loaded.mesh.tets);
        // Kept only once points have moved over the same cells: a series
        // whose steps share their mesh never needs it.
        self.known = (several && moved).then(|| KnownTopology {
            tets: loaded.mesh.tets.clone(),
            topology: loaded.topology.clone(),
        });
        self.held = geometry;
        let input = MeshInput {
            name: file,
            loaded,
            load_time: start.elapsed(),
        };
        Ok((input, topology_kept))
    }
}

/// `options` with the opacity unit distance of `setup` (the first step's
/// default when none was given): a step made anew keeps it, as it keeps the
/// colour range, so that opacity means the same in every frame.
fn same_view_options(setup: &Setup, options: &FrameOptions) -> FrameOptions {
    let mut options = options.clone();
    options
        .integrator
        .unit_distance
        .get_or_insert(setup.unit_distance);
    options
}

/// The camera of a setup, in the file's coordinates.
struct View {
    camera: Camera,
    origin: DVec3,
}

impl View {
    fn of(setup: &Setup) -> View {
        View {
            camera: setup.camera,
            origin: setup.extent.origin,
        }
    }

    /// Puts the camera in `setup`, moved to its origin (a moving mesh far
    /// from the file's origin is stored relative to each step's centre).
    fn keep(self, setup: &mut Setup) {
        let shift = (self.origin - setup.extent.origin).as_vec3();
        setup.camera = Camera {
            position: self.camera.position + shift,
            focal_point: self.camera.focal_point + shift,
            ..self.camera
        };
    }
}

fn cost(setup: &Setup, kept: bool) -> StepCost {
    StepCost {
        load: setup.load_time,
        scene: setup.scene_time,
        kept,
        topology_kept: false,
    }
}
