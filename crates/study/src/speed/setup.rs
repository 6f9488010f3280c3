//! What the speed study renders: the three PLOT3D datasets and generated
//! box meshes, each made a scene with the CLI's defaults (the default
//! transfer function over the scalar's range, ParaView's unit distance,
//! a ResetCamera view).

use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::Vec3;
use tetray_boundary_bvh::BuildPreset;
use tetray_core::Camera;
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_io::LoadOptions;
use tetray_mesh::synthetic::{box_grid, CellSplit};
use tetray_mesh::{mean_tet_chord, ScalarField, TetMesh, Topology};
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

/// A scene ready to time, with what the integrators need.
pub struct Prepared {
    pub name: String,
    pub scene: Scene,
    pub camera: Camera,
    pub tf: TransferFunction,
    pub options: IntegratorOptions,
    /// Seconds to build the topology (generated meshes) or load (files),
    /// and to make the scene (checks, boundary BVH).
    pub load_s: f64,
    pub scene_s: f64,
}

impl Prepared {
    pub fn integrator(&self, method: Method) -> Result<ScalarIntegrator, StudyError> {
        Ok(ScalarIntegrator::new(method, &self.tf, &self.options)?)
    }
}

/// Loads `dataset` from `dir` and prepares it for `size`.
pub fn load_dataset(
    dir: &Path,
    dataset: &Dataset,
    size: (u32, u32),
) -> Result<Prepared, StudyError> {
    let path: PathBuf = dir.join(dataset.grid);
    let start = Instant::now();
    let loaded = tetray_io::load(&path, &LoadOptions::default())?;
    let load_s = start.elapsed().as_secs_f64();
    let unit_distance = loaded.paraview_unit_distance();
    prepare(
        dataset.name.to_string(),
        loaded.mesh,
        loaded.topology,
        dataset.field,
        unit_distance,
        size,
        load_s,
    )
}

/// A box of `cells^3` hexahedra, five tetrahedra each, with a smooth
/// non-linear field (two Gaussian blobs over a gradient), prepared for
/// `size`. Returns the number of tetrahedra too.
pub fn generated_box(cells: u32, size: (u32, u32)) -> Result<Prepared, StudyError> {
    let start = Instant::now();
    let mut mesh = box_grid(Vec3::ZERO, Vec3::ONE, [cells; 3], CellSplit::Five)?;
    let values = mesh.points.iter().map(|&p| blobs(p)).collect();
    mesh.fields.push(ScalarField {
        name: "blobs".into(),
        values,
    });
    let topology = Topology::build(&mesh)?;
    let load_s = start.elapsed().as_secs_f64();
    // ParaView's rule on the hexahedra the box was cut into.
    let unit_distance = 3f32.sqrt() / cells as f32;
    prepare(
        format!("box {cells}^3 x 5"),
        mesh,
        topology,
        "blobs",
        unit_distance,
        size,
        load_s,
    )
}

/// Hexahedra per axis of the generated box nearest `tets` tetrahedra.
pub fn cells_for(tets: usize) -> u32 {
    ((tets as f64 / 5.0).cbrt().round() as u32).max(1)
}

fn blobs(p: Vec3) -> f32 {
    let blob = |c: Vec3, r: f32| (-(p - c).length_squared() / (r * r)).exp();
    0.3 * p.x + blob(Vec3::new(0.35, 0.4, 0.5), 0.2) + 0.7 * blob(Vec3::new(0.7, 0.6, 0.4), 0.15)
}

fn prepare(
    name: String,
    mesh: TetMesh,
    topology: Topology,
    field: &str,
    unit_distance: f32,
    (width, height): (u32, u32),
    load_s: f64,
) -> Result<Prepared, StudyError> {
    let chord = mean_tet_chord(&mesh);
    let start = Instant::now();
    let scene = Scene::new(mesh, topology, field, BuildPreset::default())?;
    let scene_s = start.elapsed().as_secs_f64();
    let (lo, hi) = scene
        .scalar
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let (b_lo, b_hi) = scene.bounds();
    let mut camera = Camera::default();
    camera.reset(b_lo, b_hi, width as f32 / height as f32)?;
    let options = IntegratorOptions {
        unit_distance,
        riemann_step: chord / 4.0,
        preintegration_length: chord,
        scalar_range: Some((lo, hi)),
        ..IntegratorOptions::default()
    };
    Ok(Prepared {
        name,
        scene,
        camera,
        tf: TransferFunction::default_for_range(lo, hi),
        options,
        load_s,
        scene_s,
    })
}
