//! The cell assembly: random points, cell types (every VTK type number, and
//! others), connectivity (indices in and out of range) and polyhedron face
//! streams, split into tetrahedra with topology and validation, as the
//! Python package's arrays are.
#![no_main]
use libfuzzer_sys::fuzz_target;
use tetray_mesh::cells::{CellArray, CellGrid};

/// VTK cell types with a volume, and some without.
const TYPES: [i64; 20] = [
    10, 11, 12, 13, 14, 24, 25, 26, 27, 29, 32, 33, 42, 71, 72, 73, 74, 5, 9, 0,
];

fuzz_target!(|data: &[u8]| {
    let mut bytes = data.iter().copied();
    let mut next = move || bytes.next();
    let Some(points) = next().map(|n| usize::from(n % 64) + 1) else {
        return;
    };
    let mut grid = CellGrid {
        dataset: "UnstructuredGrid",
        ..CellGrid::default()
    };
    for _ in 0..3 * points {
        // Coordinates on a small lattice: coincident points, flat and
        // tangled cells come up often.
        let v = next().unwrap_or(0);
        grid.points
            .push(f64::from(v % 8) - 3.5 + f64::from(v / 64) * 1e-7);
    }
    grid.offsets.push(0);
    while let Some(pick) = next() {
        let kind = if pick >= 250 {
            i64::from(pick) * 3
        } else {
            TYPES[usize::from(pick) % TYPES.len()]
        };
        let count = usize::from(next().unwrap_or(0) % 32);
        for _ in 0..count {
            let raw = i64::from(next().unwrap_or(0));
            // Mostly valid indices, some past the end or negative.
            let id = if raw >= 240 {
                raw - 250
            } else {
                raw % points as i64
            };
            grid.connectivity.push(id);
        }
        grid.types.push(kind);
        grid.offsets.push(grid.connectivity.len());
    }
    grid.point_arrays.push(CellArray {
        name: "f".into(),
        components: 1,
        values: (0..points).map(|i| i as f64).collect(),
        section: "fuzz".into(),
        defined: None,
    });
    let _ = tetray_io::load_grid(
        grid,
        "fuzz",
        "fuzz arrays",
        &tetray_io::LoadOptions::default(),
    );
});
