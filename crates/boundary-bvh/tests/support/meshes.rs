//! Small tetrahedral meshes with known boundaries.

use glam::Vec3;
use tetray_mesh::TetMesh;

use super::Rng;

/// How each grid cube is cut into tetrahedra.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Split {
    /// Five tets, corner parity alternating so neighbouring cubes conform.
    Five,
    /// Six tets around the cube's main diagonal (Kuhn), conforming as is.
    Six,
}

/// A structured grid of `n[0] x n[1] x n[2]` cubes of edge `h` from `origin`,
/// keeping the cells where `keep(i, j, k)`. Points are shared; unused points
/// stay in the mesh (they are on no face).
pub struct Grid {
    pub n: [usize; 3],
    pub origin: Vec3,
    pub h: f32,
    pub split: Split,
}

impl Grid {
    pub fn point(&self, i: usize, j: usize, k: usize) -> Vec3 {
        self.origin + Vec3::new(i as f32, j as f32, k as f32) * self.h
    }

    pub fn index(&self, i: usize, j: usize, k: usize) -> u32 {
        (i + (self.n[0] + 1) * (j + (self.n[1] + 1) * k)) as u32
    }

    pub fn mesh(&self, keep: impl Fn(usize, usize, usize) -> bool) -> TetMesh {
        let [nx, ny, nz] = self.n;
        let mut points = Vec::new();
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    points.push(self.point(i, j, k));
                }
            }
        }
        let mut tets = Vec::new();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    if !keep(i, j, k) {
                        continue;
                    }
                    // Corner c = dx + 2 dy + 4 dz.
                    let c: [u32; 8] = std::array::from_fn(|c| {
                        self.index(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2))
                    });
                    let local: &[[usize; 4]] = match (self.split, (i + j + k) % 2) {
                        (Split::Six, _) => &[
                            [0, 1, 3, 7],
                            [0, 1, 5, 7],
                            [0, 2, 3, 7],
                            [0, 2, 6, 7],
                            [0, 4, 5, 7],
                            [0, 4, 6, 7],
                        ],
                        (Split::Five, 0) => &[
                            [1, 2, 4, 7],
                            [0, 1, 2, 4],
                            [3, 1, 2, 7],
                            [5, 1, 4, 7],
                            [6, 2, 4, 7],
                        ],
                        (Split::Five, _) => &[
                            [0, 3, 5, 6],
                            [1, 0, 3, 5],
                            [2, 0, 3, 6],
                            [4, 0, 5, 6],
                            [7, 3, 5, 6],
                        ],
                    };
                    tets.extend(local.iter().map(|l| l.map(|v| c[v])));
                }
            }
        }
        let mut mesh = TetMesh {
            points,
            tets,
            fields: Vec::new(),
        };
        orient(&mut mesh);
        mesh
    }
}

/// Signed volume times 6.
pub fn volume6(mesh: &TetMesh, tet: [u32; 4]) -> f32 {
    let [a, b, c, d] = tet.map(|v| mesh.points[v as usize]);
    (b - a).dot((c - a).cross(d - a))
}

/// Makes every tet positively oriented; panics on a flat one (a test bug).
pub fn orient(mesh: &mut TetMesh) {
    for t in 0..mesh.tets.len() {
        let v = volume6(mesh, mesh.tets[t]);
        assert!(v.abs() > 1e-9, "test mesh has a flat tet {t}");
        if v < 0.0 {
            mesh.tets[t].swap(2, 3);
        }
    }
}

/// Orients every non-flat tet positively; flat ones (degenerate hexes of
/// real grids) stay as they are.
pub fn orient_or_keep(mesh: &mut TetMesh) {
    for t in 0..mesh.tets.len() {
        if volume6(mesh, mesh.tets[t]) < 0.0 {
            mesh.tets[t].swap(2, 3);
        }
    }
}

/// Moves every point by up to `amount` per axis; asserts no tet inverts.
pub fn jitter(mesh: &mut TetMesh, amount: f32, rng: &mut Rng) {
    for p in &mut mesh.points {
        *p += Vec3::new(
            rng.range(-amount, amount),
            rng.range(-amount, amount),
            rng.range(-amount, amount),
        );
    }
    for &tet in &mesh.tets {
        assert!(volume6(mesh, tet) > 0.0, "jitter inverted a tet");
    }
}

/// Both meshes in one (disjoint point sets).
pub fn merge(mut a: TetMesh, b: &TetMesh) -> TetMesh {
    let offset = a.points.len() as u32;
    a.points.extend_from_slice(&b.points);
    a.tets.extend(b.tets.iter().map(|t| t.map(|v| v + offset)));
    a
}

/// A named test mesh with the grid that made it (for exact grid rays).
pub struct Case {
    pub name: &'static str,
    pub mesh: TetMesh,
    /// Grids whose lines and vertices the exact rays follow.
    pub grids: Vec<Grid>,
    /// A single convex box: every line enters at most once.
    pub convex: bool,
}

/// Binary-fraction spacing so grid coordinates are exact in f32.
fn box_grid(split: Split, n: [usize; 3]) -> Grid {
    Grid {
        n,
        origin: Vec3::new(-1.0, 0.5, -0.25),
        h: 0.25,
        split,
    }
}

pub fn cases() -> Vec<Case> {
    let mut rng = Rng::new(0x7e7_2a11);
    let five = box_grid(Split::Five, [4, 3, 5]);
    let six = box_grid(Split::Six, [5, 4, 3]);
    let box_five = five.mesh(|_, _, _| true);
    let box_six = six.mesh(|_, _, _| true);

    // Two boxes side by side with a gap, one of each split; a spacing that is
    // not a binary fraction.
    let left = Grid {
        n: [3, 3, 3],
        origin: Vec3::new(0.0, 0.0, 0.0),
        h: 0.1,
        split: Split::Five,
    };
    let right = Grid {
        n: [2, 4, 3],
        origin: Vec3::new(0.5, 0.05, -0.1),
        h: 0.1,
        split: Split::Six,
    };
    let two_boxes = merge(left.mesh(|_, _, _| true), &right.mesh(|_, _, _| true));

    // A 5^3 box with its middle 3x3x1 slab and 1x1x3 column removed: an inner
    // cavity with a concave rim, so lines leave and re-enter.
    let hollow_grid = box_grid(Split::Five, [5, 5, 5]);
    let hollow = hollow_grid.mesh(|i, j, k| {
        let slab = (1..4).contains(&i) && (1..4).contains(&j) && k == 2;
        let column = i == 2 && j == 2 && (1..4).contains(&k);
        !(slab || column)
    });

    let jitter_grid = box_grid(Split::Six, [5, 4, 4]);
    let mut jittered = jitter_grid.mesh(|i, j, k| (i + 2 * j + k) % 7 != 3);
    jitter(&mut jittered, 0.06 * 0.25, &mut rng);

    vec![
        Case {
            name: "box-5",
            mesh: box_five,
            grids: vec![five],
            convex: true,
        },
        Case {
            name: "box-6",
            mesh: box_six,
            grids: vec![six],
            convex: true,
        },
        Case {
            name: "two-boxes",
            mesh: two_boxes,
            grids: vec![left, right],
            convex: false,
        },
        Case {
            name: "hollow",
            mesh: hollow,
            grids: vec![hollow_grid],
            convex: false,
        },
        Case {
            name: "jittered",
            mesh: jittered,
            // Rays along the unjittered lines still graze jittered faces.
            grids: vec![jitter_grid],
            convex: false,
        },
    ]
}
