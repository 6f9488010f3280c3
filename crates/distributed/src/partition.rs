//! Which part of the mesh each rank renders: a contiguous run of a
//! parallel file's pieces, or, for a mesh in one file, a spatial slab of
//! its tetrahedra.

use std::ops::Range;

use tetray_mesh::{ScalarField, TetMesh};

/// The pieces rank `rank` of `ranks` loads: a contiguous run, the runs'
/// lengths differing by at most one (neighbouring pieces, usually
/// neighbours in space, stay on one rank). Empty when there are more ranks
/// than pieces.
pub fn pieces_for_rank(pieces: usize, rank: usize, ranks: usize) -> Range<usize> {
    let ranks = ranks.max(1);
    (rank * pieces / ranks)..((rank + 1) * pieces / ranks)
}

/// The tetrahedra of `mesh` rank `rank` of `ranks` renders, as a mesh of
/// their own (points they use, in the input's order, with every field):
/// the tetrahedra sorted by centroid along the longest axis of the bounds
/// (ties by index, so every rank computes the same order) and cut into
/// `ranks` runs of equal count. Every tetrahedron goes to exactly one rank.
pub fn spatial_split(mesh: &TetMesh, rank: usize, ranks: usize) -> TetMesh {
    let ranks = ranks.max(1);
    let (lo, hi) = mesh.bounds();
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let key = |t: &[u32; 4]| -> f32 { t.iter().map(|&v| mesh.points[v as usize][axis]).sum() };
    let mut order: Vec<usize> = (0..mesh.tets.len()).collect();
    order.sort_by(|&a, &b| {
        key(&mesh.tets[a])
            .total_cmp(&key(&mesh.tets[b]))
            .then(a.cmp(&b))
    });
    let n = order.len();
    let mut mine: Vec<usize> = order[rank * n / ranks..(rank + 1) * n / ranks].to_vec();
    mine.sort_unstable();
    subset(mesh, &mine)
}

/// The tetrahedra `tets` of `mesh` with the points they use (renumbered in
/// the input's order) and every field.
pub fn subset(mesh: &TetMesh, tets: &[usize]) -> TetMesh {
    let mut new_id = vec![u32::MAX; mesh.points.len()];
    for &t in tets {
        for &v in &mesh.tets[t] {
            new_id[v as usize] = 0;
        }
    }
    let mut kept = Vec::new();
    for (old, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = kept.len() as u32;
            kept.push(old);
        }
    }
    TetMesh {
        points: kept.iter().map(|&p| mesh.points[p]).collect(),
        tets: tets
            .iter()
            .map(|&t| mesh.tets[t].map(|v| new_id[v as usize]))
            .collect(),
        fields: mesh
            .fields
            .iter()
            .map(|f| ScalarField {
                name: f.name.clone(),
                values: kept.iter().map(|&p| f.values[p]).collect(),
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn pieces_are_shared_out_whole_and_once() {
        for (pieces, ranks) in [(8, 3), (2, 4), (5, 5), (1, 1)] {
            let runs: Vec<Range<usize>> = (0..ranks)
                .map(|r| pieces_for_rank(pieces, r, ranks))
                .collect();
            let all: Vec<usize> = runs.iter().flat_map(|r| r.clone()).collect();
            assert_eq!(all, (0..pieces).collect::<Vec<_>>());
            let lens: Vec<usize> = runs.iter().map(|r| r.len()).collect();
            assert!(lens.iter().max().unwrap() - lens.iter().min().unwrap() <= 1);
        }
    }

    #[test]
    fn a_spatial_split_keeps_every_tetrahedron_once_with_its_points() {
        // A row of 10 tetrahedra along x (sharing no points): 3 ranks get
        // 3, 3 and 4 of them, in x order, each with its own four points
        // and their field values.
        let mut mesh = TetMesh::default();
        let mut values = Vec::new();
        for i in (0..10).rev() {
            let x = i as f32 * 2.0;
            let base = mesh.points.len() as u32;
            mesh.points.extend([
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x + 1.0, 0.0, 0.0),
                Vec3::new(x, 1.0, 0.0),
                Vec3::new(x, 0.0, 1.0),
            ]);
            values.extend([x; 4]);
            mesh.tets.push([base, base + 1, base + 2, base + 3]);
        }
        mesh.fields.push(ScalarField {
            name: "x".into(),
            values,
        });
        let parts: Vec<TetMesh> = (0..3).map(|r| spatial_split(&mesh, r, 3)).collect();
        assert_eq!(
            parts.iter().map(|p| p.tets.len()).collect::<Vec<_>>(),
            vec![3, 3, 4]
        );
        for (r, part) in parts.iter().enumerate() {
            assert_eq!(part.points.len(), 4 * part.tets.len());
            for t in &part.tets {
                let x = part.points[t[0] as usize].x;
                assert_eq!(part.fields[0].values[t[0] as usize], x);
                // Rank r holds the slab of x it should.
                let slot = (x / 2.0) as usize;
                let expected = [0, 0, 0, 1, 1, 1, 2, 2, 2, 2][slot];
                assert_eq!(r, expected);
            }
        }
    }
}
