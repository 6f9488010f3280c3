//! `Scene`: a mesh loaded once (topology, BVH, integrator tables, GPU
//! uploads) and rendered from many cameras.

use std::sync::atomic::AtomicBool;
use std::sync::{Mutex, RwLock};

use glam::Vec3;
use numpy::PyArray3;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use tetray_engine::{
    CameraOptions, Engine, FrameOptions, IntegratorChoice, Log, MeshInput, RendererChoice, Setup,
    Source, TfSource, TimeSteps, WalkOptions,
};
use tetray_integrate::{ColorPoint, Method, OpacityMode, OpacityPoint};
use tetray_mesh::MeshSummary;

use crate::convert::{TfPoints, camera_options, check_size, image_array};
use crate::grid::Grid;
use crate::interrupt::interruptible;
use crate::{guard, to_py, value_error};

/// A prepared mesh and renderer.
#[pyclass(module = "tetray._native", frozen)]
pub struct Scene {
    /// Written by `compare`, which switches integrators, and `go_to_step`.
    setup: RwLock<Setup>,
    /// Written by `go_to_step`.
    engine: RwLock<Engine>,
    /// A file's time steps (none for arrays): `go_to_step` moves through
    /// them, keeping what the steps share.
    steps: Option<Mutex<TimeSteps>>,
    options: FrameOptions,
    renderer: RendererChoice,
    walk: WalkOptions,
    size: (u32, u32),
    camera: CameraOptions,
    info: Info,
    /// Progress lines and warnings since the last `take_log`.
    log: Mutex<(Vec<String>, Vec<String>)>,
}

/// What `info` reports, kept from the load (the scene consumes the mesh).
struct Info {
    summary: MeshSummary,
    name: String,
    input_cells: usize,
    paraview_unit_distance: f32,
    load_seconds: f64,
    /// The file's time steps and the one read.
    times: Vec<f64>,
    time_step: Option<usize>,
}

#[pymethods]
impl Scene {
    #[new]
    #[pyo3(signature = (mesh, *, scalars=None, size=(512, 512), integrator="ppi",
        renderer="auto", camera=None, tf_json=None, tf_name=None, tf_rescale=true,
        tf_points=None, clim=None, unit_distance=None, opacity_mode="exact",
        early_termination=1.0, max_steps=None, linearize="subdivide", q=None,
        time_step=None, time=None, block=None, psi_size=1024))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        mesh: &Bound<'_, PyAny>,
        scalars: Option<String>,
        size: (u32, u32),
        integrator: &str,
        renderer: &str,
        camera: Option<&Bound<'_, PyDict>>,
        tf_json: Option<String>,
        tf_name: Option<String>,
        tf_rescale: bool,
        tf_points: Option<TfPoints>,
        clim: Option<(f32, f32)>,
        unit_distance: Option<f32>,
        opacity_mode: &str,
        early_termination: f32,
        max_steps: Option<u32>,
        linearize: &str,
        q: Option<std::path::PathBuf>,
        time_step: Option<usize>,
        time: Option<f64>,
        block: Option<String>,
        psi_size: usize,
    ) -> PyResult<Scene> {
        check_size(size)?;
        let method: Method = integrator
            .parse()
            .map_err(|e: tetray_integrate::UnknownMethod| value_error(e.to_string()))?;
        let renderer: RendererChoice = renderer.parse().map_err(value_error)?;
        if renderer == RendererChoice::ShearWarp {
            return Err(value_error(
                "renderer=\"shear-warp\" is the CLI's only (tetray render --renderer shear-warp)",
            ));
        }
        let opacity_mode = match opacity_mode {
            "exact" => OpacityMode::Exact,
            "vtk" => OpacityMode::Vtk,
            other => {
                return Err(value_error(format!(
                    "opacity_mode {other:?}: expected \"exact\" or \"vtk\""
                )));
            }
        };
        let linearize = match linearize {
            "subdivide" => tetray_io::vtk::Linearize::Subdivide,
            "corners" => tetray_io::vtk::Linearize::Corners,
            other => {
                return Err(value_error(format!(
                    "linearize {other:?}: expected \"subdivide\" or \"corners\""
                )));
            }
        };
        if !(early_termination > 0.0 && early_termination <= 1.0) {
            return Err(value_error(format!(
                "early_termination {early_termination} is outside (0, 1] (1 disables early \
                 termination)"
            )));
        }
        if let Some(u) = unit_distance.filter(|u| !(u.is_finite() && *u > 0.0)) {
            return Err(value_error(format!(
                "unit_distance {u} must be a finite number greater than 0"
            )));
        }
        if max_steps == Some(0) {
            return Err(value_error("max_steps must be at least 1"));
        }
        let tf = match (tf_json, tf_points) {
            (Some(_), Some(_)) => {
                return Err(value_error("give tf or cmap/opacity, not both"));
            }
            (Some(text), None) => TfSource::ParaView {
                text,
                name: tf_name,
                rescale: tf_rescale,
                label: "tf".into(),
            },
            (None, Some((color, opacity))) => TfSource::Normalized {
                color: color
                    .into_iter()
                    .map(|(s, r, g, b)| ColorPoint {
                        scalar: s,
                        rgb: Vec3::new(r, g, b),
                    })
                    .collect(),
                opacity: opacity
                    .into_iter()
                    .map(|(s, a)| OpacityPoint {
                        scalar: s,
                        alpha: a,
                    })
                    .collect(),
                range: clim,
            },
            // The default ramp, over `clim` when given (see the choice's
            // range below), as the CLI's --clim.
            (None, None) => TfSource::Default,
        };
        let default_range = clim.filter(|_| matches!(tf, TfSource::Default));
        let camera = camera_options(camera)?;
        let options = FrameOptions {
            integrator: IntegratorChoice {
                scalar: scalars,
                method,
                tf,
                unit_distance,
                opacity_mode,
                psi_size,
                range: default_range,
                ..IntegratorChoice::default()
            },
            camera: camera.clone(),
            bvh_preset: None,
            size,
            representation: tetray_engine::Representation::Tetrahedra,
        };
        let walk = WalkOptions {
            early_termination,
            max_steps,
            ..WalkOptions::default()
        };
        let (source, mut steps) = match mesh.cast::<Grid>() {
            Ok(grid) => {
                let grid = grid.get();
                let source = Source::Arrays {
                    grid: Box::new(grid.grid.clone()),
                    name: grid.name.clone(),
                    format: "Python arrays",
                    linearize,
                };
                (Some(source), None)
            }
            _ => match mesh.extract::<std::path::PathBuf>() {
                Ok(path) => {
                    let load = tetray_io::LoadOptions {
                        plot3d_q: q,
                        time_step,
                        time,
                        block,
                        linearize,
                    };
                    (None, Some(TimeSteps::new(path, load)))
                }
                _ => {
                    return Err(value_error("mesh must be a path or a tetray._native.Grid"));
                }
            },
        };
        let lines = Mutex::new((Vec::new(), Vec::new()));
        let built = py.detach(|| {
            guard(|| {
                let info = |line: String| lines.lock().expect("log lock").0.push(line);
                let warn = |line: String| lines.lock().expect("log lock").1.push(line);
                let log = Log {
                    info: &info,
                    warn: &warn,
                };
                let input = match (source, &mut steps) {
                    (Some(source), _) => tetray_engine::load(source),
                    (None, Some(steps)) => steps.load(None),
                    (None, None) => unreachable!("a path or arrays"),
                }
                .map_err(to_py)?;
                let info_of = info_of(&input);
                let setup =
                    tetray_engine::prepare_mesh(input, None, &options, log).map_err(to_py)?;
                let engine = Engine::new(renderer, &setup, &info).map_err(to_py)?;
                Ok((setup, engine, info_of))
            })
        });
        let (setup, engine, info) = built?;
        Ok(Scene {
            setup: RwLock::new(setup),
            engine: RwLock::new(engine),
            steps: steps.map(Mutex::new),
            options,
            renderer,
            walk,
            size,
            camera,
            info,
            log: lines,
        })
    }

    /// Renders one frame: `camera` (a dict of CameraOptions' fields, see
    /// `tetray.render`) or the scene's; `size` (width, height) or the
    /// scene's. Returns (height, width, 4) float32, premultiplied.
    #[pyo3(signature = (camera=None, size=None))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        camera: Option<&Bound<'py, PyDict>>,
        size: Option<(u32, u32)>,
    ) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let size = size.unwrap_or(self.size);
        check_size(size)?;
        let camera = match camera {
            Some(dict) => Some(camera_options(Some(dict))?),
            None if size != self.size => Some(self.camera.clone()),
            None => None,
        };
        let cancel = AtomicBool::new(false);
        let image = interruptible(py, &cancel, || {
            let setup = self.setup.read().expect("setup lock");
            let camera = match &camera {
                Some(options) => setup.camera_for(options, size).map_err(to_py)?,
                None => setup.camera,
            };
            let frame = self
                .engine
                .read()
                .expect("engine lock")
                .render_watched(&setup, &camera, self.walk, size, None, Some(&cancel))
                .map_err(to_py)?;
            Ok(frame.image)
        })?;
        image_array(py, &image)
    }

    /// The scene's first view turned `degrees` about its view-up (none:
    /// as it is), as `tetray animate --orbit` turns each frame.
    #[pyo3(signature = (degrees=None))]
    fn render_turned<'py>(
        &self,
        py: Python<'py>,
        degrees: Option<f32>,
    ) -> PyResult<Bound<'py, PyArray3<f32>>> {
        if degrees.is_some_and(|d| !d.is_finite()) {
            return Err(value_error(format!("degrees {degrees:?} is not finite")));
        }
        let cancel = AtomicBool::new(false);
        let image = interruptible(py, &cancel, || {
            let setup = self.setup.read().expect("setup lock");
            let mut camera = setup.camera;
            if let Some(degrees) = degrees {
                camera
                    .azimuth(degrees)
                    .and_then(|()| camera.orthogonalize_view_up())
                    .map_err(|e| value_error(format!("turning the camera: {e}")))?;
            }
            let frame = self
                .engine
                .read()
                .expect("engine lock")
                .render_watched(&setup, &camera, self.walk, self.size, None, Some(&cancel))
                .map_err(to_py)?;
            Ok(frame.image)
        })?;
        image_array(py, &image)
    }

    /// `frames` images orbiting the camera as `tetray bench` does: from the
    /// scene's camera, turned `step` degrees (default 360 / frames) about
    /// the view-up after each frame.
    #[pyo3(signature = (frames, step=None))]
    fn orbit<'py>(
        &self,
        py: Python<'py>,
        frames: u32,
        step: Option<f32>,
    ) -> PyResult<Vec<Bound<'py, PyArray3<f32>>>> {
        let step = step.unwrap_or(360.0 / frames.max(1) as f32);
        if !step.is_finite() {
            return Err(value_error(format!("step {step} is not finite")));
        }
        let images = py.detach(|| {
            guard(|| {
                let setup = self.setup.read().expect("setup lock");
                let mut camera = setup.camera;
                let mut images = Vec::with_capacity(frames as usize);
                for _ in 0..frames {
                    let frame = self
                        .engine
                        .read()
                        .expect("engine lock")
                        .render(&setup, &camera, self.walk, self.size, None)
                        .map_err(to_py)?;
                    images.push(frame.image);
                    camera
                        .azimuth(step)
                        .and_then(|()| camera.orthogonalize_view_up())
                        .map_err(|e| value_error(format!("orbiting the camera: {e}")))?;
                }
                Ok(images)
            })
        })?;
        images.iter().map(|image| image_array(py, image)).collect()
    }

    /// The `tetray info` summary of the mesh, and the scene's choices.
    #[getter]
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = &self.info.summary;
        let d = PyDict::new(py);
        d.set_item("mesh", &self.info.name)?;
        d.set_item("format", s.format)?;
        d.set_item("points", s.points)?;
        d.set_item("tets", s.tets)?;
        d.set_item("interior_faces", s.interior_faces)?;
        d.set_item("boundary_faces", s.boundary_faces)?;
        d.set_item("components", s.components)?;
        let (lo, hi) = s.bounds;
        let o = s.origin;
        let world = |v: Vec3| (o + v.as_dvec3()).to_array();
        d.set_item("bounds", (world(lo), world(hi)))?;
        d.set_item("origin", o.to_array())?;
        let fields = PyList::empty(py);
        for f in &s.fields {
            let fd = PyDict::new(py);
            fd.set_item("name", &f.name)?;
            fd.set_item("min", f.min)?;
            fd.set_item("max", f.max)?;
            fields.append(fd)?;
        }
        d.set_item("fields", fields)?;
        d.set_item("input_cells", self.info.input_cells)?;
        d.set_item("cells_split", s.cells_split)?;
        d.set_item("tets_from_split", s.tets_from_split)?;
        d.set_item("reoriented", s.inverted_fixed)?;
        d.set_item("degenerate_dropped", s.degenerate_dropped)?;
        d.set_item("excluded_cells", s.excluded.cells.len())?;
        d.set_item("paraview_unit_distance", self.info.paraview_unit_distance)?;
        d.set_item("load_seconds", self.info.load_seconds)?;
        d.set_item("times", self.info.times.clone())?;
        d.set_item("time_step", self.info.time_step)?;
        d.set_item("warnings", s.warnings.clone())?;
        let setup = self.setup.read().expect("setup lock");
        let scene = setup.scene().map_err(to_py)?;
        d.set_item("field", &scene.field)?;
        d.set_item(
            "range",
            setup.integrator_options.scalar_range.unwrap_or((0.0, 0.0)),
        )?;
        d.set_item("unit_distance", setup.unit_distance)?;
        d.set_item("integrator", setup.method.name())?;
        let engine = self.engine.read().expect("engine lock");
        d.set_item("renderer", engine.name())?;
        d.set_item("adapter", engine.adapter())?;
        d.set_item("scene_seconds", setup.scene_time.as_secs_f64())?;
        d.set_item("integrator_seconds", setup.integrator_time.as_secs_f64())?;
        Ok(d)
    }

    /// The camera of the scene's first view, in the file's coordinates:
    /// position, focal_point, view_up, view_angle, parallel_scale.
    #[getter]
    fn camera<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let setup = self.setup.read().expect("setup lock");
        let (c, o) = (&setup.camera, setup.extent.origin);
        let d = PyDict::new(py);
        d.set_item("position", (o + c.position.as_dvec3()).to_array())?;
        d.set_item("focal_point", (o + c.focal_point.as_dvec3()).to_array())?;
        d.set_item("view_up", c.view_up.to_array())?;
        d.set_item("view_angle", c.view_angle)?;
        d.set_item("parallel_scale", c.parallel_scale)?;
        Ok(d)
    }

    /// `tetray compare` from the scene's camera at its size: the CPU f64
    /// reference and each (renderer, integrator, sort) of `specs`. Returns
    /// the table (JSON rows, as `table.json`'s "methods"), the reference
    /// image and the images of the specs, in order.
    #[pyo3(signature = (specs, frames=1))]
    #[allow(clippy::type_complexity)]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        specs: Vec<crate::extras::Spec>,
        frames: u32,
    ) -> PyResult<(
        String,
        Bound<'py, PyArray3<f32>>,
        Vec<Bound<'py, PyArray3<f32>>>,
    )> {
        let size = self.size;
        let report = py.detach(|| {
            guard(|| {
                let mut setup = self.setup.write().expect("setup lock");
                let info = |line: String| self.log.lock().expect("log lock").0.push(line);
                crate::extras::compare(&mut setup, &specs, frames, size, &info)
            })
        })?;
        let rows = serde_json::to_string(&report.rows)
            .map_err(|e| value_error(format!("the comparison table: {e}")))?;
        let reference = image_array(py, &report.reference.image)?;
        let images = report
            .methods
            .iter()
            .map(|m| image_array(py, &m.image))
            .collect::<PyResult<Vec<_>>>()?;
        Ok((rows, reference, images))
    }

    /// `tetray export-html` of the scene at its camera and size: the HTML
    /// (one file, or `index.html` with `folder`) and, for a folder, the
    /// text of its `scene.js`.
    #[pyo3(signature = (background, bench=None, folder=false))]
    fn to_html(
        &self,
        py: Python<'_>,
        background: [f32; 3],
        bench: Option<(u32, u32)>,
        folder: bool,
    ) -> PyResult<(String, Option<String>)> {
        py.detach(|| {
            guard(|| {
                let setup = self.setup.read().expect("setup lock");
                let options = tetray_web::PageOptions {
                    size: self.size,
                    background,
                    early_termination: self.walk.early_termination,
                    max_steps: self.walk.max_steps,
                    bench,
                    preintegrate_all: false,
                };
                let layout = if folder {
                    tetray_web::Layout::Folder
                } else {
                    tetray_web::Layout::SingleFile
                };
                let page = tetray_web::bundle(&setup, &options)
                    .and_then(|bundle| tetray_web::page(&bundle, layout))
                    .map_err(|e| value_error(e.to_string()))?;
                Ok((page.html, page.scene_js))
            })
        })
    }

    /// Moves the scene to the file's time step `step` (0-based), as
    /// `tetray animate` moves through its steps: when the step's points
    /// and cells are the ones held, only its fields are read and taken
    /// (the topology, BVH and GPU upload of the cells stay); otherwise the
    /// scene is made again, keeping its camera. The colour range follows
    /// the step's field unless the scene was given `clim`. Returns (load
    /// seconds, scene seconds, whether the mesh was kept).
    fn go_to_step(&self, py: Python<'_>, step: usize) -> PyResult<(f64, f64, bool)> {
        let Some(steps) = &self.steps else {
            return Err(value_error(
                "the scene was made from arrays, not a file: it has no time steps",
            ));
        };
        py.detach(|| {
            guard(|| {
                let info = |line: String| self.log.lock().expect("log lock").0.push(line);
                let warn = |line: String| self.log.lock().expect("log lock").1.push(line);
                let log = Log {
                    info: &info,
                    warn: &warn,
                };
                let mut steps = steps.lock().expect("steps lock");
                let mut setup = self.setup.write().expect("setup lock");
                let mut engine = self.engine.write().expect("engine lock");
                let cost = steps
                    .advance(&mut setup, step, &self.options, log)
                    .map_err(to_py)?;
                if cost.kept {
                    engine.take_fields(&setup, &info).map_err(to_py)?;
                } else {
                    *engine = Engine::new(self.renderer, &setup, &info).map_err(to_py)?;
                }
                Ok((cost.load.as_secs_f64(), cost.scene.as_secs_f64(), cost.kept))
            })
        })
    }

    /// The range of the scene's field over the file's time steps `steps`
    /// (read, not made into scenes): an animation's colour range. `None`
    /// for a field constant over them, or a mesh without fields.
    fn range_over(&self, py: Python<'_>, steps: Vec<usize>) -> PyResult<Option<(f32, f32)>> {
        let Some(series) = &self.steps else {
            return Err(value_error(
                "the scene was made from arrays, not a file: it has no time steps",
            ));
        };
        let field = self.setup.read().expect("setup lock").extent.field.clone();
        if field == tetray_engine::SOLID {
            return Ok(None);
        }
        py.detach(|| {
            guard(|| {
                let series = series.lock().expect("steps lock");
                series.range(&steps, Some(&field)).map_err(to_py)
            })
        })
    }

    /// The progress lines and warnings gathered so far, emptied.
    fn take_log(&self) -> (Vec<String>, Vec<String>) {
        let mut log = self.log.lock().expect("log lock");
        (std::mem::take(&mut log.0), std::mem::take(&mut log.1))
    }
}

fn info_of(input: &MeshInput) -> Info {
    Info {
        summary: MeshSummary::new(&input.loaded),
        name: input.name.clone(),
        input_cells: input.input_cells(),
        paraview_unit_distance: input.paraview_unit_distance(),
        load_seconds: input.load_time.as_secs_f64(),
        times: input.loaded.report.times.clone(),
        time_step: input.loaded.report.time_step,
    }
}
