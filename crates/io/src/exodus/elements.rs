//! Exodus II element types and their VTK equivalents, with one node
//! reordering table per cell type.
//!
//! Exodus node order: the SEACAS "Exodus Element Types" page
//! (exodus-element-types.md, "Exodus Node Ordering Convention", which
//! follows the PATRAN element library); the IOSS topologies spell out the
//! edge and face nodes (`Ioss_Hex27.C`: edges `{0,1,8} .. {3,0,11}`, top
//! `{4,5,16} .. {7,4,19}`, vertical `{0,4,12} .. {3,7,15}`; face centres
//! 21..26 and the centroid 20). VTK node order: the class documentation of
//! vtkTetra, vtkHexahedron, vtkWedge, vtkPyramid and their quadratic
//! versions (vtkCellType.h for the ids).

/// What a block's `elem_type` says, by the prefixes SEACAS matches
/// (case-insensitive, `TETRA`/`TET4`/`tetra10` alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Family {
    Tetra,
    Hexahedron,
    Wedge,
    Pyramid,
    /// Circles, spheres, bars, trusses, beams, triangles, quads, shells:
    /// skipped with a warning.
    LowerDim,
    /// Polyhedra (NFACED): volume cells this reader cannot split.
    Polyhedron,
    Unknown,
}

pub(super) fn family(elem_type: &str) -> Family {
    let t = elem_type.trim().to_ascii_uppercase();
    let starts = |p: &str| t.starts_with(p);
    if starts("TET") {
        Family::Tetra
    } else if starts("HEX") {
        Family::Hexahedron
    } else if starts("WEDGE") || starts("PRISM") {
        Family::Wedge
    } else if starts("PYR") {
        Family::Pyramid
    } else if starts("NFACED") {
        Family::Polyhedron
    } else if [
        "CIRCLE", "SPHERE", "BAR", "TRUSS", "BEAM", "TRI", "QUAD", "SHELL", "NSIDED", "EDGE",
        "POINT", "SUPER",
    ]
    .iter()
    .any(|p| starts(p))
        || t == "NULL"
        || t.is_empty()
    {
        Family::LowerDim
    } else {
        Family::Unknown
    }
}

/// A volume cell as VTK knows it: the type id, and for each VTK node the
/// index of the Exodus node that goes there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct VtkCell {
    pub type_id: i64,
    pub name: &'static str,
    pub exodus_node_of_vtk: &'static [usize],
}

/// Linear tetra: same order in both (corners 1-2-3 seen counter-clockwise
/// from corner 4 in Exodus; (0,1,2) normal towards 3 in VTK).
const TETRA4: [usize; 4] = [0, 1, 2, 3];
/// TETRA10: Exodus mid-edge nodes 5..10 lie on edges 1-2, 2-3, 3-1, 1-4,
/// 2-4, 3-4, as VTK's 4..9 on 0-1, 1-2, 2-0, 0-3, 1-3, 2-3: no change.
const TETRA10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9];
/// HEX8: bottom 1-2-3-4 then top 5-6-7-8 in both.
const HEX8: [usize; 8] = [0, 1, 2, 3, 4, 5, 6, 7];
/// HEX20: Exodus puts the vertical edges (1-5 .. 4-8) at 13..16 and the top
/// edges (5-6 .. 8-5) at 17..20; VTK puts the top edges at 12..15 and the
/// vertical ones at 16..19.
const HEX20: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15,
];
/// HEX27: edges as HEX20; Exodus node 21 is the centroid and 22..27 the
/// centres of faces -z, +z, -x, +x, -y, +y; VTK's 20..25 are the centres of
/// faces -x (0,4,7,3), +x (1,2,6,5), -y (0,1,5,4), +y (3,2,6,7), -z, +z and
/// 26 the centroid.
const HEX27: [usize; 27] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15, 23, 24, 25, 26, 21, 22,
    20,
];
/// WEDGE6: Exodus orders the bottom triangle 1-2-3 counter-clockwise seen
/// from the top (its side 4 is 1-3-2, outward), VTK's (0,1,2) has its
/// normal pointing away from (3,4,5): swap the second and third corner of
/// both triangles.
const WEDGE6: [usize; 6] = [0, 2, 1, 3, 5, 4];
/// WEDGE15: corners as WEDGE6; Exodus mid-edge nodes 7-9 on 1-2, 2-3, 3-1,
/// 10-12 on 1-4, 2-5, 3-6, 13-15 on 4-5, 5-6, 6-4. VTK's 6-8 lie on 0-1,
/// 1-2, 2-0, 9-11 on 3-4, 4-5, 5-3, 12-14 on 0-3, 1-4, 2-5, whose corners
/// are the swapped Exodus ones (VTK 0-1 is Exodus 1-3, ...).
const WEDGE15: [usize; 15] = [0, 2, 1, 3, 5, 4, 8, 7, 6, 14, 13, 12, 9, 11, 10];
/// PYRAMID5: base 1-2-3-4, apex 5, in both.
const PYRAMID5: [usize; 5] = [0, 1, 2, 3, 4];
/// PYRAMID13: mid-edge nodes 6-9 on the base edges, 10-13 on the edges to
/// the apex, as VTK's 5-8 and 9-12: no change.
const PYRAMID13: [usize; 13] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12];

/// The VTK cell of an Exodus volume family with `nodes` nodes per element,
/// or why there is none.
pub(super) fn vtk_cell(family: Family, nodes: usize) -> Result<VtkCell, &'static str> {
    let cell = |type_id, name, map: &'static [usize]| {
        Ok(VtkCell {
            type_id,
            name,
            exodus_node_of_vtk: map,
        })
    };
    match (family, nodes) {
        (Family::Tetra, 4) => cell(10, "tetra", &TETRA4),
        (Family::Tetra, 10) => cell(24, "quadratic tetra", &TETRA10),
        (Family::Hexahedron, 8) => cell(12, "hexahedron", &HEX8),
        (Family::Hexahedron, 20) => cell(25, "quadratic hexahedron", &HEX20),
        (Family::Hexahedron, 27) => cell(29, "triquadratic hexahedron", &HEX27),
        (Family::Wedge, 6) => cell(13, "wedge", &WEDGE6),
        (Family::Wedge, 15) => cell(26, "quadratic wedge", &WEDGE15),
        (Family::Pyramid, 5) => cell(14, "pyramid", &PYRAMID5),
        (Family::Pyramid, 13) => cell(27, "quadratic pyramid", &PYRAMID13),
        (Family::Tetra, _) => Err("tetrahedra are read with 4 or 10 nodes"),
        (Family::Hexahedron, _) => Err("hexahedra are read with 8, 20 or 27 nodes"),
        (Family::Wedge, _) => Err("wedges are read with 6 or 15 nodes"),
        (Family::Pyramid, _) => Err("pyramids are read with 5 or 13 nodes"),
        (Family::Polyhedron, _) => Err("polyhedra cannot be split into tetrahedra"),
        (Family::Unknown, _) => Err("not an Exodus element type this reader knows"),
        (Family::LowerDim, _) => Err("not a volume element"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn families_by_prefix_any_case() {
        for (name, f) in [
            ("TETRA", Family::Tetra),
            ("tet4", Family::Tetra),
            ("TETRA10", Family::Tetra),
            ("Hex8", Family::Hexahedron),
            ("HEX27", Family::Hexahedron),
            ("wedge15", Family::Wedge),
            ("PYRAMID13", Family::Pyramid),
            ("SHELL4", Family::LowerDim),
            ("beam2", Family::LowerDim),
            ("BAR", Family::LowerDim),
            ("SPHERE", Family::LowerDim),
            ("TRISHELL3", Family::LowerDim),
            ("quad4", Family::LowerDim),
            ("nfaced", Family::Polyhedron),
            ("blob", Family::Unknown),
        ] {
            assert_eq!(family(name), f, "{name}");
        }
    }

    #[test]
    fn every_table_is_a_permutation_of_its_size() {
        for (f, n) in [
            (Family::Tetra, 4),
            (Family::Tetra, 10),
            (Family::Hexahedron, 8),
            (Family::Hexahedron, 20),
            (Family::Hexahedron, 27),
            (Family::Wedge, 6),
            (Family::Wedge, 15),
            (Family::Pyramid, 5),
            (Family::Pyramid, 13),
        ] {
            let map = vtk_cell(f, n).unwrap().exodus_node_of_vtk;
            let mut sorted = map.to_vec();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..n).collect::<Vec<_>>(), "{f:?} {n}");
        }
        assert!(vtk_cell(Family::Hexahedron, 9).is_err());
        assert!(vtk_cell(Family::Polyhedron, 8).is_err());
    }

    /// Exodus reference nodes: the corners, then each higher-order node
    /// at the centre of the corners the Exodus/PATRAN numbering puts it on.
    fn exodus_nodes(corners: &[[f64; 3]], centres: &[&[usize]]) -> Vec<[f64; 3]> {
        let mut nodes = corners.to_vec();
        nodes.extend(
            centres
                .iter()
                .map(|on| centre(on.iter().map(|&c| corners[c]))),
        );
        nodes
    }

    fn centre(points: impl Iterator<Item = [f64; 3]>) -> [f64; 3] {
        let (mut sum, mut n) = ([0.0; 3], 0.0);
        for p in points {
            (0..3).for_each(|a| sum[a] += p[a]);
            n += 1.0;
        }
        sum.map(|s| s / n)
    }

    /// The nodes in VTK order, as the reader orders a block's connectivity.
    fn in_vtk_order(f: Family, nodes: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let cell = vtk_cell(f, nodes.len()).unwrap();
        let ids: Vec<i64> = (0..nodes.len() as i64).collect();
        crate::exodus::read::vtk_order(&ids, cell)
            .map(|i| nodes[i as usize])
            .collect()
    }

    /// Checks VTK's higher-order nodes against the centres of the VTK
    /// corners they belong on (vtkQuadraticTetra, vtkQuadraticHexahedron,
    /// vtkTriQuadraticHexahedron, vtkQuadraticWedge, vtkQuadraticPyramid).
    fn check_vtk_centres(vtk: &[[f64; 3]], first: usize, on: &[&[usize]], what: &str) {
        for (k, corners) in on.iter().enumerate() {
            let expected = centre(corners.iter().map(|&c| vtk[c]));
            assert_eq!(vtk[first + k], expected, "{what}: VTK node {}", first + k);
        }
    }

    /// (b - a) x (c - a) . (d - a): positive when d lies on the side the
    /// right-hand normal of a-b-c points to.
    fn side(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
        let (u, v, w) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            [d[0] - a[0], d[1] - a[1], d[2] - a[2]],
        );
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        n[0] * w[0] + n[1] * w[1] + n[2] * w[2]
    }

    const TET_EDGES: [&[usize]; 6] = [&[0, 1], &[1, 2], &[2, 0], &[0, 3], &[1, 3], &[2, 3]];
    const CUBE: [[f64; 3]; 8] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    /// Exodus HEX20 edges: bottom, vertical, top (nodes 9-20).
    const EXODUS_HEX_EDGES: [&[usize]; 12] = [
        &[0, 1],
        &[1, 2],
        &[2, 3],
        &[3, 0],
        &[0, 4],
        &[1, 5],
        &[2, 6],
        &[3, 7],
        &[4, 5],
        &[5, 6],
        &[6, 7],
        &[7, 4],
    ];
    /// VTK quadratic hexahedron edges: bottom, top, vertical (8-19).
    const VTK_HEX_EDGES: [&[usize]; 12] = [
        &[0, 1],
        &[1, 2],
        &[2, 3],
        &[3, 0],
        &[4, 5],
        &[5, 6],
        &[6, 7],
        &[7, 4],
        &[0, 4],
        &[1, 5],
        &[2, 6],
        &[3, 7],
    ];

    #[test]
    fn quadratic_tetra_mid_edge_nodes_land_on_vtk_edges() {
        let corners = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let vtk = in_vtk_order(Family::Tetra, &exodus_nodes(&corners, &TET_EDGES));
        check_vtk_centres(&vtk, 4, &TET_EDGES, "TETRA10");
        assert!(
            side(vtk[0], vtk[1], vtk[2], vtk[3]) > 0.0,
            "VTK: 0-1-2 faces 3"
        );
    }

    #[test]
    fn quadratic_hexahedra_mid_edge_and_face_nodes_land_on_vtk_places() {
        let vtk = in_vtk_order(Family::Hexahedron, &exodus_nodes(&CUBE, &EXODUS_HEX_EDGES));
        check_vtk_centres(&vtk, 8, &VTK_HEX_EDGES, "HEX20");
        assert!(
            side(vtk[0], vtk[1], vtk[2], vtk[4]) > 0.0,
            "VTK: 0-1-2-3 faces 4-5-6-7"
        );

        // HEX27: Exodus node 21 the centroid, 22-27 the centres of faces
        // 5, 6, 4, 2, 1, 3 of the Exodus side numbering.
        let mut exodus: Vec<&[usize]> = EXODUS_HEX_EDGES.to_vec();
        exodus.extend([
            &[0, 1, 2, 3, 4, 5, 6, 7][..],
            &[0, 3, 2, 1],
            &[4, 5, 6, 7],
            &[0, 4, 7, 3],
            &[1, 2, 6, 5],
            &[0, 1, 5, 4],
            &[2, 3, 7, 6],
        ]);
        let vtk = in_vtk_order(Family::Hexahedron, &exodus_nodes(&CUBE, &exodus));
        check_vtk_centres(&vtk, 8, &VTK_HEX_EDGES, "HEX27 edges");
        let vtk_faces: [&[usize]; 7] = [
            &[0, 4, 7, 3],
            &[1, 2, 6, 5],
            &[0, 1, 5, 4],
            &[3, 2, 6, 7],
            &[0, 1, 2, 3],
            &[4, 5, 6, 7],
            &[0, 1, 2, 3, 4, 5, 6, 7],
        ];
        check_vtk_centres(&vtk, 20, &vtk_faces, "HEX27 faces and centre");
    }

    #[test]
    fn wedges_turn_to_vtk_orientation_and_edges() {
        // Exodus: 1-2-3 counter-clockwise seen from the top triangle 4-5-6.
        let corners = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
        ];
        assert!(side(corners[0], corners[1], corners[2], corners[3]) > 0.0);
        let vtk = in_vtk_order(Family::Wedge, &corners);
        assert!(
            side(vtk[0], vtk[1], vtk[2], vtk[3]) < 0.0,
            "VTK: 0-1-2 faces away from 3-4-5"
        );
        for k in 0..3 {
            // Each VTK top corner still sits above its bottom corner.
            assert_eq!([vtk[k][0], vtk[k][1]], [vtk[k + 3][0], vtk[k + 3][1]]);
        }
        let exodus: [&[usize]; 9] = [
            &[0, 1],
            &[1, 2],
            &[2, 0],
            &[0, 3],
            &[1, 4],
            &[2, 5],
            &[3, 4],
            &[4, 5],
            &[5, 3],
        ];
        let vtk = in_vtk_order(Family::Wedge, &exodus_nodes(&corners, &exodus));
        let vtk_edges: [&[usize]; 9] = [
            &[0, 1],
            &[1, 2],
            &[2, 0],
            &[3, 4],
            &[4, 5],
            &[5, 3],
            &[0, 3],
            &[1, 4],
            &[2, 5],
        ];
        check_vtk_centres(&vtk, 6, &vtk_edges, "WEDGE15");
    }

    #[test]
    fn quadratic_pyramid_mid_edge_nodes_land_on_vtk_edges() {
        let corners = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, 1.0],
        ];
        let edges: [&[usize]; 8] = [
            &[0, 1],
            &[1, 2],
            &[2, 3],
            &[3, 0],
            &[0, 4],
            &[1, 4],
            &[2, 4],
            &[3, 4],
        ];
        let vtk = in_vtk_order(Family::Pyramid, &exodus_nodes(&corners, &edges));
        check_vtk_centres(&vtk, 5, &edges, "PYRAMID13");
        assert!(
            side(vtk[0], vtk[1], vtk[2], vtk[4]) > 0.0,
            "VTK: the base faces the apex"
        );
    }
}
