//! Distorted hexahedra: a cell whose default split (the face diagonals
//! through each face's smallest point index, then the 5- or 6-tetrahedron
//! realisation) has tetrahedra of both orientations is split from another
//! corner with the same face diagonals, so the mesh stays conforming; a
//! cell no such split fixes is left out and reported (see the ray caster's
//! `imperfect.rs` for the images).

use tetray_io::vtk::read_legacy_bytes;
use tetray_io::{LoadOptions, load};

/// Two unit hexahedra side by side along x. The first lists its points as
/// global ids `[3, 1, 2, 0, 4, 5, 6, 7]` and has its corner (0, 0, 0)
/// pushed to `dent` towards the cell's centre (a dented, non-convex cell);
/// the second shares the face x = 1 (not holding the dent).
fn two_hexes(dent: f64) -> String {
    let mut points = [[0.0f64; 3]; 12];
    let first = [3usize, 1, 2, 0, 4, 5, 6, 7];
    let corners = [
        [0., 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.],
        [0., 1., 0.],
        [0., 0., 1.],
        [1., 0., 1.],
        [1., 1., 1.],
        [0., 1., 1.],
    ];
    for (k, &id) in first.iter().enumerate() {
        points[id] = corners[k];
    }
    points[3] = [dent; 3];
    // The second cell's far points 8..11: (2,0,0), (2,1,0), (2,0,1), (2,1,1).
    points[8] = [2., 0., 0.];
    points[9] = [2., 1., 0.];
    points[10] = [2., 0., 1.];
    points[11] = [2., 1., 1.];
    let xyz: Vec<String> = points
        .iter()
        .map(|p| format!("{:?} {:?} {:?}", p[0], p[1], p[2]))
        .collect();
    format!(
        "# vtk DataFile Version 3.0\ndented\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 12 double\n{}\n\
         CELLS 2 18\n8 3 1 2 0 4 5 6 7\n8 1 8 9 2 5 10 11 6\nCELL_TYPES 2\n12\n12\n",
        xyz.join("\n")
    )
}

#[test]
fn a_dented_hexahedron_is_split_from_another_corner_and_stays_conforming() {
    // Found by a search over pushed corners: the default (5-tetrahedron)
    // split of the first cell inverts a tetrahedron once the corner is at
    // 0.35 (0.7 of the way to the centre) or further; the cone from
    // another corner stays positive.
    for dent in [0.35, 0.5, 0.7] {
        let read = read_legacy_bytes(two_hexes(dent).as_bytes(), "dented").unwrap();
        assert!(
            read.warnings
                .iter()
                .any(|w| w.contains("1 distorted hexahedra")),
            "{dent}: {:?}",
            read.warnings
        );
        let path = std::env::temp_dir().join(format!("tetray-dented-{}.vtk", std::process::id()));
        std::fs::write(&path, two_hexes(dent)).unwrap();
        let loaded = load(&path, &LoadOptions::default()).unwrap();
        std::fs::remove_file(&path).unwrap();
        let report = &loaded.report;
        assert!(report.excluded.is_empty(), "{:?}", report.changes());
        assert!(report.validation.nonconforming_faces.is_empty());
        assert_eq!(report.validation.components, 1);
        let volume: f64 = (0..loaded.mesh.tets.len())
            .map(|t| {
                let v = loaded.mesh.signed_volume(t);
                assert!(v > 0.0, "{dent}: tet {t} has volume {v}");
                v
            })
            .sum();
        // All positive, so no tetrahedron overlaps another: the volumes sum
        // to the enclosed volume, two cubes less the dent.
        assert!(volume < 2.0 && volume > 1.5, "{dent}: {volume}");
    }
    // Undented, the default split is kept (no warning).
    let read = read_legacy_bytes(two_hexes(0.0).as_bytes(), "cube").unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
}
