//! Splitting linear VTK volume cells into tetrahedra, conforming across
//! cells.
//!
//! Rule (Dompierre, Labbé, Vallet, Camarero 1999, "How to subdivide
//! pyramids, prisms and hexahedra into tetrahedra"): every quadrilateral face
//! is cut by its diagonal through the face vertex with the smallest global
//! point index. Both cells sharing a face see the same global indices, so
//! they cut it the same way and the tetrahedra conform.
//!
//! Realisation (equivalent to the paper's case tables, written as cones):
//! - pyramid: cone from the apex over the two base triangles (2 tets);
//! - wedge: cone from the cell's smallest-index vertex `m` over the faces not
//!   containing `m` (the far triangle and the far quad, 3 tets). The two quad
//!   faces through `m` are then cut through `m`, which is their own smallest
//!   vertex, as the rule requires;
//! - hexahedron and voxel: when none of the three faces opposite `m` has its
//!   diagonal through `o`, the vertex opposite `m`, every face diagonal joins
//!   two vertices of `m`'s parity class and the cell splits into 5 tets (the
//!   4 corners of the other class plus the central tet). Otherwise a cone
//!   from `m` over the three far faces gives 6 tets. With the rule applied
//!   this way no configuration ever needs a Steiner point: the cases that do
//!   (no vertex touching three diagonals) cannot occur, because `m` touches
//!   the diagonals of its three faces.
//!
//! Output tets are oriented like the parent cell: each template tet is made
//! positive on the VTK reference cell, so a well-shaped cell in VTK order
//! gives positive tets and an inverted one gives negative tets (the mesh
//! loader fixes orientation afterwards). Tets of collapsed cells (repeated
//! point indices) that repeat a point have no volume and are dropped.

use super::cell_types::CellKind;

type Point = [f64; 3];

/// VTK hexahedron corners (points 0-3 the bottom quad, 4-7 above them).
pub(super) const HEX_REF: [Point; 8] = [
    [0., 0., 0.],
    [1., 0., 0.],
    [1., 1., 0.],
    [0., 1., 0.],
    [0., 0., 1.],
    [1., 0., 1.],
    [1., 1., 1.],
    [0., 1., 1.],
];
pub(super) const HEX_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [3, 0, 4, 7],
];
/// The three edge neighbours of each hexahedron vertex.
const HEX_NEIGHBOURS: [[usize; 3]; 8] = [
    [1, 3, 4],
    [0, 2, 5],
    [1, 3, 6],
    [0, 2, 7],
    [0, 5, 7],
    [1, 4, 6],
    [2, 5, 7],
    [3, 4, 6],
];
/// The three vertices across a face diagonal from each hexahedron vertex.
const HEX_DIAGONAL_PARTNERS: [[usize; 3]; 8] = [
    [2, 5, 7],
    [3, 4, 6],
    [0, 5, 7],
    [1, 4, 6],
    [1, 3, 6],
    [0, 2, 7],
    [1, 3, 4],
    [0, 2, 5],
];
/// The vertex sharing no face with each hexahedron vertex.
const HEX_OPPOSITE: [usize; 8] = [6, 7, 4, 5, 2, 3, 0, 1];
/// Voxel point order (x fastest, then y, then z) to hexahedron order.
const VOXEL_TO_HEX: [usize; 8] = [0, 1, 3, 2, 4, 5, 7, 6];

/// VTK wedge corners: triangle 0-1-2, triangle 3-4-5 above it. These are
/// vtkWedge's parametric coordinates; the (0,1,2) normal points towards
/// (3,4,5), whatever vtkWedge's header comment says.
const WEDGE_REF: [Point; 6] = [
    [0., 0., 0.],
    [1., 0., 0.],
    [0., 1., 0.],
    [0., 0., 1.],
    [1., 0., 1.],
    [0., 1., 1.],
];
const WEDGE_TRIANGLES: [[usize; 3]; 2] = [[0, 1, 2], [3, 5, 4]];
const WEDGE_QUADS: [[usize; 4]; 3] = [[0, 1, 4, 3], [1, 2, 5, 4], [2, 0, 3, 5]];

/// VTK pyramid corners: base quad 0-3, apex 4.
const PYRAMID_REF: [Point; 5] = [
    [0., 0., 0.],
    [1., 0., 0.],
    [1., 1., 0.],
    [0., 1., 0.],
    [0.5, 0.5, 1.],
];

/// Appends the tetrahedra of one cell (global point ids `ids`, VTK order) to
/// `out`; returns how many zero-volume tets of a collapsed cell were
/// dropped. `kind` must be one of the five linear volume kinds and `ids` of
/// its length (checked by the caller).
pub fn split_cell(kind: CellKind, ids: &[u32], out: &mut Vec<[u32; 4]>) -> usize {
    let mut emit = Emitter {
        ids,
        reference: &[],
        out,
        dropped: 0,
    };
    match kind {
        CellKind::Tetra => emit.out.push([ids[0], ids[1], ids[2], ids[3]]),
        CellKind::Pyramid => {
            emit.reference = &PYRAMID_REF;
            for tri in quad_triangles(ids, [0, 1, 2, 3]) {
                emit.tet(4, tri);
            }
        }
        CellKind::Wedge => {
            emit.reference = &WEDGE_REF;
            let m = argmin(ids);
            for tri in WEDGE_TRIANGLES.iter().filter(|t| !t.contains(&m)) {
                emit.tet(m, *tri);
            }
            for quad in WEDGE_QUADS.iter().filter(|q| !q.contains(&m)) {
                for tri in quad_triangles(ids, *quad) {
                    emit.tet(m, tri);
                }
            }
        }
        CellKind::Hexahedron => {
            emit.reference = &HEX_REF;
            hexahedron(&mut emit);
        }
        CellKind::Voxel => {
            let hex_ids: [u32; 8] = VOXEL_TO_HEX.map(|i| ids[i]);
            let mut hex = Emitter {
                ids: &hex_ids,
                reference: &HEX_REF,
                out: emit.out,
                dropped: 0,
            };
            hexahedron(&mut hex);
            return hex.dropped;
        }
        _ => {}
    }
    emit.dropped
}

/// Hexahedron split, 5 or 6 tets (see the module comment).
fn hexahedron(emit: &mut Emitter<'_, '_>) {
    let m = argmin(emit.ids);
    let o = HEX_OPPOSITE[m];
    let mut far = [[[0usize; 3]; 2]; 3];
    let far_faces = HEX_FACES.iter().filter(|q| !q.contains(&m));
    for (slot, quad) in far.iter_mut().zip(far_faces) {
        *slot = quad_triangles(emit.ids, *quad);
    }
    // The diagonal of a triangulated quad joins tri[0][0] and tri[0][2].
    let through_o = |t: &[[usize; 3]; 2]| t[0][0] == o || t[0][2] == o;
    if !far.iter().any(through_o) {
        // Corners of the class not containing m, then the central tet.
        let odd = HEX_NEIGHBOURS[m].into_iter().chain([o]);
        for u in odd {
            let [a, b, c] = HEX_NEIGHBOURS[u];
            emit.tet(u, [a, b, c]);
        }
        emit.tet(m, HEX_DIAGONAL_PARTNERS[m]);
    } else {
        for tri in far.iter().flatten() {
            emit.tet(m, *tri);
        }
    }
}

/// Other splits of a hexahedron (VTK order) with the same face diagonals as
/// [`split_cell`]'s, so still conforming: the cone from each vertex that the
/// diagonals of its three faces pass through (6 tets, oriented like the
/// parent cell; tets repeating a point dropped). A distorted cell whose
/// default split has tets of both orientations may have a cone without.
pub fn hexahedron_cones(ids: &[u32]) -> Vec<Vec<[u32; 4]>> {
    let faces = HEX_FACES.map(|q| (q, quad_triangles(ids, q)));
    (0..8)
        .filter(|&v| {
            faces
                .iter()
                .filter(|(q, _)| q.contains(&v))
                .all(|(_, t)| t[0][0] == v || t[0][2] == v)
        })
        .map(|v| {
            let mut out = Vec::with_capacity(6);
            let mut emit = Emitter {
                ids,
                reference: &HEX_REF,
                out: &mut out,
                dropped: 0,
            };
            for (_, t) in faces.iter().filter(|(q, _)| !q.contains(&v)) {
                for tri in t {
                    emit.tet(v, *tri);
                }
            }
            out
        })
        .collect()
}

/// The two triangles (local vertex indices) of quad `q`, cut by the
/// diagonal through its vertex with the smallest global index (the first
/// such vertex on ties, which only collapsed cells have).
pub(super) fn quad_triangles(ids: &[u32], q: [usize; 4]) -> [[usize; 3]; 2] {
    let mut k = 0;
    for i in 1..4 {
        if ids[q[i]] < ids[q[k]] {
            k = i;
        }
    }
    let at = |i: usize| q[(k + i) % 4];
    [[at(0), at(1), at(2)], [at(0), at(2), at(3)]]
}

/// Local index of the smallest global id (first on ties).
fn argmin(ids: &[u32]) -> usize {
    let mut k = 0;
    for (i, &id) in ids.iter().enumerate() {
        if id < ids[k] {
            k = i;
        }
    }
    k
}

struct Emitter<'a, 'o> {
    ids: &'a [u32],
    reference: &'static [Point],
    out: &'o mut Vec<[u32; 4]>,
    dropped: usize,
}

impl Emitter<'_, '_> {
    /// Emits the tet (apex, tri) oriented positively on the reference cell.
    fn tet(&mut self, apex: usize, tri: [usize; 3]) {
        let mut local = [apex, tri[0], tri[1], tri[2]];
        if signed_volume6(local.map(|i| self.reference[i])) < 0.0 {
            local.swap(2, 3);
        }
        let t = local.map(|i| self.ids[i]);
        let repeats = (0..4).any(|i| (i + 1..4).any(|j| t[i] == t[j]));
        if repeats {
            self.dropped += 1;
        } else {
            self.out.push(t);
        }
    }
}

/// Six times the signed volume of a tetrahedron.
pub fn signed_volume6(p: [Point; 4]) -> f64 {
    let d = |a: Point, b: Point| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (u, v, w) = (d(p[0], p[1]), d(p[0], p[2]), d(p[0], p[3]));
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Every permutation of 0..n, by Heap's algorithm.
    fn permutations(n: usize) -> Vec<Vec<u32>> {
        fn heap(k: usize, a: &mut Vec<u32>, out: &mut Vec<Vec<u32>>) {
            if k <= 1 {
                out.push(a.clone());
                return;
            }
            for i in 0..k {
                heap(k - 1, a, out);
                a.swap(if k & 1 == 0 { i } else { 0 }, k - 1);
            }
        }
        let mut out = Vec::new();
        heap(n, &mut (0..n as u32).collect(), &mut out);
        out
    }

    /// Splits the reference cell under every labelling of its vertices and
    /// checks: all tets positive, volumes summing to the cell's (exact in
    /// binary: the reference volumes are dyadic), and the tets' boundary is
    /// exactly the cell's faces with each quad cut through its smallest
    /// label. Returns how many labellings gave each tet count.
    fn check_all_labellings(
        kind: CellKind,
        reference: &[Point],
        triangles: &[[usize; 3]],
        quads: &[[usize; 4]],
        volume6: f64,
    ) -> HashMap<usize, usize> {
        let mut tally = HashMap::new();
        for ids in permutations(reference.len()) {
            let mut tets = Vec::new();
            assert_eq!(split_cell(kind, &ids, &mut tets), 0);
            *tally.entry(tets.len()).or_insert(0) += 1;
            // Labels are a permutation: label -> local vertex.
            let mut local = vec![0; ids.len()];
            for (i, &id) in ids.iter().enumerate() {
                local[id as usize] = i;
            }
            let mut total = 0.0;
            let mut faces: HashMap<[u32; 3], usize> = HashMap::new();
            for t in &tets {
                let v = signed_volume6(t.map(|g| reference[local[g as usize]]));
                assert!(v > 0.0, "{kind:?} {ids:?}: tet {t:?} has volume {v}");
                total += v;
                for skip in 0..4 {
                    let mut f = [0; 3];
                    let mut n = 0;
                    for (i, &g) in t.iter().enumerate() {
                        if i != skip {
                            f[n] = g;
                            n += 1;
                        }
                    }
                    f.sort_unstable();
                    *faces.entry(f).or_insert(0) += 1;
                }
            }
            assert_eq!(total, volume6, "{kind:?} {ids:?}");
            let boundary: Vec<[u32; 3]> = faces
                .into_iter()
                .filter(|&(_, c)| c == 1)
                .map(|(f, _)| f)
                .collect();
            let mut expected: Vec<[u32; 3]> = triangles.iter().map(|t| t.map(|i| ids[i])).collect();
            for q in quads {
                let k = (0..4).min_by_key(|&i| ids[q[i]]).unwrap_or(0);
                let at = |i: usize| ids[q[(k + i) % 4]];
                expected.push([at(0), at(1), at(2)]);
                expected.push([at(0), at(2), at(3)]);
            }
            for f in expected.iter_mut() {
                f.sort_unstable();
            }
            let mut boundary = boundary;
            boundary.sort_unstable();
            expected.sort_unstable();
            assert_eq!(boundary, expected, "{kind:?} {ids:?}");
        }
        tally
    }

    #[test]
    fn hexahedron_split_is_valid_for_every_labelling() {
        let tally = check_all_labellings(CellKind::Hexahedron, &HEX_REF, &[], &HEX_FACES, 6.0);
        // Both the 5-tet and the 6-tet cases occur, nothing else.
        assert!(
            tally[&5] > 0 && tally[&6] > 0 && tally.len() == 2,
            "{tally:?}"
        );
    }

    #[test]
    fn wedge_split_is_valid_for_every_labelling() {
        let tally = check_all_labellings(
            CellKind::Wedge,
            &WEDGE_REF,
            &WEDGE_TRIANGLES,
            &WEDGE_QUADS,
            3.0,
        );
        assert_eq!(tally.keys().copied().collect::<Vec<_>>(), vec![3]);
    }

    #[test]
    fn pyramid_split_is_valid_for_every_labelling() {
        let sides = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
        let tally = check_all_labellings(
            CellKind::Pyramid,
            &PYRAMID_REF,
            &sides,
            &[[0, 1, 2, 3]],
            2.0,
        );
        assert_eq!(tally.keys().copied().collect::<Vec<_>>(), vec![2]);
    }

    #[test]
    fn voxel_splits_like_the_reordered_hexahedron() {
        let ids = [7, 3, 9, 1, 4, 8, 2, 6];
        let (mut a, mut b) = (Vec::new(), Vec::new());
        split_cell(CellKind::Voxel, &ids, &mut a);
        split_cell(CellKind::Hexahedron, &VOXEL_TO_HEX.map(|i| ids[i]), &mut b);
        assert_eq!(a, b);
    }

    #[test]
    fn collapsed_hexahedron_drops_flat_tets() {
        // A hexahedron with its top face collapsed onto an edge is a wedge.
        let ids = [0, 1, 2, 3, 4, 4, 5, 5];
        let mut tets = Vec::new();
        let dropped = split_cell(CellKind::Hexahedron, &ids, &mut tets);
        assert!(dropped > 0);
        assert!(
            tets.iter()
                .all(|t| (0..4).all(|i| (i + 1..4).all(|j| t[i] != t[j])))
        );
    }
}
