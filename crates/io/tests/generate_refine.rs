//! Refinement of PLOT3D grids (`generate::refine`): counts per level,
//! interpolation of coordinates and solution, IBLANK, collapsed cells, the
//! refined mesh's conformity and volume, and the factors chosen for a
//! requested tetrahedron count. Small synthetic grids only.

use std::f32::consts::PI;

use tetray_io::generate::GenerateError;
use tetray_io::generate::{Refinement, RefinementPlan, near_uniform_factors, refine};
use tetray_io::plot3d::{
    Plot3dGrid, Plot3dSolution, Plot3dSource, plot3d_split_counts, write_plot3d_q, write_plot3d_xyz,
};
use tetray_io::{LoadedMesh, load_plot3d_bytes};
use tetray_mesh::structured::{boundary_quad_count, hex_count};
use tetray_mesh::{NO_NEIGHBOR, Topology};

/// A `dims` grid filling the unit box, its interior bent by a smooth
/// displacement that vanishes across each side, so every boundary quad
/// stays in its side's plane (the volume is 1 at any refinement) while the
/// cells are curved; the solution varies nonlinearly.
fn box_grid(dims: [usize; 3]) -> Plot3dGrid {
    let n: usize = dims.iter().product();
    let mut xyz = [vec![0f32; n], vec![0f32; n], vec![0f32; n]];
    let mut q: [Vec<f32>; 5] = std::array::from_fn(|_| vec![0f32; n]);
    for p in 0..n {
        let (i, j, k) = (
            p % dims[0],
            (p / dims[0]) % dims[1],
            p / (dims[0] * dims[1]),
        );
        let u = [i, j, k].map(|c| c as f32);
        let s = [0, 1, 2].map(|a| u[a] / (dims[a] - 1) as f32);
        let bend = |a: usize, b: usize| 0.04 * (PI * s[a]).sin() * (PI * s[b]).cos();
        let x = s[0] + bend(0, 1);
        let y = s[1] + bend(1, 2);
        let z = s[2] + bend(2, 0);
        xyz[0][p] = x;
        xyz[1][p] = y;
        xyz[2][p] = z;
        q[0][p] = 1.0 + 0.5 * x * y + z * z;
        q[1][p] = (3.0 * x).sin();
        q[2][p] = y - z;
        q[3][p] = x * y * z;
        q[4][p] = 2.5 + (x + y).cos();
    }
    Plot3dGrid {
        dims,
        xyz,
        iblank: None,
        solution: Some(Plot3dSolution {
            conditions: [0.5, 2.0, 1.0e6, 0.0],
            q,
        }),
    }
}

fn files(source: &impl Plot3dSource) -> (Vec<u8>, Vec<u8>) {
    let (mut xyz, mut q) = (Vec::new(), Vec::new());
    write_plot3d_xyz(source, &mut xyz).unwrap();
    write_plot3d_q(source, &mut q).unwrap();
    (xyz, q)
}

fn load(source: &impl Plot3dSource) -> LoadedMesh {
    let (xyz, q) = files(source);
    load_plot3d_bytes(&xyz, Some(&q), "refined").unwrap()
}

fn volume(loaded: &LoadedMesh) -> f64 {
    (0..loaded.mesh.tets.len())
        .map(|t| loaded.mesh.signed_volume(t))
        .sum()
}

/// Every interior face has exactly two tetrahedra: the neighbour relation
/// is symmetric, and the faces left unmatched are exactly the two
/// triangles of each boundary quad of the grid.
fn assert_conforming(loaded: &LoadedMesh, dims: [usize; 3]) {
    let topology = Topology::build(&loaded.mesh).unwrap();
    for (t, nbs) in topology.neighbors.iter().enumerate() {
        for &nb in nbs.iter().filter(|&&nb| nb != NO_NEIGHBOR) {
            assert!(topology.shared_face(t as u32, nb).is_some(), "{t} -> {nb}");
        }
    }
    assert_eq!(topology.boundary_faces.len(), 2 * boundary_quad_count(dims));
}

fn index(dims: [usize; 3], i: usize, j: usize, k: usize) -> usize {
    i + dims[0] * (j + dims[1] * k)
}

#[test]
fn each_level_multiplies_the_hexahedra_by_8_and_keeps_the_volume() {
    let grid = box_grid([4, 3, 3]);
    let base = load(&grid);
    assert_eq!(base.mesh.tets.len(), 5 * 12);
    let mut previous = grid.clone();
    for level in 1..=2u32 {
        let refined = Refinement::levels(&grid, level).unwrap();
        let dims = refined.dims();
        assert_eq!(hex_count(dims), 12 * 8usize.pow(level));
        let loaded = load(&refined);
        assert_eq!(loaded.mesh.tets.len(), 5 * hex_count(dims));
        assert_eq!(loaded.report.degenerate_dropped, 0);
        assert_eq!(loaded.report.inverted_fixed, 0);
        assert_conforming(&loaded, dims);
        // Planar boundary quads bound the same box at every level.
        let (v0, v) = (volume(&base), volume(&loaded));
        assert!((v - v0).abs() <= 1e-5 * v0, "level {level}: {v} vs {v0}");
        assert!((v - 1.0).abs() < 1e-5, "{v}");
        // Doubling the previous level gives the same grid as doubling
        // `level` times at once, up to f32 rounding of the intermediate.
        let again = refine(&previous, [2, 2, 2]).unwrap();
        let direct = Plot3dGrid::from_source(&refined);
        assert_eq!(again.dims, direct.dims);
        assert_close(&again, &direct, 4.0 * f32::EPSILON);
        previous = again;
    }
}

fn assert_close(a: &Plot3dGrid, b: &Plot3dGrid, tolerance: f32) {
    let pairs = a.xyz.iter().zip(&b.xyz).chain(
        a.solution
            .iter()
            .zip(&b.solution)
            .flat_map(|(s, t)| s.q.iter().zip(&t.q)),
    );
    for (x, y) in pairs {
        let scale = x.iter().fold(1f32, |m, v| m.max(v.abs()));
        for (p, (u, v)) in x.iter().zip(y).enumerate() {
            assert!((u - v).abs() <= tolerance * scale, "point {p}: {u} vs {v}");
        }
    }
}

#[test]
fn refined_values_interpolate_the_source() {
    let grid = box_grid([4, 3, 3]);
    let refined = refine(&grid, [2, 2, 2]).unwrap();
    let (sd, rd) = (grid.dims, refined.dims);
    assert_eq!(rd, [7, 5, 5]);
    assert_eq!(
        refined.solution.as_ref().unwrap().conditions,
        grid.solution.as_ref().unwrap().conditions
    );
    let arrays = |g: &Plot3dGrid| -> Vec<Vec<f32>> {
        let mut all = g.xyz.to_vec();
        all.extend(g.solution.clone().unwrap().q);
        all
    };
    let (source, fine) = (arrays(&grid), arrays(&refined));
    let mean = |a: &[f32], points: &[usize]| -> f32 {
        let sum: f64 = points.iter().map(|&p| f64::from(a[p])).sum();
        (sum / points.len() as f64) as f32
    };
    for (a, (s, f)) in source.iter().zip(&fine).enumerate() {
        for k in 0..sd[2] {
            for j in 0..sd[1] {
                for i in 0..sd[0] {
                    // Every source point is kept bit for bit.
                    let at = f[index(rd, 2 * i, 2 * j, 2 * k)];
                    assert_eq!(at, s[index(sd, i, j, k)], "array {a} at {i},{j},{k}");
                }
            }
        }
        let close = |x: f32, y: f32, what: &str| {
            assert!(
                (x - y).abs() <= 2.0 * f32::EPSILON * x.abs().max(1.0),
                "{what}: {x} vs {y}"
            );
        };
        for k in 0..sd[2] - 1 {
            for j in 0..sd[1] - 1 {
                for i in 0..sd[0] - 1 {
                    let s_at = |di, dj, dk| index(sd, i + di, j + dj, k + dk);
                    // Edge midpoints are the mean of the edge's ends, face
                    // centres of 4 corners, cell centres of 8.
                    let edge = f[index(rd, 2 * i + 1, 2 * j, 2 * k)];
                    close(edge, mean(s, &[s_at(0, 0, 0), s_at(1, 0, 0)]), "edge");
                    let face = f[index(rd, 2 * i + 1, 2 * j + 1, 2 * k)];
                    let corners = [s_at(0, 0, 0), s_at(1, 0, 0), s_at(0, 1, 0), s_at(1, 1, 0)];
                    close(face, mean(s, &corners), "face");
                    let centre = f[index(rd, 2 * i + 1, 2 * j + 1, 2 * k + 1)];
                    let all: Vec<usize> =
                        (0..8).map(|c| s_at(c & 1, (c >> 1) & 1, c >> 2)).collect();
                    close(centre, mean(s, &all), "centre");
                }
            }
        }
    }
}

#[test]
fn refinement_is_deterministic() {
    let grid = box_grid([5, 4, 3]);
    let refinement = Refinement::new(&grid, [3, 2, 2]).unwrap();
    assert_eq!(files(&refinement), files(&refinement));
    // The lazy source and the grid held in memory write the same bytes.
    assert_eq!(
        files(&refinement),
        files(&Plot3dGrid::from_source(&refinement))
    );
}

#[test]
fn blanked_cells_stay_blanked_and_kept_cells_stay_kept() {
    let mut grid = box_grid([5, 4, 3]);
    let mut iblank = vec![1; 60];
    // An interior point: the 8 hexahedra around it are blanked.
    iblank[index(grid.dims, 2, 1, 1)] = 0;
    // A fringe value (another grid's number) must not blank anything.
    iblank[index(grid.dims, 0, 0, 0)] = -2;
    grid.iblank = Some(iblank);
    let base = load(&grid);
    assert_eq!(base.mesh.tets.len(), 5 * (24 - 8));
    for factors in [[2, 2, 2], [3, 2, 1]] {
        let product: usize = factors.iter().product();
        let refinement = Refinement::new(&grid, factors).unwrap();
        let counts = plot3d_split_counts(&refinement);
        assert_eq!(counts.blanked_hexahedra, 8 * product, "{factors:?}");
        let loaded = load(&refinement);
        assert_eq!(loaded.mesh.tets.len(), 5 * 16 * product);
        assert_eq!(counts.tets, loaded.mesh.tets.len());
        // The corner keeps its fringe flag, the blanked point its 0.
        let rd = refinement.dims();
        assert_eq!(refinement.iblank(0), -2);
        let [fi, fj, fk] = factors;
        assert_eq!(refinement.iblank(index(rd, 2 * fi, fj, fk)), 0);
    }
}

#[test]
fn collapsed_cells_lose_their_flat_tetrahedra_and_the_counts_are_exact() {
    // As in Blunt Fin: points (i, 0, 0) and (i, 1, 0) coincide.
    let mut grid = box_grid([5, 4, 3]);
    for i in 0..5 {
        for a in 0..3 {
            let below = grid.xyz[a][index(grid.dims, i, 0, 0)];
            grid.xyz[a][index(grid.dims, i, 1, 0)] = below;
        }
    }
    let base = load(&grid);
    assert!(base.report.degenerate_dropped > 0);
    for factors in [[2, 2, 2], [2, 3, 2]] {
        let plan = RefinementPlan::for_factors(&grid, factors).unwrap();
        let loaded = load(&Refinement::new(&grid, factors).unwrap());
        assert_eq!(plan.counts.tets, loaded.mesh.tets.len(), "{factors:?}");
        assert_eq!(
            plan.counts.degenerate_dropped,
            loaded.report.degenerate_dropped
        );
        assert!(plan.counts.degenerate_dropped > base.report.degenerate_dropped);
        // The collapsed side's refined points coincide bit for bit: the
        // points (I, J, 0) with 0 < J <= fj repeat (I, 0, 0).
        let refined_ni = 4 * factors[0] + 1;
        assert_eq!(
            loaded.report.validation.duplicate_points,
            refined_ni * factors[1]
        );
        let (v0, v) = (volume(&base), volume(&loaded));
        assert!((v - v0).abs() <= 1e-5 * v0, "{factors:?}: {v} vs {v0}");
    }
}

#[test]
fn near_uniform_factors_grow_one_axis_at_a_time() {
    // Fewest cells first: k (2 cells), then j (3), then i (4).
    let factors: Vec<[usize; 3]> = near_uniform_factors([5, 4, 3]).take(7).collect();
    assert_eq!(
        factors,
        [
            [1, 1, 1],
            [1, 1, 2],
            [1, 2, 2],
            [2, 2, 2],
            [2, 2, 3],
            [2, 3, 3],
            [3, 3, 3]
        ]
    );
}

#[test]
fn the_plan_is_the_smallest_refinement_reaching_the_request() {
    let grid = box_grid([5, 4, 3]);
    // 24 hexahedra, 120 tetrahedra.
    for requested in [1, 120, 121, 500, 1000, 3000, 7000] {
        let plan = RefinementPlan::for_tets(&grid, requested).unwrap();
        assert!(plan.counts.tets >= requested, "{requested}: {plan:?}");
        let all: Vec<[usize; 3]> = near_uniform_factors(grid.dims).take(40).collect();
        let at = all.iter().position(|&f| f == plan.factors).unwrap();
        if at > 0 {
            let smaller = RefinementPlan::for_factors(&grid, all[at - 1]).unwrap();
            assert!(smaller.counts.tets < requested, "{requested}: {smaller:?}");
        }
        assert_eq!(
            plan.counts.tets,
            load(&Refinement::new(&grid, plan.factors).unwrap())
                .mesh
                .tets
                .len()
        );
    }
    assert_eq!(
        RefinementPlan::for_tets(&grid, 121).unwrap().factors,
        [1, 1, 2]
    );
    assert_eq!(
        RefinementPlan::for_level(&grid, 1).unwrap().factors,
        [2, 2, 2]
    );
    assert!(matches!(
        RefinementPlan::for_tets(&grid, 0),
        Err(GenerateError::TetCount { .. })
    ));
    assert!(matches!(
        RefinementPlan::for_tets(&grid, usize::MAX),
        Err(GenerateError::TetCount { .. })
    ));
    assert!(matches!(
        Refinement::new(&grid, [0, 1, 1]),
        Err(GenerateError::ZeroFactor { .. })
    ));
    let huge = Refinement::new(&grid, [5000, 5000, 5000]).unwrap_err();
    assert!(huge.to_string().contains("at most"), "{huge}");
}

#[test]
fn a_concave_corner_refines_on_its_tetrahedra_without_folds() {
    // Two cells along i; their shared corner (1, 0, 0), on the boundary
    // edge j = k = 0, pushed inwards until the trilinear map of both cells
    // inverts there (as at the Combustor's two concave cells). The split
    // with diagonals through that point is still valid.
    let mut grid = box_grid([3, 2, 2]);
    let c = index(grid.dims, 1, 0, 0);
    grid.xyz[1][c] += 0.55;
    grid.xyz[2][c] += 0.55;
    let base = load(&grid);
    assert_eq!(base.report.inverted_fixed, 0);
    assert_eq!(base.report.degenerate_dropped, 0);
    for factors in [[2, 2, 2], [3, 3, 3], [4, 4, 4], [5, 5, 5]] {
        let refinement = Refinement::new(&grid, factors).unwrap();
        assert_eq!(refinement.folded_cells(), 2);
        let plan = RefinementPlan::for_factors(&grid, factors).unwrap();
        assert!(plan.defect().is_none(), "{factors:?}: {plan:?}");
        let loaded = load(&refinement);
        assert_eq!(loaded.report.inverted_fixed, 0, "{factors:?}");
        assert_eq!(loaded.report.degenerate_dropped, 0, "{factors:?}");
        assert_eq!(loaded.mesh.tets.len(), 5 * hex_count(refinement.dims()));
        // Refined boundary triangles lie on the source's (the diagonals
        // through the corner are kept), so the volume is the same.
        let (v0, v) = (volume(&base), volume(&loaded));
        assert!((v - v0).abs() <= 1e-5 * v0, "{factors:?}: {v} vs {v0}");
        // Source points are kept bit for bit.
        let fine = Plot3dGrid::from_source(&refinement);
        let [fi, fj, fk] = factors;
        assert_eq!(fine.xyz[1][index(fine.dims, fi, 0, 0)], grid.xyz[1][c]);
        let centre = index(fine.dims, fi, fj, fk);
        assert_eq!(fine.xyz[0][centre], grid.xyz[0][index(grid.dims, 1, 1, 1)]);
    }
    // Unequal factors can cut the cell at the corner across its
    // tetrahedra's faces and fold it: the plan says so, and the loader
    // indeed has to leave cells of that mesh out (it once rejected it), so
    // a requested count skips such factors.
    let folding = RefinementPlan::for_factors(&grid, [2, 4, 2]).unwrap();
    assert!(folding.defect().is_some());
    let (xyz, q) = files(&Refinement::new(&grid, [2, 4, 2]).unwrap());
    let folded = load_plot3d_bytes(&xyz, Some(&q), "folded").unwrap();
    let changes = folded.report.changes().unwrap();
    assert!(!folded.report.excluded.cells.is_empty(), "{changes}");
    for requested in (20..3000).step_by(97) {
        let plan = RefinementPlan::for_tets(&grid, requested).unwrap();
        assert!(
            plan.defect().is_none() && plan.counts.tets >= requested,
            "{plan:?}"
        );
    }
}

#[test]
fn cells_too_thin_for_f32_are_avoided() {
    // A collapsed edge (as in Blunt Fin) whose wedge cells are only 3e-5
    // wide at their top: cut rj x rk times, the cells beside the edge
    // shrink quadratically below f32 resolution.
    let mut grid = box_grid([5, 4, 3]);
    for k in 0..3 {
        for i in 0..5 {
            let (below, above) = (index(grid.dims, i, 0, k), index(grid.dims, i, 1, k));
            for a in 0..3 {
                grid.xyz[a][above] = grid.xyz[a][below];
            }
            grid.xyz[1][above] += if k == 0 { 0.0 } else { 3e-5 };
        }
    }
    let thin = RefinementPlan::for_factors(&grid, [4, 4, 4]).unwrap();
    assert!(thin.counts.thin > 0 && thin.defect().is_some(), "{thin:?}");
    let (xyz, q) = files(&Refinement::new(&grid, [4, 4, 4]).unwrap());
    // The reader drops the flat tetrahedra, which leaves faces folded onto
    // each other: the loader once rejected the mesh; now they are boundary
    // faces, reported.
    let thin_mesh = load_plot3d_bytes(&xyz, Some(&q), "thin").unwrap();
    let v = &thin_mesh.report.validation;
    assert!(thin_mesh.report.degenerate_dropped > 0);
    assert!(v.folded_face_pairs > 0 && !v.nonconforming_faces.is_empty());
    // 8000 tetrahedra: the near-uniform factors (4, 4, 5) are thin, so
    // others of a similar product are used, and load.
    let first = near_uniform_factors(grid.dims)
        .find(|f| 112 * f.iter().product::<usize>() >= 8000)
        .unwrap();
    assert_eq!(first, [4, 4, 5]);
    assert!(
        RefinementPlan::for_factors(&grid, first)
            .unwrap()
            .defect()
            .is_some()
    );
    let plan = RefinementPlan::for_tets(&grid, 8000).unwrap();
    assert!(
        plan.defect().is_none() && plan.counts.tets >= 8000,
        "{plan:?}"
    );
    let loaded = load(&Refinement::new(&grid, plan.factors).unwrap());
    assert_eq!(loaded.mesh.tets.len(), plan.counts.tets);
}
