//! In situ, as a simulation would call it: every rank builds its part of
//! a mesh in memory (a hollow box, split spatially by rank), hands the
//! arrays to `render_in_situ` on the world communicator, and rank 0
//! writes the image. Rank 0 then renders the whole mesh alone (the same
//! camera fit, transfer function and unit distance, from the whole mesh)
//! and prints the largest difference per pixel channel; it exits with 1
//! when that exceeds 9e-7 (the compositing is exact up to f32 rounding:
//! measured at most 3.0e-7 for 1 to 4 ranks) or when fewer than 1000 of
//! the 6912 pixels are lit (1909 are).
//! With the argument `cells`, each rank hands over a slab of a hollow box
//! of hexahedra as VTK cells (`render_in_situ_cells`) instead, checked
//! against the whole grid split into tetrahedra in one process.
//!
//! ```sh
//! mpirun -n 4 target/release/in_situ [cells] [out.exr]
//! ```

use std::process::ExitCode;

use glam::{DVec3, Vec3};
use tetray_distributed::mpi::traits::*;
use tetray_distributed::{
    InSituView, RankMesh, render_in_situ, render_in_situ_cells, spatial_split,
};
use tetray_engine::{Engine, Log, Source, WalkOptions};
use tetray_mesh::cells::{CellArray, CellGrid, ReadOptions, assemble_at};
use tetray_mesh::synthetic::{CellSplit, hollow_box};
use tetray_mesh::{ScalarField, TetMesh, prepare};

/// A nonlinear field, so a wrong split or order would show.
fn field(p: Vec3) -> f32 {
    (p.x * 1.7).sin() * 0.5 + p.y * p.z * 0.3
}

fn whole_mesh() -> TetMesh {
    let mut mesh = hollow_box(
        Vec3::new(-2.0, -1.0, -1.0),
        Vec3::new(2.0, 1.0, 1.5),
        [10, 5, 6],
        [2, 1, 1],
        [8, 4, 5],
        CellSplit::Five,
    )
    .expect("a valid box");
    let values = mesh.points.iter().map(|&p| field(p)).collect();
    mesh.fields.push(ScalarField {
        name: "s".into(),
        values,
    });
    mesh
}

/// Points per axis of the hexahedral grid, and its hole (cells).
const DIMS: [usize; 3] = [11, 6, 7];
const HOLE: ([usize; 3], [usize; 3]) = ([2, 1, 1], [8, 4, 5]);

/// A hollow box of hexahedra (VTK type 12) over [-2, 2] x [-1, 1] x
/// [-1, 1.5], with the point field `s`.
fn hex_grid() -> CellGrid {
    let [nx, ny, nz] = DIMS;
    let id = |i: usize, j: usize, k: usize| (i + nx * (j + ny * k)) as i64;
    let mut points = Vec::new();
    let mut values = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let p = Vec3::new(
                    -2.0 + 4.0 * i as f32 / (nx - 1) as f32,
                    -1.0 + 2.0 * j as f32 / (ny - 1) as f32,
                    -1.0 + 2.5 * k as f32 / (nz - 1) as f32,
                );
                points.extend(p.to_array().map(f64::from));
                values.push(f64::from(field(p)));
            }
        }
    }
    let (mut connectivity, mut offsets, mut types) = (Vec::new(), vec![0], Vec::new());
    let (lo, hi) = HOLE;
    for k in 0..nz - 1 {
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let c = [i, j, k];
                if (0..3).all(|a| lo[a] <= c[a] && c[a] < hi[a]) {
                    continue;
                }
                connectivity.extend([
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ]);
                offsets.push(connectivity.len());
                types.push(12);
            }
        }
    }
    CellGrid {
        points,
        points_section: "in situ points".into(),
        offsets,
        connectivity,
        types,
        point_arrays: vec![CellArray {
            name: "s".into(),
            components: 1,
            values,
            section: "in situ field".into(),
            defined: None,
        }],
        dataset: "UnstructuredGrid",
        ..CellGrid::default()
    }
}

/// Rank `rank`'s slab of hexahedra (by first corner along x), with the
/// points they use numbered in the whole grid's order (so the cells split
/// into the same tetrahedra as in the whole grid).
fn hex_slab(grid: &CellGrid, rank: usize, size: usize) -> CellGrid {
    let cells = grid.types.len();
    let mine: Vec<usize> = (rank * cells / size..(rank + 1) * cells / size).collect();
    let mut order: Vec<usize> = (0..cells).collect();
    let x = |c: usize| grid.points[3 * grid.connectivity[8 * c] as usize];
    order.sort_by(|&a, &b| x(a).total_cmp(&x(b)).then(a.cmp(&b)));
    let chosen: Vec<usize> = mine.iter().map(|&i| order[i]).collect();
    let mut used = vec![false; grid.points.len() / 3];
    for &c in &chosen {
        for &p in &grid.connectivity[8 * c..8 * c + 8] {
            used[p as usize] = true;
        }
    }
    let mut new_id = vec![-1i64; used.len()];
    let mut points = Vec::new();
    let mut values = Vec::new();
    for (p, _) in used.iter().enumerate().filter(|&(_, &u)| u) {
        new_id[p] = (points.len() / 3) as i64;
        points.extend_from_slice(&grid.points[3 * p..3 * p + 3]);
        values.push(grid.point_arrays[0].values[p]);
    }
    let connectivity: Vec<i64> = chosen
        .iter()
        .flat_map(|&c| {
            grid.connectivity[8 * c..8 * c + 8]
                .iter()
                .map(|&p| new_id[p as usize])
        })
        .collect();
    CellGrid {
        points,
        offsets: (0..=chosen.len()).map(|i| 8 * i).collect(),
        connectivity,
        types: vec![12; chosen.len()],
        point_arrays: vec![CellArray {
            values,
            ..grid.point_arrays[0].clone()
        }],
        ..grid.clone()
    }
}

fn main() -> ExitCode {
    let Some(universe) = tetray_distributed::mpi::initialize() else {
        eprintln!("error: MPI is already initialised");
        return ExitCode::FAILURE;
    };
    let world = universe.world();
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let args: Vec<String> = std::env::args().skip(1).collect();
    let use_cells = args.first().is_some_and(|a| a == "cells");
    let output = args.iter().find(|a| *a != "cells").cloned();
    let view = InSituView {
        width: 96,
        height: 72,
        azimuth: 70.0,
        elevation: 15.0,
        ..InSituView::default()
    };
    let (whole, result) = if use_cells {
        let grid = hex_grid();
        let whole = assemble_at(grid.clone(), "whole", &ReadOptions::default(), DVec3::ZERO)
            .expect("a valid grid")
            .mesh;
        let part = hex_slab(&grid, rank, size);
        (whole, render_in_situ_cells(&world, part, "s", &view))
    } else {
        let whole = whole_mesh();
        let part = spatial_split(&whole, rank, size);
        let points: Vec<[f64; 3]> = part
            .points
            .iter()
            .map(|p| p.as_dvec3().to_array())
            .collect();
        let mesh = RankMesh {
            points: &points,
            tets: &part.tets,
            scalars: &part.fields[0].values,
        };
        let result = render_in_situ(&world, mesh, &view);
        (whole, result)
    };
    let frame = match result {
        Ok(frame) => frame,
        Err(e) => {
            eprintln!("error: rank {rank}: {e}");
            world.abort(1);
        }
    };
    let Some(frame) = frame else {
        return ExitCode::SUCCESS;
    };
    println!("{}", frame.report.describe());
    if let Some(path) = output
        && let Err(e) = frame.image.write_exr(std::path::Path::new(&path))
    {
        eprintln!("error: {e}");
        return ExitCode::FAILURE;
    }
    // The whole mesh in this one process, through the engine as `tetray
    // render` makes a frame.
    let loaded = prepare(whole).expect("a valid mesh");
    let source = Source::Mesh {
        mesh: Box::new(loaded),
        name: "the whole mesh".into(),
    };
    let setup = tetray_engine::prepare(source, &view.frame_options(), Log::quiet())
        .expect("the single-process setup");
    let reference = Engine::Cpu
        .render(
            &setup,
            &setup.camera,
            WalkOptions::default(),
            (view.width, view.height),
            None,
        )
        .expect("a frame");
    let worst = frame
        .image
        .rgba
        .iter()
        .zip(&reference.image.rgba)
        .flat_map(|(a, b)| (0..4).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0f32, f32::max);
    let lit = reference.image.rgba.iter().filter(|p| p[3] > 0.0).count();
    let what = if use_cells { "cells" } else { "tetrahedra" };
    println!(
        "in situ ({what}) over {size} ranks: max error {worst:e} against one process ({lit} \
         pixels lit)"
    );
    if worst > 9e-7 || lit < 1000 {
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
