//! Geometric coincidences that render fine but are worth a warning:
//! duplicate points and boundary faces lying on each other (seams).

use glam::Vec3;
use rayon::prelude::*;

use crate::Topology;

/// For every point, the lowest index of a point with exactly the same
/// coordinates (itself when it is unique). `-0.0` equals `0.0`.
pub(crate) fn duplicate_points(points: &[Vec3]) -> Vec<u32> {
    let bits = |p: Vec3| p.to_array().map(|c| (c + 0.0).to_bits());
    // Keys sorted with their points' indices beside them: no comparison
    // reads the point array.
    let mut keyed: Vec<([u32; 3], u32)> = points
        .par_iter()
        .enumerate()
        .map(|(i, &p)| (bits(p), i as u32))
        .collect();
    keyed.par_sort_unstable();
    let mut canonical: Vec<u32> = (0..points.len() as u32).collect();
    for run in keyed.chunk_by(|a, b| a.0 == b.0) {
        // Sorted by index within a run, so run[0] is the lowest.
        for &(_, i) in &run[1..] {
            canonical[i as usize] = run[0].1;
        }
    }
    canonical
}

/// Number of boundary faces whose three corners coincide with those of
/// another boundary face (`canonical` from [`duplicate_points`]).
pub(crate) fn coincident_boundary_faces(topology: &Topology, canonical: &[u32]) -> usize {
    let mut keys: Vec<[u32; 3]> = topology
        .boundary_faces
        .par_iter()
        .map(|face| {
            let mut k = face.vertices.map(|v| canonical[v as usize]);
            k.sort_unstable();
            k
        })
        .collect();
    keys.par_sort_unstable();
    keys.chunk_by(|a, b| a == b)
        .filter(|run| run.len() > 1)
        .map(<[_]>::len)
        .sum()
}
