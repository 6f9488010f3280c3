//! Helpers shared by the tests of the CFD formats' readers (CGNS, EnSight
//! Gold, OpenFOAM, VTKHDF, file series): the data folder, a scratch folder,
//! a load at a time step, a field by name.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use tetray_io::{LoadOptions, LoadedMesh, load};

/// `path` under the repository's `data/`.
pub fn data(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(path)
}

/// An empty folder `group/name` in Cargo's scratch space for tests.
pub fn scratch(group: &str, name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(group)
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// The file at `path`, at `time_step` (`None`: the default).
pub fn at_step(path: &Path, time_step: Option<usize>) -> LoadedMesh {
    let opts = LoadOptions {
        time_step,
        ..LoadOptions::default()
    };
    load(path, &opts).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The values of the point field `name`.
pub fn field<'a>(mesh: &'a LoadedMesh, name: &str) -> &'a [f32] {
    &mesh
        .mesh
        .fields
        .iter()
        .find(|f| f.name == name)
        .expect(name)
        .values
}

/// The mesh's volume: the sum of its tetrahedra's, in f64 in the file's
/// coordinates.
pub fn volume(mesh: &LoadedMesh) -> f64 {
    let origin = mesh.origin();
    mesh.mesh
        .tets
        .iter()
        .map(|t| {
            let [a, b, c, d] = t.map(|i| mesh.mesh.points[i as usize].as_dvec3() + origin);
            (b - a).cross(c - a).dot(d - a).abs() / 6.0
        })
        .sum()
}
