//! Test meshes, rays and helpers shared by the boundary-BVH tests.
#![allow(dead_code)] // each test binary uses a different subset

pub mod meshes;
pub mod rays;

use std::collections::HashMap;

use tetray_core::watertight::{Crossing, RayFrame, cross_triangle};
use tetray_mesh::{BoundaryFace, FACE_VERTICES, NO_NEIGHBOR, TetMesh, Topology};

/// Face adjacency by matching sorted vertex triples. Stands in for
/// `tetray_mesh::Topology::build` (written in parallel) and doubles as an
/// independent check of it: boundary faces come out in (tet, local face)
/// order with the vertex order of `FACE_VERTICES` (outward, CCW).
pub fn topology(mesh: &TetMesh) -> Topology {
    let mut open: HashMap<[u32; 3], (u32, usize)> = HashMap::new();
    let mut neighbors = vec![[NO_NEIGHBOR; 4]; mesh.tets.len()];
    for (t, tet) in (0u32..).zip(&mesh.tets) {
        for (f, local) in FACE_VERTICES.iter().enumerate() {
            let mut key = local.map(|i| tet[i]);
            key.sort_unstable();
            if let Some((other, of)) = open.remove(&key) {
                neighbors[t as usize][f] = other;
                neighbors[other as usize][of] = t;
            } else {
                open.insert(key, (t, f));
            }
        }
    }
    let mut boundary_faces = Vec::new();
    for (t, tet) in (0u32..).zip(&mesh.tets) {
        for (f, local) in FACE_VERTICES.iter().enumerate() {
            if neighbors[t as usize][f] == NO_NEIGHBOR {
                boundary_faces.push(BoundaryFace {
                    tet: t,
                    local_face: f as u8,
                    vertices: local.map(|i| tet[i]),
                });
            }
        }
    }
    Topology {
        neighbors,
        boundary_faces,
    }
}

/// Every crossing of the whole line of `ray` with the boundary, by the
/// shared predicate, as `(face, crossing)` sorted by distance then face.
pub fn line_crossings(mesh: &TetMesh, topo: &Topology, ray: &RayFrame) -> Vec<(u32, Crossing)> {
    let mut out: Vec<(u32, Crossing)> = (0u32..)
        .zip(&topo.boundary_faces)
        .filter_map(|(i, face)| {
            let [a, b, c] = face.vertices.map(|v| ray.project(mesh.points[v as usize]));
            cross_triangle(a, b, c).map(|x| (i, x))
        })
        .collect();
    out.sort_by(|a, b| a.1.t.total_cmp(&b.1.t).then(a.0.cmp(&b.0)));
    out
}

/// The nearest leaving crossing with `t >= t_from` (the exit after an entry).
pub fn next_exit(
    mesh: &TetMesh,
    topo: &Topology,
    ray: &RayFrame,
    t_from: f32,
) -> Option<(u32, f32)> {
    line_crossings(mesh, topo, ray)
        .into_iter()
        .find(|(_, x)| !x.entering && x.t >= t_from)
        .map(|(f, x)| (f, x.t))
}

/// SplitMix64: a small deterministic generator so the tests need no crate.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}
