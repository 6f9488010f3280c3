//! Face-neighbour graph: which tetrahedron lies across each face, and the
//! boundary faces.
//!
//! Faces are matched by sorting, not hashing: every face of every
//! tetrahedron becomes one `u128` holding its three sorted point indices
//! above `4 * tet + local_face`; after a parallel sort equal faces are
//! adjacent, and each run of equal point triples is one mesh face.

use rayon::prelude::*;

use crate::{BoundaryFace, MeshError, TetMesh, Topology, FACE_VERTICES, NO_NEIGHBOR};

/// Largest number of tetrahedra: `4 * tet + face` must fit in 32 bits, and
/// `u32::MAX` is [`NO_NEIGHBOR`].
pub const MAX_TETS: usize = (u32::MAX / 4) as usize;

/// Sort key of local face `f` of `tet`: sorted point indices, then the
/// face's id `4 * tet + f` in the low 32 bits.
fn face_key(tet: &[u32; 4], id: u32, f: usize) -> u128 {
    let [a, b, c] = FACE_VERTICES[f];
    let mut v = [tet[a], tet[b], tet[c]];
    v.sort_unstable();
    (u128::from(v[0]) << 96) | (u128::from(v[1]) << 64) | (u128::from(v[2]) << 32) | u128::from(id)
}

/// The sorted point triple of a key (the face without its id).
fn key_face(key: u128) -> u128 {
    key >> 32
}

fn key_id(key: u128) -> u32 {
    // The low 32 bits are the id by construction.
    (key & u128::from(u32::MAX)) as u32
}

fn key_vertices(key: u128) -> [u32; 3] {
    [(key >> 96) as u32, (key >> 64) as u32, (key >> 32) as u32]
}

impl Topology {
    /// Matches the faces of `mesh`'s tetrahedra.
    ///
    /// Only point indices are used (no coordinates), so this works on any
    /// mesh; the boundary faces are outward oriented when the tetrahedra
    /// are positively oriented. Boundary faces are listed by tetrahedron,
    /// then local face.
    ///
    /// # Errors
    /// [`MeshError::NonManifoldFace`] when a face belongs to more than two
    /// tetrahedra (naming them); [`MeshError::TooLarge`] beyond 2^30 - 1
    /// tetrahedra.
    pub fn build(mesh: &TetMesh) -> Result<Topology, MeshError> {
        let n = mesh.tets.len();
        if n > MAX_TETS {
            return Err(MeshError::TooLarge {
                what: "tetrahedra",
                count: n,
                max: MAX_TETS,
            });
        }
        let mut keys: Vec<u128> = mesh
            .tets
            .par_iter()
            .enumerate()
            .flat_map_iter(|(t, tet)| {
                // t < MAX_TETS, so 4 t + 3 fits in u32.
                let base = 4 * t as u32;
                (0..4).map(move |f| face_key(tet, base + f as u32, f))
            })
            .collect();
        keys.par_sort_unstable();

        let mut neighbors = vec![[NO_NEIGHBOR; 4]; n];
        let mut start = 0;
        while start < keys.len() {
            let face = key_face(keys[start]);
            let mut end = start + 1;
            while end < keys.len() && key_face(keys[end]) == face {
                end += 1;
            }
            match end - start {
                1 => {}
                2 => {
                    let (a, b) = (key_id(keys[start]), key_id(keys[start + 1]));
                    neighbors[(a / 4) as usize][(a % 4) as usize] = b / 4;
                    neighbors[(b / 4) as usize][(b % 4) as usize] = a / 4;
                }
                _ => {
                    return Err(MeshError::NonManifoldFace {
                        vertices: key_vertices(keys[start]),
                        tets: keys[start..end].iter().map(|&k| key_id(k) / 4).collect(),
                    })
                }
            }
            start = end;
        }
        drop(keys);

        let mut boundary_faces = Vec::new();
        let mut boundary_index = vec![[u32::MAX; 4]; n];
        for (t, (nb, tet)) in neighbors.iter().zip(&mesh.tets).enumerate() {
            for f in 0..4 {
                if nb[f] == NO_NEIGHBOR {
                    boundary_index[t][f] = boundary_faces.len() as u32;
                    boundary_faces.push(BoundaryFace {
                        tet: t as u32,
                        local_face: f as u8,
                        vertices: FACE_VERTICES[f].map(|v| tet[v]),
                    });
                }
            }
        }
        Ok(Topology {
            neighbors,
            boundary_faces,
            boundary_index,
        })
    }

    /// The local face of `neighbor` that is shared with `tet`, if they are
    /// face neighbours.
    pub fn shared_face(&self, tet: u32, neighbor: u32) -> Option<usize> {
        self.neighbors
            .get(neighbor as usize)?
            .iter()
            .position(|&t| t == tet)
    }

    /// Connected components through shared faces: `(count, label per
    /// tetrahedron)`, labels numbered from 0 in order of first tetrahedron.
    pub fn components(&self) -> (usize, Vec<u32>) {
        let n = self.neighbors.len();
        let mut label = vec![u32::MAX; n];
        let mut count = 0u32;
        let mut stack = Vec::new();
        for seed in 0..n {
            if label[seed] != u32::MAX {
                continue;
            }
            label[seed] = count;
            stack.push(seed as u32);
            while let Some(t) = stack.pop() {
                for &nb in &self.neighbors[t as usize] {
                    if nb != NO_NEIGHBOR && label[nb as usize] == u32::MAX {
                        label[nb as usize] = count;
                        stack.push(nb);
                    }
                }
            }
            count += 1;
        }
        (count as usize, label)
    }
}
