//! Build time per preset and query throughput on the Oxygen Post boundary.
//! Ignored by default (it is a measurement, not a check):
//! `cargo test -p tetray-boundary-bvh --test measure -- --ignored --nocapture`
//! (the `test` profile is opt-level 2; build times are obvhs' core time, so
//! its debug-build validation is not counted).

mod support;

use std::path::Path;
use std::time::Instant;

use glam::Vec3;
use support::meshes::{orient_or_keep, Grid, Split};
use support::rays::random_dir;
use support::{topology, Rng};
use tetray_boundary_bvh::watertight::RayFrame;
use tetray_boundary_bvh::{brute_force_first_entry, BoundaryBvh, BuildPreset};
use tetray_mesh::TetMesh;

const DATA: &str = "/work/shared/data/plot3d";
const GRIDS: [(&str, &str); 3] = [
    ("Oxygen Post", "postxyz.bin"),
    ("Blunt Fin", "bluntfinxyz.bin"),
    ("Combustor", "combxyz.bin"),
];

/// Minimal PLOT3D grid reader for this measurement only (big-endian single
/// grid, optional IBLANK), split 5 tets per hex with alternating parity.
/// Stands in until the mesh crate's reader lands.
fn plot3d_tets(file: &str) -> Option<TetMesh> {
    let bytes = std::fs::read(Path::new(DATA).join(file)).ok()?;
    let word = |i: usize| -> [u8; 4] { bytes[4 * i..4 * i + 4].try_into().unwrap() };
    let dims = [0, 1, 2].map(|i| i32::from_be_bytes(word(i)) as usize);
    let n = dims[0] * dims[1] * dims[2];
    assert!(
        bytes.len() == 12 + 12 * n || bytes.len() == 12 + 16 * n,
        "unexpected size"
    );
    let coord = |axis: usize, p: usize| f32::from_be_bytes(word(3 + axis * n + p));
    let points = (0..n)
        .map(|p| Vec3::new(coord(0, p), coord(1, p), coord(2, p)))
        .collect();
    // Reuse the test grid's connectivity (same point order: i fastest).
    let grid = Grid {
        n: dims.map(|d| d - 1),
        origin: Vec3::ZERO,
        h: 1.0,
        split: Split::Five,
    };
    let mut mesh = grid.mesh(|_, _, _| true);
    mesh.points = points;
    orient_or_keep(&mut mesh);
    Some(mesh)
}

#[test]
#[ignore = "measurement; run with --ignored --nocapture"]
fn presets_on_the_dissertation_grids() {
    for (name, file) in GRIDS {
        let Some(mesh) = plot3d_tets(file) else {
            eprintln!("SKIPPED: {DATA}/{file} not found");
            continue;
        };
        measure(name, &mesh);
    }
}

fn measure(name: &str, mesh: &TetMesh) {
    let mesh = mesh.clone();
    let topo = topology(&mesh);
    let (lo, hi) = mesh
        .points
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    println!(
        "{name}: {} points, {} tets, {} boundary faces, bounds {lo} .. {hi}",
        mesh.points.len(),
        mesh.tets.len(),
        topo.boundary_faces.len()
    );

    // Primary rays: a 256x256 pinhole view from outside, aimed at the middle.
    let centre = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    let eye = centre + Vec3::new(1.3, 0.7, 1.9).normalize() * radius * 2.5;
    let forward = (centre - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let res = 256;
    let primary: Vec<RayFrame> = (0..res * res)
        .map(|i| {
            let (x, y) = (
                (i % res) as f32 / res as f32 - 0.5,
                (i / res) as f32 / res as f32 - 0.5,
            );
            RayFrame::new(eye, forward + (right * x + up * y) * 0.9)
        })
        .collect();
    // Re-entry style: from random points inside the mesh, random directions.
    let mut rng = Rng::new(5);
    let inside: Vec<RayFrame> = (0..res * res)
        .map(|_| {
            RayFrame::new(
                support::rays::point_inside(&mesh, &mut rng),
                random_dir(&mut rng),
            )
        })
        .collect();

    println!(
        "{:>10} {:>9} {:>8} {:>7} {:>6} {:>12} {:>12} {:>7}",
        "preset", "build ms", "nodes", "leaves", "depth", "primary/s", "inside/s", "hits"
    );
    let mut reference = None;
    for preset in BuildPreset::ALL {
        let bvh = (0..3)
            .map(|_| BoundaryBvh::build(&mesh, &topo, preset).expect("build"))
            .min_by_key(|b| b.stats().build_time)
            .unwrap();
        let s = bvh.stats();
        // Best of three passes: the machine is shared, the minimum is the
        // least disturbed.
        let rate = |rays: &[RayFrame]| {
            let mut best = 0.0f64;
            let mut hits = 0;
            for _ in 0..3 {
                let start = Instant::now();
                hits = rays
                    .iter()
                    .filter(|r| bvh.first_entry(r, 0.0, f32::INFINITY, &[]).is_some())
                    .count();
                best = best.max(rays.len() as f64 / start.elapsed().as_secs_f64());
            }
            (best, hits)
        };
        let (primary_rate, primary_hits) = rate(&primary);
        let (inside_rate, inside_hits) = rate(&inside);
        // Every preset must agree on the hit counts (full agreement is checked
        // by the other tests).
        let hits = (primary_hits, inside_hits);
        assert_eq!(*reference.get_or_insert(hits), hits);
        println!(
            "{:>10} {:>9.1} {:>8} {:>7} {:>6} {:>12.0} {:>12.0} {:>7}",
            preset.name(),
            s.build_time.as_secs_f64() * 1e3,
            s.nodes,
            s.leaves,
            s.max_depth,
            primary_rate,
            inside_rate,
            primary_hits
        );
    }
    let start = Instant::now();
    let sample = &primary[..500];
    for r in sample {
        brute_force_first_entry(&mesh, &topo, r, 0.0, f32::INFINITY, &[]);
    }
    println!(
        "brute force: {:.0} rays/s",
        sample.len() as f64 / start.elapsed().as_secs_f64()
    );
}
