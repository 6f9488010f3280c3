//! Query rays: random ones and ones exactly along grid lines and planes.

use glam::Vec3;
use tetray_core::watertight::RayFrame;
use tetray_mesh::TetMesh;

use super::Rng;
use super::meshes::Grid;

/// A ray with the query range to ask about.
#[derive(Debug, Clone, Copy)]
pub struct Query {
    pub ray: RayFrame,
    pub t_min: f32,
    pub t_max: f32,
}

fn bounds(mesh: &TetMesh) -> (Vec3, Vec3) {
    mesh.points
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        })
}

pub fn random_dir(rng: &mut Rng) -> Vec3 {
    loop {
        let d = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let len2 = d.length_squared();
        if len2 > 1e-4 && len2 <= 1.0 {
            return d;
        }
    }
}

/// A uniformly random point inside a random tetrahedron.
pub fn point_inside(mesh: &TetMesh, rng: &mut Rng) -> Vec3 {
    let tet = mesh.tets[rng.below(mesh.tets.len())];
    let mut w = [rng.unit(), rng.unit(), rng.unit(), rng.unit()];
    let sum: f32 = w.iter().sum::<f32>() + 1e-6;
    w.iter_mut().for_each(|x| *x /= sum);
    tet.iter()
        .zip(w)
        .map(|(&v, w)| mesh.points[v as usize] * w)
        .sum()
}

/// `count` rays: half from anywhere in the (enlarged) bounding box, mostly
/// outside the mesh, half from inside a tetrahedron; random directions and a
/// mix of query ranges (whole line, from the origin, random windows).
pub fn random_queries(mesh: &TetMesh, count: usize, rng: &mut Rng) -> Vec<Query> {
    let (lo, hi) = bounds(mesh);
    let extent = hi - lo;
    (0..count)
        .map(|i| {
            let origin = if i % 2 == 0 {
                lo - extent * 0.5 + extent * 2.0 * Vec3::new(rng.unit(), rng.unit(), rng.unit())
            } else {
                point_inside(mesh, rng)
            };
            let ray = RayFrame::new(origin, random_dir(rng));
            let scale = extent.length();
            let (t_min, t_max) = match i % 4 {
                0 => (0.0, f32::INFINITY),
                1 => (f32::NEG_INFINITY, f32::INFINITY),
                2 => (rng.range(-scale, scale), f32::INFINITY),
                _ => {
                    let a = rng.range(-scale, scale);
                    (a, a + rng.range(0.0, scale))
                }
            };
            Query { ray, t_min, t_max }
        })
        .collect()
}

/// Rays exactly along grid lines (through every vertex of a line) and along
/// grid planes (half-way between lines), both ways along each axis, from
/// outside the grid and from grid vertices themselves; plus diagonal rays
/// aimed through grid vertices.
pub fn grid_queries(grid: &Grid) -> Vec<Query> {
    let mut out = Vec::new();
    let h = grid.h;
    let n = grid.n.map(|n| n as i32);
    let coord = |axis: usize, i: f32| grid.origin[axis] + i * h;
    for axis in 0..3 {
        let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
        // Line positions in half steps, one step beyond the grid each side.
        for p2 in -2..=2 * n[a1] + 2 {
            for q2 in -2..=2 * n[a2] + 2 {
                for sign in [1.0f32, -1.0] {
                    let mut origin = Vec3::ZERO;
                    origin[a1] = coord(a1, p2 as f32 * 0.5);
                    origin[a2] = coord(a2, q2 as f32 * 0.5);
                    let start = if sign > 0.0 {
                        -2.0
                    } else {
                        n[axis] as f32 + 2.0
                    };
                    origin[axis] = coord(axis, start);
                    let mut dir = Vec3::ZERO;
                    dir[axis] = sign;
                    let ray = RayFrame::new(origin, dir);
                    out.push(Query {
                        ray,
                        t_min: 0.0,
                        t_max: f32::INFINITY,
                    });
                    // Starting on a grid vertex / on a grid plane mid-grid.
                    if p2 % 2 == 0 && q2 % 2 == 0 {
                        origin[axis] = coord(axis, (n[axis] / 2) as f32);
                        out.push(Query {
                            ray: RayFrame::new(origin, dir),
                            t_min: 0.0,
                            t_max: f32::INFINITY,
                        });
                    }
                }
            }
        }
    }
    let diagonals = [
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, -1.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
    ];
    for k in 0..=grid.n[2] {
        for j in 0..=grid.n[1] {
            for i in 0..=grid.n[0] {
                let through = grid.point(i, j, k);
                for (d, dir) in diagonals.iter().enumerate() {
                    if (i + j + k + d) % 3 != 0 {
                        continue; // a third of them keeps the test fast
                    }
                    out.push(Query {
                        ray: RayFrame::new(through - *dir * (4.0 * h), *dir),
                        t_min: 0.0,
                        t_max: f32::INFINITY,
                    });
                }
            }
        }
    }
    out
}
