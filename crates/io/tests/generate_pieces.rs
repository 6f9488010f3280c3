//! The torus shell written as a partitioned `.pvtu` reads back as the one
//! shell: the pieces' shared planes welded by equal coordinates, no seam,
//! the same tetrahedra as the single `.vtu`.

use std::collections::BTreeSet;

use tetray_io::generate::GenerateError;
use tetray_io::generate::pieces::write_pvtu;
use tetray_io::generate::solid::TorusShell;
use tetray_io::{LoadOptions, load};

#[test]
fn the_pieces_weld_into_the_whole_shell() {
    let cells = [16, 8, 2];
    let shell = TorusShell::new(cells).unwrap();
    let dir = std::env::temp_dir().join(format!("tetray-pieces-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let pieces = 3;
    let written = write_pvtu(&shell, &dir.join("shell.pvtu"), pieces).unwrap();
    assert_eq!(written.len(), 1 + pieces);
    for (path, bytes) in &written {
        assert_eq!(*bytes, std::fs::metadata(path).unwrap().len());
    }
    let joined = load(&written[0].0, &LoadOptions::default()).unwrap();
    shell.write_vtu(&dir.join("shell.vtu")).unwrap();
    let whole = load(&dir.join("shell.vtu"), &LoadOptions::default()).unwrap();

    let report = &joined.report;
    assert_eq!(report.pieces.pieces, pieces);
    // Each of the 3 cut planes (the wrap included) has nv * (nw + 1)
    // points written twice, welded once.
    assert_eq!(
        report.pieces.welded_points,
        pieces * cells[1] * (cells[2] + 1)
    );
    assert_eq!(joined.mesh.points.len(), whole.mesh.points.len());
    assert_eq!(joined.mesh.tets.len(), whole.mesh.tets.len());
    assert_eq!(report.validation.components, 1);
    assert_eq!(report.validation.seam_faces, 0);
    assert_eq!(
        joined.topology.boundary_faces.len(),
        whole.topology.boundary_faces.len()
    );
    // The same tetrahedra, by their corner positions.
    let corners = |m: &tetray_mesh::TetMesh| -> BTreeSet<Vec<[u32; 3]>> {
        m.tets
            .iter()
            .map(|t| {
                let mut c: Vec<[u32; 3]> = t
                    .iter()
                    .map(|&p| m.points[p as usize].to_array().map(f32::to_bits))
                    .collect();
                c.sort_unstable();
                c
            })
            .collect()
    };
    assert_eq!(corners(&joined.mesh), corners(&whole.mesh));
    assert!(joined.mesh.field("wave").is_some());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn more_pieces_than_cells_around_the_axis_is_an_error() {
    let shell = TorusShell::new([4, 4, 1]).unwrap();
    let path = std::env::temp_dir().join("tetray-pieces-none.pvtu");
    for pieces in [0, 5] {
        assert!(matches!(
            write_pvtu(&shell, &path, pieces),
            Err(GenerateError::BadShell { .. })
        ));
    }
}
