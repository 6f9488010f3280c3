//! Splitting a structured (i, j, k) grid of hexahedra into tetrahedra.
//!
//! Each hexahedron becomes 5 tetrahedra: a central one on four corners that
//! are pairwise diagonal, and four corner ones cutting off the other four
//! corners. Which set of four corners forms the central tetrahedron
//! alternates with the parity of `i + j + k`, so every face diagonal joins
//! two grid points with even `i + j + k`: two hexahedra sharing a face cut
//! it along the same diagonal, and the tetrahedra meet face to face.

use rayon::prelude::*;

/// Local corner offsets `(di, dj, dk)` of a hexahedron's tetrahedra:
/// `[parity][tet][corner]`.
pub type Templates = [[[[u32; 3]; 4]; 5]; 2];

/// Local corner offsets `(di, dj, dk)` of a hexahedron's tetrahedra, one set
/// per parity of `i + j + k`, each tetrahedron positively oriented when the
/// grid axes i, j, k are right-handed.
pub fn templates() -> Templates {
    let even = [
        [[0, 0, 0], [1, 1, 0], [1, 0, 1], [0, 1, 1]],
        [[1, 0, 0], [0, 0, 0], [1, 1, 0], [1, 0, 1]],
        [[0, 1, 0], [0, 0, 0], [1, 1, 0], [0, 1, 1]],
        [[0, 0, 1], [0, 0, 0], [1, 0, 1], [0, 1, 1]],
        [[1, 1, 1], [1, 1, 0], [1, 0, 1], [0, 1, 1]],
    ];
    let odd = [
        [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]],
        [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
        [[1, 1, 0], [1, 0, 0], [0, 1, 0], [1, 1, 1]],
        [[1, 0, 1], [1, 0, 0], [0, 0, 1], [1, 1, 1]],
        [[0, 1, 1], [0, 1, 0], [0, 0, 1], [1, 1, 1]],
    ];
    [even, odd].map(|set| set.map(orient_local))
}

/// Swaps two corners of a local tetrahedron whose integer volume (on the
/// unit cube) is negative.
fn orient_local(mut t: [[u32; 3]; 4]) -> [[u32; 3]; 4] {
    let d = |a: [u32; 3], b: [u32; 3]| [0, 1, 2].map(|c| a[c] as i32 - b[c] as i32);
    let (e1, e2, e3) = (d(t[1], t[0]), d(t[2], t[0]), d(t[3], t[0]));
    let det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0])
        + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
    if det < 0 {
        t.swap(2, 3);
    }
    t
}

/// Number of hexahedra of an `ni x nj x nk` point grid.
pub fn hex_count(dims: [usize; 3]) -> usize {
    dims.iter().map(|&n| n.saturating_sub(1)).product()
}

/// Number of boundary quadrilaterals of an `ni x nj x nk` point grid (its
/// six sides); each is cut into two boundary triangles.
pub fn boundary_quad_count(dims: [usize; 3]) -> usize {
    let [a, b, c] = dims.map(|n| n.saturating_sub(1));
    2 * (a * b + b * c + c * a)
}

/// The 5 tetrahedra of every hexahedron of an `ni x nj x nk` point grid
/// whose point `(i, j, k)` has index `i + ni (j + nj k)` (PLOT3D order),
/// hexahedron by hexahedron in the same order. Every face diagonal joins
/// two points with `(i + j + k) % 2 == diagonal_parity` (0 or 1: the two
/// conforming splits). The caller guarantees the point count fits in `u32`.
pub fn structured_tets(dims: [usize; 3], diagonal_parity: usize) -> Vec<[u32; 4]> {
    let templates = templates();
    (0..hex_count(dims))
        .into_par_iter()
        .flat_map_iter(|h| hex_tets(&templates, dims, h, diagonal_parity))
        .collect()
}

/// The 5 tetrahedra of hexahedron `h` (numbered like the points, i
/// fastest) of an `ni x nj x nk` point grid, as in [`structured_tets`].
pub fn hex_tets(
    templates: &Templates,
    dims: [usize; 3],
    h: usize,
    diagonal_parity: usize,
) -> [[u32; 4]; 5] {
    let [ni, nj, _] = dims;
    let [hi, hj, _] = dims.map(|n| n.saturating_sub(1));
    let (i, j, k) = (h % hi, (h / hi) % hj, h / (hi * hj));
    let set = &templates[(i + j + k + diagonal_parity) % 2];
    set.map(|tet| {
        tet.map(|[di, dj, dk]| {
            let (pi, pj, pk) = (i + di as usize, j + dj as usize, k + dk as usize);
            (pi + ni * (pj + nj * pk)) as u32
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn templates_fill_the_cube_positively() {
        for (parity, set) in templates().iter().enumerate() {
            let mut total = 0;
            for t in set {
                let d = |a: [u32; 3]| [0, 1, 2].map(|c| a[c] as i32 - t[0][c] as i32);
                let (e1, e2, e3) = (d(t[1]), d(t[2]), d(t[3]));
                let det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1])
                    - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0])
                    + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
                assert!(det > 0, "parity {parity}: {t:?}");
                total += det;
            }
            // Four corner tets of volume 1/6 and a central one of 1/3: 6 V
            // sums to 6, the unit cube.
            assert_eq!(total, 6, "parity {parity}");
        }
    }

    #[test]
    fn counts() {
        assert_eq!(hex_count([40, 32, 32]), 37_479);
        assert_eq!(structured_tets([3, 3, 3], 1).len(), 40);
        assert_eq!(boundary_quad_count([3, 3, 3]), 24);
    }
}
