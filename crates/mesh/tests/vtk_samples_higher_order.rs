//! The higher-order and polyhedral samples of `data/real` load.

use std::path::PathBuf;

fn sample(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/real").join(name)
}

#[test]
fn explore() {
    for name in ["QuadraticTetra.vtu", "tetra.vtu", "QuadraticWedge.vtu", "notch_disp.vtu", "polyhedron2pieces.vtu"] {
        let read = tetray_mesh::vtk::read_vtu_file(&sample(name));
        match read {
            Ok(r) => {
                println!("{name}: points {} tets {} {:?} warnings {:?}", r.mesh.points.len(), r.mesh.tets.len(), r.cells, r.warnings);
                let loaded = tetray_mesh::load(&sample(name), &Default::default());
                match loaded { Ok(l) => println!("  load ok {:?}", l.report.warnings), Err(e) => println!("  load error {e}") }
            }
            Err(e) => println!("{name}: {e}"),
        }
    }
}
