//! Quadratic and order-2 Lagrange cells: meshes of each type built here,
//! every cell given a random orientation-preserving relabelling of its
//! nodes and the points random global ids, so neighbours see each shared
//! face from different starting nodes. After splitting, the tetrahedra
//! must conform (every interior triangle in exactly two tets, the boundary
//! only the box's outer faces, validation passing), fill the box exactly,
//! and carry a linear field exactly at the added points.

mod vtk_common;

use std::collections::HashMap;
use std::fmt::Write;

use tetray_io::vtk::{Linearize, ReadOptions, read_legacy_bytes, read_legacy_bytes_with};
use vtk_common::{Lcg, face_counts, volume6};

/// A cell type as the test sees it: each node (VTK order) is the mean of
/// some corners; `rotations[r][c]` is the old corner that becomes corner c
/// under an orientation-preserving symmetry of the reference cell.
struct CellType {
    id: i64,
    nodes: Vec<Vec<usize>>,
    rotations: Vec<Vec<usize>>,
}

/// Node tables written from VTK's documentation (vtkQuadraticTetra.h,
/// vtkQuadraticHexahedron.h, vtkTriQuadraticHexahedron.cxx,
/// vtkHigherOrderHexahedron, vtkQuadraticWedge.h,
/// vtkBiQuadraticQuadraticWedge.h, vtkQuadraticPyramid.h).
fn nodes(corners: usize, edges: &[[usize; 2]], faces: &[&[usize]], body: bool) -> Vec<Vec<usize>> {
    let mut n: Vec<Vec<usize>> = (0..corners).map(|c| vec![c]).collect();
    n.extend(edges.iter().map(|e| e.to_vec()));
    n.extend(faces.iter().map(|f| f.to_vec()));
    if body {
        n.push((0..corners).collect());
    }
    n
}

const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
const HEX_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];
const HEX_FACES: [&[usize]; 6] = [
    &[0, 4, 7, 3],
    &[1, 2, 6, 5],
    &[0, 1, 5, 4],
    &[3, 2, 6, 7],
    &[0, 1, 2, 3],
    &[4, 5, 6, 7],
];
const WEDGE_EDGES: [[usize; 2]; 9] = [
    [0, 1],
    [1, 2],
    [2, 0],
    [3, 4],
    [4, 5],
    [5, 3],
    [0, 3],
    [1, 4],
    [2, 5],
];
const WEDGE_FACES: [&[usize]; 3] = [&[0, 1, 4, 3], &[1, 2, 5, 4], &[2, 0, 3, 5]];
const PYRAMID_EDGES: [[usize; 2]; 8] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [0, 4],
    [1, 4],
    [2, 4],
    [3, 4],
];

fn tet_rotations() -> Vec<Vec<usize>> {
    // The even permutations of the 4 corners.
    let mut out = Vec::new();
    for a in 0..4 {
        for b in 0..4 {
            for c in 0..4 {
                let Some(d) = 6usize.checked_sub(a + b + c) else {
                    continue;
                };
                let p = [a, b, c, d];
                let distinct = d < 4 && (0..4).all(|i| (i + 1..4).all(|j| p[i] != p[j]));
                let inversions = (0..4)
                    .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
                    .filter(|&(i, j)| p[i] > p[j])
                    .count();
                if distinct && inversions % 2 == 0 {
                    out.push(p.to_vec());
                }
            }
        }
    }
    out
}

fn hex_rotations() -> Vec<Vec<usize>> {
    // Signed permutation matrices of determinant +1 acting on the centred
    // corners (+-1, +-1, +-1).
    let corner = |c: usize| -> [i32; 3] {
        let p = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]][c % 4];
        [2 * p[0] - 1, 2 * p[1] - 1, if c < 4 { -1 } else { 1 }]
    };
    let perms = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [0, 2, 1],
        [2, 1, 0],
        [1, 0, 2],
    ];
    let mut out = Vec::new();
    for (k, perm) in perms.iter().enumerate() {
        for signs in 0..8 {
            let s = [0, 1, 2].map(|i| if signs >> i & 1 == 1 { -1 } else { 1 });
            let det = s[0] * s[1] * s[2] * if k < 3 { 1 } else { -1 };
            if det != 1 {
                continue;
            }
            let image = |c: usize| {
                let p = corner(c);
                let q = [0, 1, 2].map(|i| s[i] * p[perm[i]]);
                (0..8).find(|&d| corner(d) == q).unwrap()
            };
            out.push((0..8).map(image).collect());
        }
    }
    assert_eq!(out.len(), 24);
    out
}

fn wedge_rotations() -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    for shift in 0..3 {
        let cyc: Vec<usize> = (0..6).map(|c| 3 * (c / 3) + (c % 3 + shift) % 3).collect();
        // Upside down: the top triangle reversed becomes the base.
        let flip = [3, 5, 4, 0, 2, 1];
        out.push(flip.iter().map(|&f| cyc[f]).collect());
        out.push(cyc);
    }
    out
}

fn pyramid_rotations() -> Vec<Vec<usize>> {
    (0..4)
        .map(|r| (0..4).map(|c| (c + r) % 4).chain([4]).collect())
        .collect()
}

/// A mesh under construction: integer point positions (exact means).
#[derive(Default)]
struct Builder {
    ids: HashMap<[i64; 3], u32>,
    points: Vec<[i64; 3]>,
    cells: Vec<(i64, Vec<u32>)>,
}

impl Builder {
    fn point(&mut self, p: [i64; 3]) -> u32 {
        let next = self.points.len() as u32;
        *self.ids.entry(p).or_insert_with(|| {
            self.points.push(p);
            next
        })
    }

    /// Adds a cell of type `t` on `corners` (VTK order, positively
    /// oriented), relabelled by a random rotation, with `nodes` of its type.
    fn cell(&mut self, t: &CellType, nodes: &[Vec<usize>], corners: &[[i64; 3]], rng: &mut Lcg) {
        let r = &t.rotations[rng.below(t.rotations.len() as u32) as usize];
        let rotated: Vec<[i64; 3]> = r.iter().map(|&o| corners[o]).collect();
        let ids = nodes
            .iter()
            .map(|mean| {
                let n = mean.len() as i64;
                let sum = mean
                    .iter()
                    .fold([0i64; 3], |s, &c| [0, 1, 2].map(|i| s[i] + rotated[c][i]));
                assert!(
                    sum.iter().all(|v| v % n == 0),
                    "positions must stay integer"
                );
                self.point(sum.map(|v| v / n))
            })
            .collect();
        self.cells.push((t.id, ids));
    }

    /// Legacy ASCII text, the point ids shuffled, with the field
    /// f = x + 2y + 3z.
    fn legacy(&self, rng: &mut Lcg) -> String {
        let n = self.points.len();
        let mut order: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            order.swap(i, rng.below(i as u32 + 1) as usize);
        }
        // order[new] = old; new id of each old point:
        let mut new_id = vec![0u32; n];
        for (new, &old) in order.iter().enumerate() {
            new_id[old as usize] = new as u32;
        }
        let mut s = format!(
            "# vtk DataFile Version 3.0\ncells\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {n} double\n"
        );
        let xyz = |p: [i64; 3]| p.map(|v| v as f64 / SCALE as f64);
        for &old in &order {
            let [x, y, z] = xyz(self.points[old as usize]);
            writeln!(s, "{x} {y} {z}").unwrap();
        }
        let size: usize = self.cells.iter().map(|(_, ids)| ids.len() + 1).sum();
        writeln!(s, "CELLS {} {size}", self.cells.len()).unwrap();
        for (_, ids) in &self.cells {
            let ids: Vec<String> = ids
                .iter()
                .map(|&i| new_id[i as usize].to_string())
                .collect();
            writeln!(s, "{} {}", ids.len(), ids.join(" ")).unwrap();
        }
        writeln!(s, "CELL_TYPES {}", self.cells.len()).unwrap();
        for (t, _) in &self.cells {
            writeln!(s, "{t}").unwrap();
        }
        writeln!(s, "POINT_DATA {n}\nSCALARS f double\nLOOKUP_TABLE default").unwrap();
        for &old in &order {
            let [x, y, z] = xyz(self.points[old as usize]);
            writeln!(s, "{}", field(x, y, z)).unwrap();
        }
        s
    }
}

/// Integer units per unit length: means of up to 8 corners stay exact.
const SCALE: i64 = 8;
/// Cubes per side of the box.
const CUBES: i64 = 2;

fn field(x: f64, y: f64, z: f64) -> f64 {
    x + 2.0 * y + 3.0 * z
}

/// Unit cube `(i, j, k)`'s corners in VTK hexahedron order (scaled by 2 so
/// the cube centre is integer too).
fn cube(i: i64, j: i64, k: i64) -> [[i64; 3]; 8] {
    let u = 2 * SCALE;
    [
        [0, 0, 0],
        [1, 0, 0],
        [1, 1, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 0, 1],
        [1, 1, 1],
        [0, 1, 1],
    ]
    .map(|[a, b, c]| [(i + a) * u, (j + b) * u, (k + c) * u])
}

fn cubes() -> impl Iterator<Item = [[i64; 3]; 8]> {
    (0..CUBES).flat_map(|i| (0..CUBES).flat_map(move |j| (0..CUBES).map(move |k| cube(i, j, k))))
}

fn volume(p: [[i64; 3]; 4]) -> i64 {
    let d = |a: [i64; 3], b: [i64; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (u, v, w) = (d(p[0], p[1]), d(p[0], p[2]), d(p[0], p[3]));
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// Fills the box of `CUBES`^3 cubes of side 2 with cells of `t`.
fn build(t: &CellType, rng: &mut Lcg) -> Builder {
    let mut b = Builder::default();
    for c in cubes() {
        match t.nodes.len() {
            10 => {
                // Kuhn's 6 tets per cube, conforming across cubes.
                for perm in [
                    [0, 1, 2],
                    [0, 2, 1],
                    [1, 0, 2],
                    [1, 2, 0],
                    [2, 0, 1],
                    [2, 1, 0],
                ] {
                    let mut p = c[0];
                    let mut tet = vec![p];
                    for axis in perm {
                        p[axis] += 2 * SCALE;
                        tet.push(p);
                    }
                    if volume([tet[0], tet[1], tet[2], tet[3]]) < 0 {
                        tet.swap(2, 3);
                    }
                    b.cell(t, &t.nodes, &tet, rng);
                }
            }
            15 | 18 => {
                for tri in [[0, 1, 2], [0, 2, 3]] {
                    let w: Vec<[i64; 3]> = tri
                        .iter()
                        .chain(&tri)
                        .enumerate()
                        .map(|(n, &v)| c[v + if n < 3 { 0 } else { 4 }])
                        .collect();
                    b.cell(t, &t.nodes, &w, rng);
                }
            }
            13 => {
                let centre = [0, 1, 2].map(|i| (c[0][i] + c[6][i]) / 2);
                for face in HEX_FACES {
                    let mut base: Vec<[i64; 3]> = face.iter().map(|&v| c[v]).collect();
                    if volume([base[0], base[1], base[2], centre]) < 0 {
                        base.reverse();
                    }
                    base.push(centre);
                    b.cell(t, &t.nodes, &base, rng);
                }
            }
            _ => b.cell(t, &t.nodes, &c, rng),
        }
    }
    b
}

fn types() -> Vec<CellType> {
    let hex72_edges = {
        let mut e = HEX_EDGES;
        e.swap(10, 11);
        e
    };
    vec![
        CellType {
            id: 24,
            nodes: nodes(4, &TET_EDGES, &[], false),
            rotations: tet_rotations(),
        },
        CellType {
            id: 71,
            nodes: nodes(4, &TET_EDGES, &[], false),
            rotations: tet_rotations(),
        },
        CellType {
            id: 25,
            nodes: nodes(8, &HEX_EDGES, &[], false),
            rotations: hex_rotations(),
        },
        CellType {
            id: 29,
            nodes: nodes(8, &HEX_EDGES, &HEX_FACES, true),
            rotations: hex_rotations(),
        },
        CellType {
            id: 72,
            nodes: nodes(8, &hex72_edges, &HEX_FACES, true),
            rotations: hex_rotations(),
        },
        CellType {
            id: 26,
            nodes: nodes(6, &WEDGE_EDGES, &[], false),
            rotations: wedge_rotations(),
        },
        CellType {
            id: 32,
            nodes: nodes(6, &WEDGE_EDGES, &WEDGE_FACES, false),
            rotations: wedge_rotations(),
        },
        CellType {
            id: 73,
            nodes: nodes(6, &WEDGE_EDGES, &WEDGE_FACES, false),
            rotations: wedge_rotations(),
        },
        CellType {
            id: 27,
            nodes: nodes(5, &PYRAMID_EDGES, &[], false),
            rotations: pyramid_rotations(),
        },
    ]
}

#[test]
fn every_higher_order_type_splits_conformingly_in_every_orientation() {
    for t in types() {
        for seed in 0..12 {
            let mut rng = Lcg(1000 * t.id as u64 + seed);
            let b = build(&t, &mut rng);
            let text = b.legacy(&mut rng);
            let context = format!("type {} seed {seed}", t.id);
            let read = read_legacy_bytes(text.as_bytes(), "cells.vtk")
                .unwrap_or_else(|e| panic!("{context}: {e}"));
            let mesh = read.mesh;

            // Every triangle in at most two tets; the boundary triangles lie
            // on the box's faces (a non-conforming shared face would leave
            // its triangles inside the box).
            let faces = face_counts(&mesh.tets);
            assert!(
                faces.values().all(|&n| n <= 2),
                "{context}: a triangle in 3 tets"
            );
            let side = (CUBES * 2) as f32;
            let on_box_face = |f: &[u32; 3]| {
                (0..3).any(|axis| {
                    let c = f.map(|p| mesh.points[p as usize][axis]);
                    c.iter().all(|&v| v == 0.0) || c.iter().all(|&v| v == side)
                })
            };
            let boundary: Vec<_> = faces
                .iter()
                .filter(|&(_, &n)| n == 1)
                .map(|(f, _)| *f)
                .collect();
            assert!(
                boundary.iter().all(on_box_face),
                "{context}: a boundary triangle inside the box"
            );

            // The tets fill the box once: volumes (exact in f32 here) sum to
            // the box's, within 1e-9 relative for the f64 summation.
            let total: f64 = mesh
                .tets
                .iter()
                .map(|&t| volume6(&mesh, t).abs() / 6.0)
                .sum();
            let box_volume = (side as f64).powi(3);
            assert!(
                (total - box_volume).abs() <= 1e-9 * box_volume,
                "{context}: volume {total}"
            );

            // Added points carry the linear field exactly (serendipity and
            // Lagrange interpolation reproduce linear functions); 1e-5
            // relative for the f32 storage.
            assert_eq!(mesh.fields.len(), 1);
            for (p, &v) in mesh.points.iter().zip(&mesh.fields[0].values) {
                let want = field(p.x as f64, p.y as f64, p.z as f64);
                assert!(
                    (v as f64 - want).abs() <= 1e-5 * (1.0 + want.abs()),
                    "{context}: f at {p} is {v}, not {want}"
                );
            }

            // Validation (orientation, overlap, conformity) passes.
            let loaded = tetray_mesh::prepare(mesh).unwrap_or_else(|e| panic!("{context}: {e}"));
            assert_eq!(loaded.report.validation.components, 1, "{context}");
            let sub = &read.cells.subdivided;
            assert_eq!(sub.len(), 1, "{context}");
            assert_eq!(sub[0].type_id, t.id);
            assert_eq!(sub[0].cells, b.cells.len());
            assert_eq!(sub[0].tets, loaded.mesh.tets.len());
        }
    }
}

#[test]
fn added_points_are_shared_face_centres_and_body_centres() {
    // 2x2x2 cubes have 36 distinct quad faces (3 x 2 x 2 per direction)
    // and 8 bodies. The 20-node hexahedron gets all 44 points; the 27-node
    // ones none; the 15-node wedge the centres of its quads: the 24
    // vertical cube faces and the 8 diagonal quads cutting the cubes; the
    // pyramid (6 per cube, apex at the centre) its 36 bases. Each shared
    // face gets one point, not one per cell.
    let expected = [
        (25, 44),
        (29, 0),
        (72, 0),
        (24, 0),
        (26, 24 + 8),
        (32, 0),
        (27, 36),
    ];
    for t in types() {
        let Some(&(_, added)) = expected.iter().find(|(id, _)| *id == t.id) else {
            continue;
        };
        let mut rng = Lcg(t.id as u64);
        let text = build(&t, &mut rng).legacy(&mut rng);
        let read = read_legacy_bytes(text.as_bytes(), "cells.vtk").unwrap();
        assert_eq!(read.cells.points_added, added, "type {}", t.id);
        assert_eq!(
            read.cells.subdivided[0].points_added, added,
            "type {}",
            t.id
        );
    }
}

#[test]
fn corners_mode_keeps_the_linear_cells() {
    for t in types() {
        let mut rng = Lcg(7 + t.id as u64);
        let b = build(&t, &mut rng);
        let text = b.legacy(&mut rng);
        let opts = ReadOptions {
            linearize: Linearize::Corners,
        };
        let read = read_legacy_bytes_with(text.as_bytes(), "cells.vtk", &opts).unwrap();
        assert_eq!(read.cells.points_added, 0, "type {}", t.id);
        let corners = t.rotations[0].len();
        let used: std::collections::HashSet<u32> =
            read.mesh.tets.iter().flatten().copied().collect();
        let corner_ids: std::collections::HashSet<u32> = b
            .cells
            .iter()
            .flat_map(|(_, ids)| ids[..corners].to_vec())
            .collect();
        assert_eq!(
            used.len(),
            corner_ids.len(),
            "type {}: only corners used",
            t.id
        );
        let total: f64 = read
            .mesh
            .tets
            .iter()
            .map(|&tet| volume6(&read.mesh, tet).abs() / 6.0)
            .sum();
        assert!((total - 64.0).abs() < 1e-9 * 64.0, "type {}: {total}", t.id);
        tetray_mesh::prepare(read.mesh).unwrap();
    }
}
