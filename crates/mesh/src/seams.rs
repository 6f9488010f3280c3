//! Geometric coincidences that render fine but are worth a warning:
//! duplicate points and boundary faces lying on each other (seams).

use glam::Vec3;
use rayon::prelude::*;

use crate::Topology;

/// For every point, the lowest index of a point with exactly the same
/// coordinates (itself when it is unique). `-0.0` equals `0.0`.
pub(crate) fn duplicate_points(points: &[Vec3]) -> Vec<u32> {
    let bits = |p: Vec3| p.to_array().map(|c| (c + 0.0).to_bits());
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    order.par_sort_unstable_by_key(|&i| (bits(points[i as usize]), i));
    let mut canonical: Vec<u32> = (0..points.len() as u32).collect();
    for run in order.chunk_by(|&a, &b| bits(points[a as usize]) == bits(points[b as usize])) {
        // Sorted by index within a run, so run[0] is the lowest.
        for &i in &run[1..] {
            canonical[i as usize] = run[0];
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
