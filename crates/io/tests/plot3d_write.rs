//! The PLOT3D writer against the reader: synthetic grids with and without
//! IBLANK and solution, and the embedded Blunt Fin, read back bit for bit
//! and loaded into the same mesh; the files it writes are found by `load`.

use std::path::Path;

use tetray_io::plot3d::{
    Plot3dGrid, Plot3dSolution, plot3d_q_bytes, plot3d_xyz_bytes, read_plot3d_grid_bytes,
    read_plot3d_grid_files, write_plot3d_files, write_plot3d_q, write_plot3d_xyz,
};
use tetray_io::{LoadOptions, load, load_plot3d_bytes};

fn grid(iblank: bool, solution: bool) -> Plot3dGrid {
    let dims = [4, 3, 5];
    let n = 60;
    // Positive density: the reader derives pressure and velocity from it.
    let value = |p: usize, a: usize| ((p * 7 + a * 13) % 17) as f32 * 0.25 + 0.5 + a as f32;
    let coordinate = |p: usize, a: usize| {
        let (i, j, k) = (p % 4, (p / 4) % 3, p / 12);
        let ijk = [i, j, k][a] as f32;
        // Sheared so the three arrays differ, with a non-representable
        // fraction to exercise every bit.
        ijk * 0.3 + 0.01 * (i + 2 * j + 3 * k) as f32 / 3.0
    };
    Plot3dGrid {
        dims,
        xyz: [0, 1, 2].map(|a| (0..n).map(|p| coordinate(p, a)).collect()),
        iblank: iblank.then(|| {
            (0..n)
                .map(|p| i32::from(p != 17) - 2 * i32::from(p == 3))
                .collect()
        }),
        solution: solution.then(|| Plot3dSolution {
            conditions: [0.5, 2.25, 1.5e6, 0.125],
            q: [0, 1, 2, 3, 4].map(|a| (0..n).map(|p| value(p, a)).collect()),
        }),
    }
}

#[test]
fn written_files_read_back_bit_exact() {
    for iblank in [false, true] {
        for solution in [false, true] {
            let source = grid(iblank, solution);
            let mut xyz = Vec::new();
            let written = write_plot3d_xyz(&source, &mut xyz).unwrap();
            assert_eq!(written as usize, xyz.len());
            assert_eq!(written, plot3d_xyz_bytes(source.dims, iblank));
            // Big-endian header, as the NASA files.
            assert_eq!(&xyz[..12], &[0, 0, 0, 4, 0, 0, 0, 3, 0, 0, 0, 5]);
            let mut q = Vec::new();
            if solution {
                let written = write_plot3d_q(&source, &mut q).unwrap();
                assert_eq!(written as usize, q.len());
                assert_eq!(written, plot3d_q_bytes(source.dims));
            } else {
                assert!(write_plot3d_q(&source, &mut q).is_err());
            }
            let q = solution.then_some(q.as_slice());
            let back = read_plot3d_grid_bytes(&xyz, q, "rt").unwrap();
            assert_eq!(back, source, "iblank {iblank}, solution {solution}");
        }
    }
}

#[test]
fn blunt_fin_round_trips_to_the_same_mesh() {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let (xyz, q) = (assets.join("bluntfinxyz.bin"), assets.join("bluntfinq.bin"));
    let source = read_plot3d_grid_files(&xyz, Some(&q)).unwrap();
    let (mut xyz_out, mut q_out) = (Vec::new(), Vec::new());
    write_plot3d_xyz(&source, &mut xyz_out).unwrap();
    write_plot3d_q(&source, &mut q_out).unwrap();
    // The original has 484 unused bytes after the solution; the rest of
    // both files is written back byte for byte.
    let (xyz_in, q_in) = (std::fs::read(&xyz).unwrap(), std::fs::read(&q).unwrap());
    assert_eq!(xyz_out, xyz_in);
    assert_eq!(q_out[..], q_in[..q_in.len() - 484]);
    let original = load_plot3d_bytes(&xyz_in, Some(&q_in), "bluntfin").unwrap();
    let rewritten = load_plot3d_bytes(&xyz_out, Some(&q_out), "bluntfin").unwrap();
    assert_eq!(original.mesh, rewritten.mesh);
}

#[test]
fn written_files_are_found_by_load() {
    let dir = std::env::temp_dir().join(format!("tetray-p3d-write-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let source = grid(true, true);
    let (xyz, q) = (dir.join("gridxyz.bin"), dir.join("gridq.bin"));
    let (xyz_bytes, q_bytes) = write_plot3d_files(&source, &xyz, Some(&q)).unwrap();
    assert_eq!(xyz_bytes, std::fs::metadata(&xyz).unwrap().len());
    assert_eq!(q_bytes, Some(std::fs::metadata(&q).unwrap().len()));
    // The q sibling is picked up by name.
    let loaded = load(&xyz, &LoadOptions::default()).unwrap();
    assert_eq!(loaded.mesh.fields.len(), 5);
    // Point 17, (1, 1, 1), is blanked: the 8 hexahedra around it (of 24)
    // are left out.
    assert_eq!(loaded.mesh.tets.len(), 5 * (24 - 8));
    let missing = dir.join("nowhere/gridxyz.bin");
    let e = write_plot3d_files(&source, &missing, None).unwrap_err();
    assert!(e.to_string().contains("nowhere/gridxyz.bin"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
