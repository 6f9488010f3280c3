//! Space-filling-curve order: points and tetrahedra renumbered along a
//! Morton (Z-order) curve, so that the tetrahedra a ray walks through, and
//! their points, lie close together in memory.
//!
//! The renumbering is a pure relabelling: every tetrahedron keeps its
//! vertices in the same local order (so its orientation, its local faces
//! and every edge function the walk evaluates are unchanged), and the
//! permutations are kept so that ids can be mapped back to the file's
//! numbering ([`Reorder::tet_from`], [`Reorder::point_from`]).

use rayon::prelude::*;
use rdst::RadixSort;
use std::sync::atomic::{AtomicU32, Ordering};
use tetray_mesh::{NO_NEIGHBOR, TetMesh, Topology, boundary_faces_of};

/// Bits per axis of the Morton code (3 x 21 = 63 bits).
const BITS: u32 = 21;

/// The permutations applied to a mesh: new index -> index in the input.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Reorder {
    /// `tet_from[new]`: the input tetrahedron now numbered `new`.
    pub tet_from: Vec<u32>,
    /// `point_from[new]`: the input point now numbered `new`.
    pub point_from: Vec<u32>,
}

/// Spreads the low 21 bits of `v` three apart.
fn spread(v: u64) -> u64 {
    let mut x = v & 0x1f_ffff;
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// Morton code of `p` quantised over the box `lo .. lo + 1 / scale`.
fn morton(p: [f32; 3], lo: [f32; 3], scale: [f32; 3]) -> u64 {
    let max = ((1u32 << BITS) - 1) as f32;
    let q = |i: usize| (((p[i] - lo[i]) * scale[i]).clamp(0.0, 1.0) * max) as u64;
    spread(q(0)) | (spread(q(1)) << 1) | (spread(q(2)) << 2)
}

/// One sort key: the top 32 of the 63 bits of a Morton `code` (10 to 11
/// bits per axis: cells of 1/1500 of the bounds, finer than any cache
/// needs) over the input `index`, so that one 8-byte integer sorts where a
/// (code, index) pair took 16 bytes, equal cells in input order.
fn sort_key(code: u64, index: usize) -> u64 {
    (code >> (3 * BITS - 32)) << 32 | index as u64
}

/// From this many elements the renumbering radix-sorts and inverts in
/// parallel; below, those passes cost more than they save (the Blunt Fin's
/// scene build was 20-30% slower with them).
const LARGE: usize = 1 << 20;

/// Sorts keys made by [`sort_key`]. The keys are distinct (each holds its
/// index), so any sort gives the one increasing order: equal codes in index
/// order. Large arrays take a parallel radix sort (rdst).
fn sort_keys(keys: &mut [u64]) {
    if keys.len() >= LARGE {
        keys.radix_sort_unstable();
    } else {
        keys.par_sort_unstable();
    }
}

/// The inverse of the permutation `from` (`to[from[new]] = new`). Large
/// ones are written in parallel: every slot once, by relaxed atomic stores
/// (plain stores on x86).
pub(crate) fn inverse(from: &[u32]) -> Vec<u32> {
    if from.len() < LARGE {
        let mut to = vec![0u32; from.len()];
        for (new, &old) in from.iter().enumerate() {
            to[old as usize] = new as u32;
        }
        return to;
    }
    let to: Vec<AtomicU32> = (0..from.len())
        .into_par_iter()
        .map(|_| AtomicU32::new(0))
        .collect();
    from.par_iter().enumerate().for_each(|(new, &old)| {
        to[old as usize].store(new as u32, Ordering::Relaxed);
    });
    to.into_par_iter().map(AtomicU32::into_inner).collect()
}

/// Renumbers `mesh` (points, tetrahedra, point fields), `topology` and the
/// active `scalar` along the Morton curve of the mesh
/// bounds: points by their own code, tetrahedra by the code of their
/// centroid (equal codes in input order; [`sort_key`]).
pub(crate) fn morton_reorder(
    mesh: &mut TetMesh,
    topology: &mut Topology,
    scalar: &mut Vec<f32>,
) -> Reorder {
    let (lo, hi) = mesh.bounds();
    let lo = lo.to_array();
    let extent = (hi - glam::Vec3::from_array(lo)).to_array();
    let scale = extent.map(|e| if e > 0.0 { 1.0 / e } else { 0.0 });

    // Tetrahedra, by centroid (of the input points: the same values).
    let points = &mesh.points;
    let mut tet_keys: Vec<u64> = mesh
        .tets
        .par_iter()
        .enumerate()
        .map(|(t, tet)| {
            let c = tet
                .iter()
                .fold(glam::Vec3::ZERO, |c, &v| c + points[v as usize])
                * 0.25;
            sort_key(morton(c.to_array(), lo, scale), t)
        })
        .collect();

    // Points.
    let mut keys: Vec<u64> = mesh
        .points
        .par_iter()
        .enumerate()
        .map(|(i, p)| sort_key(morton(p.to_array(), lo, scale), i))
        .collect();
    sort_keys(&mut keys);
    let point_from: Vec<u32> = keys.par_iter().map(|&k| k as u32).collect();
    let point_to = inverse(&point_from);
    mesh.points = point_from
        .par_iter()
        .map(|&old| mesh.points[old as usize])
        .collect();
    *scalar = point_from
        .par_iter()
        .map(|&old| scalar[old as usize])
        .collect();
    for field in &mut mesh.fields {
        if field.values.len() == point_from.len() {
            field.values = point_from
                .par_iter()
                .map(|&old| field.values[old as usize])
                .collect();
        }
    }

    drop(keys);
    sort_keys(&mut tet_keys);
    let tet_from: Vec<u32> = tet_keys.par_iter().map(|&k| k as u32).collect();
    drop(tet_keys);
    let tet_to = inverse(&tet_from);
    mesh.tets = tet_from
        .par_iter()
        .map(|&old| mesh.tets[old as usize].map(|v| point_to[v as usize]))
        .collect();
    topology.neighbors = tet_from
        .par_iter()
        .map(|&old| {
            topology.neighbors[old as usize].map(|n| {
                if n == NO_NEIGHBOR {
                    NO_NEIGHBOR
                } else {
                    tet_to[n as usize]
                }
            })
        })
        .collect();
    drop(tet_to);
    topology.boundary_faces = boundary_faces_of(&topology.neighbors, &mesh.tets);
    Reorder {
        tet_from,
        point_from,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_interleaves() {
        assert_eq!(spread(0b111), 0b1001001);
        assert_eq!(spread(0x1f_ffff).count_ones(), 21);
        let code = morton([1.0, 0.0, 0.0], [0.0; 3], [1.0; 3]);
        assert_eq!(code, spread(0x1f_ffff));
    }

    /// Both sorts give what a comparison sort of the whole keys gives
    /// (codes from a few cells, so that many tie and the index decides),
    /// and both inverses the inverse permutation.
    #[test]
    fn key_sorts_and_inverses_match_a_comparison_sort() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for (n, cells) in [
            (0, 1),
            (1, 1),
            (1000, 1),
            (5000, 7),
            (70_000, 1 << 20),
            (70_000, 1 << 32),
            (LARGE + 5, 1 << 12),
            (LARGE, 1 << 32),
        ] {
            let mut keys: Vec<u64> = (0..n)
                .map(|i| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    let code = (state % cells) << (3 * BITS - 32 - 1);
                    sort_key(code << 1 | (state >> 63), i)
                })
                .collect();
            let mut want = keys.clone();
            want.sort_unstable();
            let mut want_to = vec![0u32; n];
            for (new, &key) in want.iter().enumerate() {
                want_to[key as u32 as usize] = new as u32;
            }
            sort_keys(&mut keys);
            assert_eq!(keys, want, "{n} keys in {cells} cells");
            let from: Vec<u32> = keys.iter().map(|&k| k as u32).collect();
            assert!(inverse(&from) == want_to, "inverse of {n}");
        }
    }

    #[test]
    fn sort_keys_order_cells_then_indices() {
        let top = 1u64 << 62;
        assert_eq!(sort_key(top, 7), (1 << 31) << 32 | 7);
        // Codes that differ only below the kept bits tie, broken by index.
        assert!(sort_key(5, 2) < sort_key(1, 3));
        assert!(sort_key(top, 0) > sort_key(top - 1, u32::MAX as usize));
    }
}
