//! Watertightness of the shared ray/triangle predicate over closed boundary
//! surfaces, using the predicate alone (no BVH): exact integer-valued
//! properties, so no tolerance.

mod support;

use glam::{DVec2, Vec3};
use support::meshes::cases;
use support::rays::{grid_queries, random_queries};
use support::{Rng, line_crossings, topology};
use tetray_core::watertight::{Projector, RayFrame};
use tetray_mesh::{TetMesh, Topology};

fn counts(mesh: &TetMesh, topo: &Topology, ray: &RayFrame) -> (usize, usize) {
    let crossings = line_crossings(mesh, topo, ray);
    let entering = crossings.iter().filter(|(_, x)| x.entering).count();
    (entering, crossings.len() - entering)
}

/// A line meets a closed surface as often going in as coming out, whether it
/// passes through vertices, runs along edges or lies in face planes.
#[test]
fn every_line_enters_as_often_as_it_leaves() {
    let mut rng = Rng::new(11);
    for case in cases() {
        let topo = topology(&case.mesh);
        let mut queries = random_queries(&case.mesh, 1000, &mut rng);
        let random_count = queries.len();
        for grid in &case.grids {
            queries.extend(grid_queries(grid));
        }
        let mut hitting = 0;
        for (i, q) in queries.iter().enumerate() {
            let (entering, leaving) = counts(&case.mesh, &topo, &q.ray);
            assert_eq!(entering, leaving, "{}: {:?}", case.name, q.ray);
            if case.convex {
                assert!(
                    entering <= 1,
                    "{}: convex box entered {entering} times",
                    case.name
                );
            }
            hitting += usize::from(entering > 0);
            // Random lines are in general position: no two crossings share a
            // distance, and in distance order they alternate in, out, in...
            if i < random_count {
                let crossings = line_crossings(&case.mesh, &topo, &q.ray);
                for (k, (_, x)) in crossings.iter().enumerate() {
                    assert_eq!(x.entering, k % 2 == 0, "{}: order {crossings:?}", case.name);
                }
            }
        }
        assert!(
            hitting * 4 > queries.len(),
            "{}: only {hitting} lines hit",
            case.name
        );
    }
}

/// Closed-triangle test in the plane `axis = const` (exact here: binary
/// fraction coordinates, f64 arithmetic).
fn contains(tri: [Vec3; 3], p: Vec3, axis: usize) -> bool {
    let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
    let flat = |v: Vec3| DVec2::new(f64::from(v[a1]), f64::from(v[a2]));
    let [a, b, c] = tri.map(flat);
    let p = flat(p);
    let e = [
        (b - a).perp_dot(p - a),
        (c - b).perp_dot(p - b),
        (a - c).perp_dot(p - c),
    ];
    e.iter().all(|&x| x >= 0.0) || e.iter().all(|&x| x <= 0.0)
}

/// Axis-aligned lines through the vertices, edge midpoints and cell centres
/// of a box's end faces: exactly one face of each fan claims the entry (and
/// one the exit), the claimed face touches the point, and the distance is
/// the exact distance to the face plane.
#[test]
fn shared_vertices_and_edges_are_claimed_exactly_once() {
    for case in cases().into_iter().filter(|c| c.convex) {
        let topo = topology(&case.mesh);
        let grid = &case.grids[0];
        let tri = |f: u32| {
            topo.boundary_faces[f as usize]
                .vertices
                .map(|v| case.mesh.points[v as usize])
        };
        let mut shared = 0;
        for axis in 0..3 {
            let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
            // Strictly inside the cross-section, in half steps.
            for p2 in 1..2 * grid.n[a1] {
                for q2 in 1..2 * grid.n[a2] {
                    for sign in [1.0f32, -1.0] {
                        let mut point = grid.origin;
                        point[a1] += p2 as f32 * 0.5 * grid.h;
                        point[a2] += q2 as f32 * 0.5 * grid.h;
                        // The end face the line enters through.
                        point[axis] += if sign > 0.0 {
                            0.0
                        } else {
                            grid.n[axis] as f32 * grid.h
                        };
                        let mut dir = Vec3::ZERO;
                        dir[axis] = sign;
                        let ray = RayFrame::new(point - dir, dir);
                        let crossings = line_crossings(&case.mesh, &topo, &ray);
                        let entries: Vec<_> =
                            crossings.iter().filter(|(_, x)| x.entering).collect();
                        assert_eq!(entries.len(), 1, "{}: {crossings:?}", case.name);
                        assert_eq!(crossings.len(), 2, "{}: {crossings:?}", case.name);
                        let (face, x) = entries[0];
                        assert_eq!(x.t, 1.0, "{}: entry distance", case.name);
                        assert!(
                            contains(tri(*face), point, axis),
                            "{}: face {face}",
                            case.name
                        );
                        // How many boundary faces touch the point: a fan of
                        // two or more when it is on a vertex or an edge.
                        let fan = (0..topo.boundary_faces.len() as u32)
                            .filter(|&f| {
                                let t = tri(f);
                                t.iter().all(|v| v[axis] == point[axis]) && contains(t, point, axis)
                            })
                            .count();
                        shared += usize::from(fan >= 2);
                    }
                }
            }
        }
        assert!(
            shared > 50,
            "{}: only {shared} lines through shared points",
            case.name
        );
    }
}

/// The walk projects its vertices with a `Projector` and the BVH with
/// `RayFrame::project`: both must give a point the same bits, or a face's
/// crossing would depend on who computed it.
#[test]
fn projector_gives_the_frame_projection_bits() {
    let mut rng = Rng::new(5);
    for case in cases() {
        for q in random_queries(&case.mesh, 200, &mut rng) {
            let projector = Projector::new(&q.ray);
            for _ in 0..20 {
                let p = Vec3::new(
                    rng.range(-1e3, 1e3),
                    rng.range(-1.0, 1.0),
                    rng.range(-1e-3, 1e-3),
                ) * rng.range(0.0, 2.0);
                let want = q.ray.project(p);
                let got = projector.project(p.extend(rng.unit()));
                assert_eq!(
                    [got.x, got.y, got.z].map(f32::to_bits),
                    [want.x, want.y, want.z].map(f32::to_bits),
                    "{}: {p} on {:?}",
                    case.name,
                    q.ray
                );
            }
        }
    }
}
