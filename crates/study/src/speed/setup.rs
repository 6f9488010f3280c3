//! What the speed study renders: the three PLOT3D datasets and generated
//! box meshes, each made ready by the engine with the CLI's defaults (the
//! default transfer function over the scalar's range, ParaView's unit
//! distance) and a plain ResetCamera view.

use std::path::Path;
use std::time::Instant;

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_engine::{CameraOptions, FrameOptions, IntegratorChoice, Log, Setup, Source};
use tetray_integrate::{Method, ScalarIntegrator};
use tetray_mesh::ScalarField;
use tetray_mesh::synthetic::{CellSplit, box_grid};
use tetray_scene::Scene;

use crate::StudyError;

/// A dataset of the timing table (dissertation table 6.1; our third is
/// NASA's combustion chamber, where the dissertation had the Delta Wing).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dataset {
    pub name: &'static str,
    /// PLOT3D grid file in the data folder (the q file is its sibling).
    pub grid: &'static str,
    /// The field rendered: the Oxygen Post's density is constant, so its
    /// velocity magnitude.
    pub field: &'static str,
}

pub const DATASETS: [Dataset; 3] = [
    Dataset {
        name: "Blunt Fin",
        grid: "bluntfinxyz.bin",
        field: "density",
    },
    Dataset {
        name: "Oxygen Post",
        grid: "postxyz.bin",
        field: "velocity_magnitude",
    },
    Dataset {
        name: "Combustion Chamber",
        grid: "combxyz.bin",
        field: "density",
    },
];

/// A scene ready to time: the engine's setup of it.
pub struct Prepared {
    pub name: String,
    pub setup: Setup,
    /// Seconds to build the topology (generated meshes) or load (files),
    /// and to make the scene (checks, boundary BVH).
    pub load_s: f64,
    pub scene_s: f64,
}

impl Prepared {
    pub fn scene(&self) -> &Scene {
        self.setup
            .scene()
            .expect("the speed study's setups have tetrahedra")
    }

    pub fn integrator(&self, method: Method) -> Result<ScalarIntegrator, StudyError> {
        let setup = &self.setup;
        Ok(setup.integrator_with(
            method,
            &setup.tf,
            setup.unit_distance,
            setup.integrator_options.opacity_mode,
        )?)
    }
}

/// Loads `dataset` from `dir` and prepares it for `size`.
pub fn load_dataset(
    dir: &Path,
    dataset: &Dataset,
    size: (u32, u32),
) -> Result<Prepared, StudyError> {
    let source = Source::file(dir.join(dataset.grid));
    prepare(dataset.name.to_string(), source, dataset.field, None, size)
}

/// A box of `cells^3` hexahedra, five tetrahedra each, with a smooth
/// non-linear field (two Gaussian blobs over a gradient), prepared for
/// `size`.
pub fn generated_box(cells: u32, size: (u32, u32)) -> Result<Prepared, StudyError> {
    let start = Instant::now();
    let mut mesh = box_grid(Vec3::ZERO, Vec3::ONE, [cells; 3], CellSplit::Five)?;
    let values = mesh.points.iter().map(|&p| blobs(p)).collect();
    mesh.fields.push(ScalarField {
        name: "blobs".into(),
        values,
    });
    let loaded = tetray_mesh::prepare(mesh)?;
    let build_s = start.elapsed().as_secs_f64();
    let name = format!("box {cells}^3 x 5");
    let source = Source::Mesh {
        mesh: Box::new(loaded),
        name: name.clone(),
    };
    // ParaView's rule on the hexahedra the box was cut into.
    let unit_distance = 3f32.sqrt() / cells as f32;
    let mut prepared = prepare(name, source, "blobs", Some(unit_distance), size)?;
    prepared.load_s = build_s;
    Ok(prepared)
}

/// Hexahedra per axis of the generated box nearest `tets` tetrahedra.
pub fn cells_for(tets: usize) -> u32 {
    ((tets as f64 / 5.0).cbrt().round() as u32).max(1)
}

fn blobs(p: Vec3) -> f32 {
    let blob = |c: Vec3, r: f32| (-(p - c).length_squared() / (r * r)).exp();
    0.3 * p.x + blob(Vec3::new(0.35, 0.4, 0.5), 0.2) + 0.7 * blob(Vec3::new(0.7, 0.6, 0.4), 0.15)
}

/// The engine's setup of `source` with `field` active: the default
/// transfer function over its range, ParaView's unit distance (or the one
/// given), the default BVH and a plain ResetCamera view (no turn).
fn prepare(
    name: String,
    source: Source,
    field: &str,
    unit_distance: Option<f32>,
    size: (u32, u32),
) -> Result<Prepared, StudyError> {
    let options = FrameOptions {
        integrator: IntegratorChoice {
            scalar: Some(field.to_string()),
            unit_distance,
            ..IntegratorChoice::default()
        },
        camera: CameraOptions {
            azimuth: Some(0.0),
            elevation: Some(0.0),
            ..CameraOptions::default()
        },
        bvh_preset: Some(BuildPreset::default()),
        size,
        ..FrameOptions::default()
    };
    let setup = tetray_engine::prepare(source, &options, Log::quiet())?;
    Ok(Prepared {
        name,
        load_s: setup.load_time.as_secs_f64(),
        scene_s: setup.scene_time.as_secs_f64(),
        setup,
    })
}
