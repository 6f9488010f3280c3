//! Pieces of a parallel file read apart (as the processes of a distributed
//! render read them) give exactly the tetrahedra of the whole file: the
//! blood-vessel `.pvtu` (4 pieces of hexahedra, split by point numbers)
//! cut into two runs of pieces at every place, each run read with the
//! whole mesh's origin. Compared as sets of tetrahedra by the bits of
//! their corner coordinates (exact), with their point field.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use tetray_io::vtk::{parallel_piece_count, read_piece_subset};
use tetray_io::{LoadOptions, LoadedMesh, load, load_piece_subset};

fn pvtu() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/blood_vessels/T0000000500.pvtu")
}

/// Each tetrahedron by its corners' coordinate bits (sorted: the same
/// cell whatever its vertex order), with its corners' `node_value`s.
fn tets(mesh: &LoadedMesh) -> HashMap<[[u32; 3]; 4], [u32; 4]> {
    let m = &mesh.mesh;
    let field = m.field("node_value").expect("a point field");
    m.tets
        .iter()
        .map(|t| {
            let mut corners: Vec<([u32; 3], u32)> = t
                .iter()
                .map(|&v| {
                    let p = m.points[v as usize];
                    (
                        p.to_array().map(f32::to_bits),
                        field.values[v as usize].to_bits(),
                    )
                })
                .collect();
            corners.sort_unstable();
            (
                std::array::from_fn(|i| corners[i].0),
                std::array::from_fn(|i| corners[i].1),
            )
        })
        .collect()
}

#[test]
fn runs_of_pieces_are_the_whole_files_tetrahedra() {
    let path = pvtu();
    let opts = LoadOptions::default();
    let whole = load(&path, &opts).unwrap();
    let expected = tets(&whole);
    assert_eq!(expected.len(), whole.mesh.tets.len());
    let pieces = parallel_piece_count(&path).unwrap();
    assert_eq!(pieces, 4);
    for cut in 1..pieces {
        let mut got = HashMap::new();
        let mut count = 0;
        for run in [0..cut, cut..pieces] {
            let subset = read_piece_subset(&path, run).unwrap();
            let part = load_piece_subset(subset, whole.origin(), &opts).unwrap();
            count += part.mesh.tets.len();
            got.extend(tets(&part));
        }
        assert_eq!(count, expected.len(), "cut at piece {cut}");
        let missing = expected.keys().filter(|k| !got.contains_key(*k)).count();
        let other_values = expected
            .iter()
            .filter(|(k, v)| got.get(*k).is_some_and(|g| g != *v))
            .count();
        assert!(
            missing == 0 && other_values == 0,
            "cut at piece {cut}: {missing} tetrahedra missing, {other_values} with other values"
        );
    }
    // Past the last piece: an error naming the file, not a panic.
    assert!(read_piece_subset(&path, 3..5).is_err());
}
