//! Subdividing quadratic (and Lagrange order 2) volume cells into linear
//! cells through their mid-edge, face and body nodes, so the scalars at
//! those nodes shape the field; the linear cells are then split by
//! `split.rs`, whose global-index rule keeps every shared face conforming.
//!
//! - tetra (24, 71, 10 nodes): 4 corner tets and the inner octahedron cut
//!   along its shortest diagonal (8 tets);
//! - hexahedron (25, 29, 72): the 3x3x3 node lattice cut into 8 linear
//!   hexahedra; the 20-node hexahedron (25) lacks the face and body nodes,
//!   which are computed from its serendipity shape functions;
//! - wedge (26, 32, 73): the 6-node triangles x 3 layers cut into 8 linear
//!   wedges; the 15-node wedge (26) lacks the quad-face centres (computed);
//! - pyramid (27, 13 nodes): 6 linear pyramids and 4 tets through the base
//!   centre (computed).
//!
//! A computed face centre is keyed by the face's sorted corner ids, so the
//! two cells of a face share it. The 8-node serendipity quadrilateral gives
//! its centre weights -1/4 at the corners and 1/2 at the mid-edge nodes;
//! the 20-node hexahedron its body centre -1/4 at the corners and 1/4 at
//! the mid-edge nodes (its shape functions at the parametric centre).
//!
//! Node orders, one table per cell type (VTK's vtkCellType.h ids):
//! - 24 quadratic tetra, 71 Lagrange tetra order 2: corners 0-3, then the
//!   edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3) (vtkQuadraticTetra.h;
//!   vtkHigherOrderTetra uses the same edge order);
//! - 25 quadratic and 29 triquadratic hexahedron: corners 0-7, edges 8-19
//!   (0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7) (7,4) (0,4) (1,5) (2,6)
//!   (3,7); 29 adds the face centres 20-25 at x=0, x=1, y=0, y=1, z=0, z=1
//!   and the body centre 26 (vtkTriQuadraticHexahedron.cxx, `HexFaces`;
//!   its header's prose lists the faces in another order, its figure and
//!   code agree with this one);
//! - 72 Lagrange hexahedron order 2: as 29 except the vertical edges, which
//!   come as (0,4) (1,5) (3,7) (2,6): vtkHigherOrderHexahedron's
//!   `PointIndexFromIJK` numbers them by (i, j) = (0,0) (1,0) (0,1) (1,1);
//!   faces in the same order as 29 (i-normal, j-normal, k-normal);
//! - 26 quadratic wedge: corners 0-5, edges (0,1) (1,2) (2,0) (3,4) (4,5)
//!   (5,3) (0,3) (1,4) (2,5); 32 biquadratic wedge and 73 Lagrange wedge
//!   order 2 add the quad-face centres of (0,1,4,3) (1,2,5,4) (2,0,3,5)
//!   (vtkBiQuadraticQuadraticWedge.h; vtkHigherOrderWedge's
//!   `PointIndexFromIJK`: j = 0, then i + j = order, then i = 0 faces);
//! - 27 quadratic pyramid: corners 0-4 (apex 4), edges (0,1) (1,2) (2,3)
//!   (3,0) (0,4) (1,4) (2,4) (3,4) (vtkQuadraticPyramid.h).

use super::Linearize;
use super::added_points::{AddedPoints, PointKey};
use super::cell_types::CellKind;
use super::split::{signed_volume6, split_cell};

type Point = [f64; 3];

/// Lattice position (i, j, k), each in 0..=2, of the nodes of the 27-node
/// hexahedron (29); the first 20 are the quadratic hexahedron's (25).
const HEX29_NODES: [[u8; 3]; 27] = [
    [0, 0, 0],
    [2, 0, 0],
    [2, 2, 0],
    [0, 2, 0],
    [0, 0, 2],
    [2, 0, 2],
    [2, 2, 2],
    [0, 2, 2],
    [1, 0, 0],
    [2, 1, 0],
    [1, 2, 0],
    [0, 1, 0],
    [1, 0, 2],
    [2, 1, 2],
    [1, 2, 2],
    [0, 1, 2],
    [0, 0, 1],
    [2, 0, 1],
    [2, 2, 1],
    [0, 2, 1],
    [0, 1, 1],
    [2, 1, 1],
    [1, 0, 1],
    [1, 2, 1],
    [1, 1, 0],
    [1, 1, 2],
    [1, 1, 1],
];

/// The Lagrange hexahedron of order 2 (72): nodes 18 and 19 swapped
/// against 29.
const HEX72_NODES: [[u8; 3]; 27] = {
    let mut nodes = HEX29_NODES;
    nodes[18] = [0, 2, 1];
    nodes[19] = [2, 2, 1];
    nodes
};

/// Lattice position (i, j, k) of the wedge nodes: (i, j) on the 6-node
/// triangle (i + j <= 2; node 1 at i = 2, node 2 at j = 2), k the layer.
/// The first 15 are the quadratic wedge's (26).
const WEDGE18_NODES: [[u8; 3]; 18] = [
    [0, 0, 0],
    [2, 0, 0],
    [0, 2, 0],
    [0, 0, 2],
    [2, 0, 2],
    [0, 2, 2],
    [1, 0, 0],
    [1, 1, 0],
    [0, 1, 0],
    [1, 0, 2],
    [1, 1, 2],
    [0, 1, 2],
    [0, 0, 1],
    [2, 0, 1],
    [0, 2, 1],
    [1, 0, 1],
    [1, 1, 1],
    [0, 1, 1],
];

/// A quad face of a lattice: corners in cyclic order, the mid-edge nodes
/// between them (`mids[c]` on edge c, c+1), the centre.
struct LatticeQuad {
    corners: [[u8; 3]; 4],
    mids: [[u8; 3]; 4],
    centre: [u8; 3],
}

/// The quad faces of the wedge lattice.
const WEDGE_QUADS: [LatticeQuad; 3] = [
    LatticeQuad {
        corners: [[0, 0, 0], [2, 0, 0], [2, 0, 2], [0, 0, 2]],
        mids: [[1, 0, 0], [2, 0, 1], [1, 0, 2], [0, 0, 1]],
        centre: [1, 0, 1],
    },
    LatticeQuad {
        corners: [[2, 0, 0], [0, 2, 0], [0, 2, 2], [2, 0, 2]],
        mids: [[1, 1, 0], [0, 2, 1], [1, 1, 2], [2, 0, 1]],
        centre: [1, 1, 1],
    },
    LatticeQuad {
        corners: [[0, 2, 0], [0, 0, 0], [0, 0, 2], [0, 2, 2]],
        mids: [[0, 1, 0], [0, 0, 1], [0, 1, 2], [0, 2, 1]],
        centre: [0, 1, 1],
    },
];

/// The 4 triangles of the refined 6-node triangle, as (i, j), all
/// counter-clockwise like the parent (0,0) (2,0) (0,2).
const WEDGE_SUB_TRIANGLES: [[[u8; 2]; 3]; 4] = [
    [[0, 0], [1, 0], [0, 1]],
    [[1, 0], [2, 0], [1, 1]],
    [[0, 1], [1, 1], [0, 2]],
    [[1, 1], [0, 1], [1, 0]],
];

/// Quadratic tetra: the edge of each mid-edge node 4-9.
const TET10_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
/// The 4 corner tets (each a half-size copy of the parent).
const TET10_CORNERS: [[usize; 4]; 4] = [[0, 4, 6, 7], [4, 1, 5, 8], [6, 5, 2, 9], [7, 8, 9, 3]];
/// The inner octahedron's three diagonals and the ring of 4 nodes around
/// each, in cyclic order.
const TET10_DIAGONALS: [([usize; 2], [usize; 4]); 3] = [
    ([4, 9], [5, 6, 7, 8]),
    ([5, 7], [4, 6, 9, 8]),
    ([6, 8], [4, 5, 9, 7]),
];

/// Quadratic pyramid: node `PYRAMID_BASE_MID[c]` is on base edge (c, c+1),
/// `PYRAMID_SIDE_MID[c]` on edge (c, apex 4).
const PYRAMID_BASE_MID: [usize; 4] = [5, 6, 7, 8];
const PYRAMID_SIDE_MID: [usize; 4] = [9, 10, 11, 12];

/// Where the subdivision writes: the tets, the added points, and the tets
/// of collapsed cells dropped for repeating a point.
pub struct Subdivision<'a> {
    /// x, y, z of the file's points (to pick the octahedron diagonal).
    pub points: &'a [f64],
    pub added: &'a mut AddedPoints,
    pub tets: &'a mut Vec<[u32; 4]>,
    pub dropped: usize,
}

/// Splits one quadratic or order-2 Lagrange cell (`ids` of the length its
/// kind requires, checked by the caller), or only its corner cell under
/// [`Linearize::Corners`].
pub fn subdivide(kind: CellKind, ids: &[u32], linearize: Linearize, s: &mut Subdivision) {
    if linearize == Linearize::Corners {
        let (linear, corners) = match kind {
            CellKind::QuadraticTetra => (CellKind::Tetra, 4),
            CellKind::QuadraticPyramid => (CellKind::Pyramid, 5),
            CellKind::QuadraticWedge | CellKind::BiquadraticWedge => (CellKind::Wedge, 6),
            _ => (CellKind::Hexahedron, 8),
        };
        s.dropped += split_cell(linear, &ids[..corners], s.tets);
        return;
    }
    match kind {
        CellKind::QuadraticTetra => tetra(ids, s),
        CellKind::QuadraticHexahedron => hexahedron(ids, &HEX29_NODES[..20], s),
        CellKind::TriquadraticHexahedron => hexahedron(ids, &HEX29_NODES, s),
        CellKind::LagrangeHexahedron => hexahedron(ids, &HEX72_NODES, s),
        CellKind::QuadraticWedge => wedge(ids, &WEDGE18_NODES[..15], s),
        CellKind::BiquadraticWedge => wedge(ids, &WEDGE18_NODES, s),
        CellKind::QuadraticPyramid => pyramid(ids, s),
        _ => {}
    }
}

fn tetra(ids: &[u32], s: &mut Subdivision) {
    let reference = |n: usize| -> Point {
        let corner = |c: usize| {
            let mut p = [0.0; 3];
            if c > 0 {
                p[c - 1] = 1.0;
            }
            p
        };
        if n < 4 {
            return corner(n);
        }
        let [a, b] = TET10_EDGES[n - 4].map(corner);
        [0, 1, 2].map(|i| 0.5 * (a[i] + b[i]))
    };
    for local in TET10_CORNERS {
        s.tet(ids, local, &reference);
    }
    let length2 = |[a, b]: [usize; 2]| -> f64 {
        let (p, q) = (ids[a] as usize * 3, ids[b] as usize * 3);
        (0..3)
            .map(|i| (s.points[p + i] - s.points[q + i]).powi(2))
            .sum()
    };
    // The shortest diagonal (the first on ties) gives the best-shaped tets.
    let shortest = TET10_DIAGONALS
        .iter()
        .min_by(|p, q| length2(p.0).total_cmp(&length2(q.0)));
    let Some(&([a, b], ring)) = shortest else {
        return;
    };
    for r in 0..4 {
        s.tet(ids, [a, b, ring[r], ring[(r + 1) % 4]], &reference);
    }
}

/// Lattice index of (i, j, k), each in 0..=2.
fn at([i, j, k]: [u8; 3]) -> usize {
    i as usize + 3 * j as usize + 9 * k as usize
}

/// Scatters the nodes of `ids` on the 3x3x3 lattice (`u32::MAX` where the
/// cell has no node).
fn lattice(ids: &[u32], nodes: &[[u8; 3]]) -> [u32; 27] {
    let mut l = [u32::MAX; 27];
    for (&id, &pos) in ids.iter().zip(nodes) {
        l[at(pos)] = id;
    }
    l
}

/// The centre of a quadratic quad face with the given corner and mid-edge
/// nodes, shared with the other cell of the face.
fn quad_centre(corners: [u32; 4], mids: [u32; 4], added: &mut AddedPoints) -> u32 {
    let mut key = corners;
    key.sort_unstable();
    added.shared(PointKey::QuadCentre(key), || {
        let corners = corners.iter().map(|&c| (c, -0.25));
        corners.chain(mids.iter().map(|&m| (m, 0.5))).collect()
    })
}

fn hexahedron(ids: &[u32], nodes: &[[u8; 3]], s: &mut Subdivision) {
    let mut l = lattice(ids, nodes);
    for axis in 0..3 {
        for side in [0u8, 2] {
            let mut centre = [1u8; 3];
            centre[axis] = side;
            if l[at(centre)] != u32::MAX {
                continue;
            }
            // Cyclic walk around the face: (u, v) in the other two axes.
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let cycle = [[0u8, 0], [2, 0], [2, 2], [0, 2]];
            let pos = |[a, b]: [u8; 2]| {
                let mut p = [side; 3];
                p[u] = a;
                p[v] = b;
                l[at(p)]
            };
            let corners = cycle.map(pos);
            let mids = [0, 1, 2, 3].map(|c| {
                let (p, q) = (cycle[c], cycle[(c + 1) % 4]);
                pos([(p[0] + q[0]) / 2, (p[1] + q[1]) / 2])
            });
            l[at(centre)] = quad_centre(corners, mids, s.added);
        }
    }
    if l[at([1, 1, 1])] == u32::MAX {
        // The serendipity body centre: corners -1/4, mid-edge nodes 1/4.
        let weights = HEX29_NODES[..20]
            .iter()
            .enumerate()
            .map(|(n, &p)| (l[at(p)], if n < 8 { -0.25 } else { 0.25 }))
            .collect();
        l[at([1, 1, 1])] = s.added.private(weights);
    }
    let corners: [[u8; 3]; 8] = std::array::from_fn(|n| HEX29_NODES[n]);
    for base in corners.map(|p| p.map(|c| c / 2)) {
        let sub = corners.map(|p| l[at([0, 1, 2].map(|i| base[i] + p[i] / 2))]);
        s.dropped += split_cell(CellKind::Hexahedron, &sub, s.tets);
    }
}

fn wedge(ids: &[u32], nodes: &[[u8; 3]], s: &mut Subdivision) {
    let mut l = lattice(ids, nodes);
    for q in &WEDGE_QUADS {
        if l[at(q.centre)] == u32::MAX {
            let (c, m) = (q.corners.map(|p| l[at(p)]), q.mids.map(|p| l[at(p)]));
            l[at(q.centre)] = quad_centre(c, m, s.added);
        }
    }
    for tri in WEDGE_SUB_TRIANGLES {
        for k in 0..2u8 {
            let node = |n: usize| {
                let [i, j] = tri[n % 3];
                l[at([i, j, k + (n / 3) as u8])]
            };
            let sub: [u32; 6] = std::array::from_fn(node);
            s.dropped += split_cell(CellKind::Wedge, &sub, s.tets);
        }
    }
}

fn pyramid(ids: &[u32], s: &mut Subdivision) {
    let base = [ids[0], ids[1], ids[2], ids[3]];
    let base_mids = PYRAMID_BASE_MID.map(|n| ids[n]);
    let centre = quad_centre(base, base_mids, s.added);
    let side = PYRAMID_SIDE_MID.map(|n| ids[n]);
    // Top half-size pyramid, and the inverted one below it (apex at the
    // base centre; its base reversed so the apex is on its positive side).
    s.dropped += split_cell(
        CellKind::Pyramid,
        &[side[0], side[1], side[2], side[3], ids[4]],
        s.tets,
    );
    s.dropped += split_cell(
        CellKind::Pyramid,
        &[side[0], side[3], side[2], side[1], centre],
        s.tets,
    );
    for c in 0..4 {
        let prev = (c + 3) % 4;
        // The corner pyramid, a half-size copy of the parent at corner c:
        // its base [corner, next mid, centre, previous mid] keeps the
        // parent's cyclic order.
        let sub = [base[c], base_mids[c], centre, base_mids[prev], side[c]];
        s.dropped += split_cell(CellKind::Pyramid, &sub, s.tets);
        // The tet under base edge (c, c+1): positive in this order on the
        // reference pyramid (checked in the tests).
        s.push_tet([base_mids[c], side[c], side[(c + 1) % 4], centre]);
    }
}

impl Subdivision<'_> {
    /// Emits the tet of local nodes `local`, oriented positively on the
    /// reference cell.
    fn tet(&mut self, ids: &[u32], local: [usize; 4], reference: &dyn Fn(usize) -> Point) {
        let mut local = local;
        if signed_volume6(local.map(reference)) < 0.0 {
            local.swap(2, 3);
        }
        self.push_tet(local.map(|n| ids[n]));
    }

    fn push_tet(&mut self, t: [u32; 4]) {
        if (0..4).any(|i| (i + 1..4).any(|j| t[i] == t[j])) {
            self.dropped += 1;
        } else {
            self.tets.push(t);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference coordinates of each node of `kind`.
    fn reference(kind: CellKind) -> Vec<Point> {
        let lattice = |nodes: &[[u8; 3]]| -> Vec<Point> {
            nodes
                .iter()
                .map(|p| p.map(|c| f64::from(c) / 2.0))
                .collect()
        };
        let with_mids = |corners: Vec<Point>, edges: &[[usize; 2]]| -> Vec<Point> {
            let mids: Vec<Point> = edges
                .iter()
                .map(|&[a, b]| [0, 1, 2].map(|i| 0.5 * (corners[a][i] + corners[b][i])))
                .collect();
            corners.into_iter().chain(mids).collect()
        };
        match kind {
            CellKind::QuadraticTetra => {
                let corners = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
                with_mids(corners, &TET10_EDGES)
            }
            CellKind::QuadraticHexahedron => lattice(&HEX29_NODES[..20]),
            CellKind::TriquadraticHexahedron => lattice(&HEX29_NODES),
            CellKind::LagrangeHexahedron => lattice(&HEX72_NODES),
            CellKind::QuadraticWedge => lattice(&WEDGE18_NODES[..15]),
            CellKind::BiquadraticWedge => lattice(&WEDGE18_NODES),
            _ => {
                let corners = vec![
                    [0., 0., 0.],
                    [1., 0., 0.],
                    [1., 1., 0.],
                    [0., 1., 0.],
                    [0.5, 0.5, 1.],
                ];
                let edges = [
                    [0, 1],
                    [1, 2],
                    [2, 3],
                    [3, 0],
                    [0, 4],
                    [1, 4],
                    [2, 4],
                    [3, 4],
                ];
                with_mids(corners, &edges)
            }
        }
    }

    /// Every type subdivides its reference cell (node ids in order) into
    /// positive tets whose volumes sum to the cell's (dyadic, so exact),
    /// each node and added point where the shape functions put it.
    #[test]
    fn reference_cells_give_positive_tets_filling_them() {
        let cases = [
            (CellKind::QuadraticTetra, 1.0, 8, 0),
            (CellKind::QuadraticHexahedron, 6.0, 0, 7),
            (CellKind::TriquadraticHexahedron, 6.0, 0, 0),
            (CellKind::LagrangeHexahedron, 6.0, 0, 0),
            (CellKind::QuadraticWedge, 3.0, 24, 3),
            (CellKind::BiquadraticWedge, 3.0, 24, 0),
            (CellKind::QuadraticPyramid, 2.0, 0, 1),
        ];
        for (kind, volume6, tets_expected, added_expected) in cases {
            let nodes = reference(kind);
            let ids: Vec<u32> = (0..nodes.len() as u32).collect();
            let mut xyz: Vec<f64> = nodes.iter().flatten().copied().collect();
            let mut added = AddedPoints::new(nodes.len());
            let mut tets = Vec::new();
            let mut s = Subdivision {
                points: &xyz,
                added: &mut added,
                tets: &mut tets,
                dropped: 0,
            };
            subdivide(kind, &ids, Linearize::Subdivide, &mut s);
            assert_eq!(s.dropped, 0, "{kind:?}");
            assert_eq!(added.len(), added_expected, "{kind:?}");
            if tets_expected > 0 {
                assert_eq!(tets.len(), tets_expected, "{kind:?}");
            }
            added.extend(&mut xyz, 3);
            let at = |p: u32| -> Point {
                let i = p as usize * 3;
                [xyz[i], xyz[i + 1], xyz[i + 2]]
            };
            let mut total = 0.0;
            for t in &tets {
                let v = signed_volume6(t.map(at));
                assert!(v > 0.0, "{kind:?}: tet {t:?} has volume {v}");
                total += v;
            }
            assert_eq!(total, volume6, "{kind:?}");
            // The 20-node hexahedron's added centres land on the lattice.
            if kind == CellKind::QuadraticHexahedron {
                let body = at(nodes.len() as u32 + 6);
                assert_eq!(body, [0.5, 0.5, 0.5]);
            }
        }
    }
}
