//! Conformity: where tetrahedra do not meet face to face, faces are left
//! unmatched inside the mesh. They are boundary faces of the topology, and a
//! ray leaving through one re-enters through the coincident face(s) of the
//! other side by the boundary BVH, exactly as at a seam: the image is that
//! of a conforming mesh. Validation reports them (warnings), found as:
//! - a hanging node (a T-junction): a point of one tetrahedron lies on an
//!   edge or inside a face of another;
//! - two sides of a shared quadrilateral split along different diagonals.
//!
//! Face matching alone cannot see either: the unmatched faces on both sides
//! of the crack form closed surfaces, so the boundary is still closed edge
//! by edge (as many i->j as j->i: that holds for the boundary of any set of
//! tetrahedra whose matched faces have opposite orientations, which
//! validation checks). The tests are geometric instead, within f32
//! resolution: a boundary point lying on a boundary face that does not
//! have it as a corner (possibly through a duplicate point, as on a seam),
//! and two boundary faces sharing an edge and folded onto each other
//! (unless they coincide through duplicate points: a seam). Nothing here
//! changes the walk; it only names the faces for the load report.

use glam::DVec3;
use rayon::prelude::*;

use crate::{BoundaryFace, DEGENERATE_HEIGHT_ULPS, TetMesh, Topology};

/// A point found on a boundary face that does not have it as a corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct HangingNode {
    pub point: u32,
    pub face: BoundaryFace,
    /// Whether the point is on an edge of the face (else inside it).
    pub on_edge: bool,
}

/// Two boundary faces sharing an edge and lying on each other.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FoldedFaces {
    pub edge: [u32; 2],
    pub faces: [BoundaryFace; 2],
}

/// Leaf size of the face hierarchy.
const LEAF: usize = 8;

struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: range in `order`; inner: `start` is the left child, `end` the
    /// right one.
    start: u32,
    end: u32,
    leaf: bool,
}

/// A bounding-box hierarchy over boundary faces (split at the middle of
/// the faces' centroids, or at their median).
struct FaceTree {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl FaceTree {
    fn build(corners: &[[DVec3; 3]]) -> FaceTree {
        let mut order: Vec<u32> = (0..corners.len() as u32).collect();
        let nodes = subtree(corners, &mut order, 0);
        FaceTree { nodes, order }
    }

    /// Calls `visit` on every face whose box, grown by `tol`, holds `p`,
    /// until it returns `true`.
    fn any_near(&self, p: DVec3, tol: f64, mut visit: impl FnMut(u32) -> bool) -> bool {
        let mut stack = vec![0u32];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if p.cmplt(node.lo - tol).any() || p.cmpgt(node.hi + tol).any() {
                continue;
            }
            if node.leaf {
                if self.order[node.start as usize..node.end as usize]
                    .iter()
                    .any(|&f| visit(f))
                {
                    return true;
                }
            } else {
                stack.push(node.start);
                stack.push(node.end);
            }
        }
        false
    }
}

/// From this many faces a subtree's two halves are built in parallel.
const PARALLEL_FACES: usize = 1 << 15;

/// The nodes of the subtree over `order` (the faces from `start` on in the
/// whole order; reordered in place), in preorder: its root first, then the
/// left subtree, then the right one. Leaves hold ranges of the whole order;
/// inner nodes hold child indices within this subtree's nodes.
fn subtree(corners: &[[DVec3; 3]], order: &mut [u32], start: usize) -> Vec<Node> {
    if order.len() < PARALLEL_FACES {
        let mut nodes = Vec::new();
        split(corners, order, start, &mut nodes);
        return nodes;
    }
    let (lo, hi, mid) = bounds_and_median(corners, order);
    let (left_order, right_order) = order.split_at_mut(mid);
    let (left, right) = rayon::join(
        || subtree(corners, left_order, start),
        || subtree(corners, right_order, start + mid),
    );
    let right_root = 1 + left.len();
    let mut nodes = Vec::with_capacity(right_root + right.len());
    nodes.push(Node {
        lo,
        hi,
        start: 1,
        end: right_root as u32,
        leaf: false,
    });
    for (offset, part) in [(1, left), (right_root, right)] {
        nodes.extend(part.into_iter().map(|mut node| {
            if !node.leaf {
                node.start += offset as u32;
                node.end += offset as u32;
            }
            node
        }));
    }
    nodes
}

/// Appends the subtree over `order` (from `start` on in the whole order)
/// to `nodes` in preorder, serially; returns its root's index.
fn split(corners: &[[DVec3; 3]], order: &mut [u32], start: usize, nodes: &mut Vec<Node>) -> u32 {
    let index = nodes.len();
    let count = order.len();
    if count <= LEAF {
        let (lo, hi) = bounds(corners, order);
        nodes.push(Node {
            lo,
            hi,
            start: start as u32,
            end: (start + count) as u32,
            leaf: true,
        });
        return index as u32;
    }
    let (lo, hi, mid) = bounds_and_median(corners, order);
    // Replaced below once the children's indices are known.
    nodes.push(Node {
        lo,
        hi,
        start: 0,
        end: 0,
        leaf: false,
    });
    let (left_order, right_order) = order.split_at_mut(mid);
    let left = split(corners, left_order, start, nodes);
    let right = split(corners, right_order, start + mid, nodes);
    nodes[index].start = left;
    nodes[index].end = right;
    index as u32
}

/// The bounds of the faces of `order`.
fn bounds(corners: &[[DVec3; 3]], order: &[u32]) -> (DVec3, DVec3) {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for &f in order {
        for p in corners[f as usize] {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (lo, hi)
}

/// The bounds of the faces of `order`, and `order` split in two along the
/// longest axis of the faces' centroids, at the middle of their range. (The longest axis of
/// the faces' own bounds would not do: long thin faces, such as those of
/// an image with one thin cell across, keep a node's bounds long along
/// their length however it is split, and the splits would never separate
/// the faces along the other axes.)
fn bounds_and_median(corners: &[[DVec3; 3]], order: &mut [u32]) -> (DVec3, DVec3, usize) {
    let (lo, hi) = bounds(corners, order);
    let sum = |f: u32| {
        let [a, b, c] = corners[f as usize];
        a + b + c
    };
    let (clo, chi) = order
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(clo, chi), &f| {
            (clo.min(sum(f)), chi.max(sum(f)))
        });
    let axis = (chi - clo).max_position();
    let centroid = |f: u32| sum(f)[axis];
    // At the middle of the centroids' range: faces that share a centroid
    // coordinate (a plane of faces) stay together, where a median would
    // cut through them and mix planes in every node below.
    let middle = 0.5 * (clo[axis] + chi[axis]);
    let mut mid = 0;
    for i in 0..order.len() {
        if centroid(order[i]) < middle {
            order.swap(mid, i);
            mid += 1;
        }
    }
    // A split that leaves under a sixteenth on one side takes the median
    // instead, which bounds the depth (graded meshes, hostile input).
    let small = order.len() / 16;
    if mid <= small || mid >= order.len() - small {
        mid = order.len() / 2;
        order.select_nth_unstable_by(mid, |&x, &y| centroid(x).total_cmp(&centroid(y)));
    }
    (lo, hi, mid)
}

/// Distance from `p` to the segment `a b`.
fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t - p).length()
}

/// Where `p` is relative to triangle `t` within `tol`: `None` when off it
/// or at a corner, `Some(true)` on an edge, `Some(false)` inside.
fn on_triangle(p: DVec3, t: [DVec3; 3], tol: f64) -> Option<bool> {
    if t.iter().any(|&c| (c - p).length() <= tol) {
        return None;
    }
    let normal = (t[1] - t[0]).cross(t[2] - t[0]);
    let len2 = normal.length_squared();
    if len2 == 0.0 || (p - t[0]).dot(normal).abs() > tol * len2.sqrt() {
        return None;
    }
    let edge = (0..3).any(|e| segment_distance(p, t[e], t[(e + 1) % 3]) <= tol);
    if edge {
        return Some(true);
    }
    // Inside when p is on the inner side of all three edges.
    let inside = (0..3).all(|e| (t[(e + 1) % 3] - t[e]).cross(p - t[e]).dot(normal) >= 0.0);
    inside.then_some(false)
}

/// Every boundary point lying on a boundary face that does not have it as
/// a corner, once per such face, by point index.
/// `canonical` maps each point to the lowest index with the same
/// coordinates.
pub(crate) fn find_hanging_nodes(
    mesh: &TetMesh,
    topology: &Topology,
    canonical: &[u32],
) -> Vec<HangingNode> {
    let faces = &topology.boundary_faces;
    if faces.is_empty() {
        return Vec::new();
    }
    let point = |i: u32| mesh.points[i as usize].as_dvec3();
    let corners: Vec<[DVec3; 3]> = faces.iter().map(|f| f.vertices.map(point)).collect();
    let tree = FaceTree::build(&corners);
    let mut points: Vec<u32> = faces.iter().flat_map(|f| f.vertices).collect();
    points.par_sort_unstable();
    points.dedup();
    let ulp = DEGENERATE_HEIGHT_ULPS * f64::from(f32::EPSILON);
    // Boxes grow by the largest tolerance any face test can use.
    let box_tol = ulp
        * corners
            .iter()
            .flatten()
            .fold(0.0, |m: f64, c| m.max(c.abs().max_element()));
    points
        .par_iter()
        .flat_map_iter(|&v| hanging_at(v, point(v), faces, &corners, &tree, canonical, box_tol))
        .collect()
}

/// Every boundary face (within `box_tol` of `p`) that point `v` lies on
/// without being its corner.
fn hanging_at(
    v: u32,
    p: DVec3,
    faces: &[BoundaryFace],
    corners: &[[DVec3; 3]],
    tree: &FaceTree,
    canonical: &[u32],
    box_tol: f64,
) -> Vec<HangingNode> {
    let ulp = DEGENERATE_HEIGHT_ULPS * f64::from(f32::EPSILON);
    let mut found = Vec::new();
    tree.any_near(p, box_tol, |f| {
        let face = faces[f as usize];
        if face
            .vertices
            .iter()
            .any(|&c| canonical[c as usize] == canonical[v as usize])
        {
            return false;
        }
        let t = corners[f as usize];
        let scale = t
            .iter()
            .fold(p.abs().max_element(), |m, c| m.max(c.abs().max_element()));
        if let Some(on_edge) = on_triangle(p, t, ulp * scale) {
            found.push(HangingNode {
                point: v,
                face,
                on_edge,
            });
        }
        false
    });
    found
}

/// Every pair of boundary faces (in edge order) that share an edge and
/// lie folded onto each other: coplanar within f32 resolution, with their
/// third points on the same side of the edge. Pairs whose third points
/// coincide (`canonical`) are seams and pass.
pub(crate) fn find_folded_faces(
    mesh: &TetMesh,
    topology: &Topology,
    canonical: &[u32],
) -> Vec<FoldedFaces> {
    let faces = &topology.boundary_faces;
    let mut edges: Vec<(u64, u32)> = faces
        .par_iter()
        .enumerate()
        .flat_map_iter(|(b, face)| {
            let v = face.vertices;
            (0..3).map(move |e| {
                let (i, j) = (v[e], v[(e + 1) % 3]);
                ((u64::from(i.min(j)) << 32) | u64::from(i.max(j)), b as u32)
            })
        })
        .collect();
    edges.par_sort_unstable();
    let point = |i: u32| mesh.points[i as usize].as_dvec3();
    let ulp = DEGENERATE_HEIGHT_ULPS * f64::from(f32::EPSILON);
    let runs: Vec<&[(u64, u32)]> = edges
        .chunk_by(|a, b| a.0 == b.0)
        .filter(|r| r.len() > 1)
        .collect();
    let mut found: Vec<FoldedFaces> = runs
        .par_iter()
        .flat_map_iter(|run| {
            let mut pairs = Vec::new();
            let edge = [(run[0].0 >> 32) as u32, run[0].0 as u32];
            let apex = |b: u32| {
                let face = faces[b as usize];
                face.vertices
                    .into_iter()
                    .find(|v| !edge.contains(v))
                    .unwrap_or(face.vertices[0])
            };
            let (u, v) = (point(edge[0]), point(edge[1]));
            for (x, &(_, fa)) in run.iter().enumerate() {
                for &(_, fb) in &run[x + 1..] {
                    let (a, b) = (apex(fa), apex(fb));
                    if canonical[a as usize] == canonical[b as usize] {
                        continue;
                    }
                    let (pa, pb) = (point(a), point(b));
                    let normal = (v - u).cross(pa - u);
                    let len = normal.length();
                    let scale = [u, v, pa, pb]
                        .iter()
                        .fold(0.0, |m: f64, p| m.max(p.abs().max_element()));
                    let coplanar = len > 0.0 && (pb - u).dot(normal).abs() <= ulp * scale * len;
                    let across = normal.cross(v - u);
                    if coplanar && (pa - u).dot(across) * (pb - u).dot(across) > 0.0 {
                        pairs.push(FoldedFaces {
                            edge,
                            faces: [faces[fa as usize], faces[fb as usize]],
                        });
                    }
                }
            }
            pairs
        })
        .collect();
    found.sort_unstable_by_key(|f| f.edge);
    found
}

/// What [`nonconformity`] found.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct NonConformity {
    /// Points lying on a boundary face (or its edge) of another tetrahedron.
    pub hanging_nodes: usize,
    /// Pairs of boundary faces sharing an edge and lying on each other.
    pub folded_pairs: usize,
    /// The boundary faces taking part, by tetrahedron and local face.
    pub faces: Vec<BoundaryFace>,
}

/// The non-conforming contacts of a mesh: hanging nodes and folded faces,
/// and the boundary faces on both sides of them. A face holding a hanging
/// node is one side; the other side is made of the boundary faces around
/// that node lying in the same plane (within f32 resolution).
pub(crate) fn nonconformity(
    mesh: &TetMesh,
    topology: &Topology,
    canonical: &[u32],
) -> NonConformity {
    let hanging = find_hanging_nodes(mesh, topology, canonical);
    let folded = find_folded_faces(mesh, topology, canonical);
    let mut faces: Vec<BoundaryFace> = folded.iter().flat_map(|f| f.faces).collect();
    if !hanging.is_empty() {
        let faces_at = faces_by_point(topology, mesh.points.len());
        let point = |i: u32| mesh.points[i as usize].as_dvec3();
        let ulp = DEGENERATE_HEIGHT_ULPS * f64::from(f32::EPSILON);
        for h in &hanging {
            faces.push(h.face);
            let t = h.face.vertices.map(point);
            let normal = (t[1] - t[0]).cross(t[2] - t[0]);
            let len = normal.length();
            let scale = t.iter().fold(0.0, |m: f64, c| m.max(c.abs().max_element()));
            let at = &faces_at.1[faces_at.0[h.point as usize]..faces_at.0[h.point as usize + 1]];
            for &b in at {
                let other = topology.boundary_faces[b as usize];
                let in_plane = other.vertices.iter().all(|&v| {
                    (point(v) - t[0]).dot(normal).abs()
                        <= ulp * scale.max(point(v).abs().max_element()) * len
                });
                if len > 0.0 && in_plane {
                    faces.push(other);
                }
            }
        }
    }
    faces.sort_unstable_by_key(|f| (f.tet, f.local_face));
    faces.dedup();
    let mut points: Vec<u32> = hanging.iter().map(|h| h.point).collect();
    points.dedup();
    NonConformity {
        hanging_nodes: points.len(),
        folded_pairs: folded.len(),
        faces,
    }
}

/// Boundary faces by point, compressed: the faces at point `p` are
/// `list[start[p]..start[p + 1]]`.
fn faces_by_point(topology: &Topology, npoints: usize) -> (Vec<usize>, Vec<u32>) {
    let mut start = vec![0usize; npoints + 1];
    for face in &topology.boundary_faces {
        for &v in &face.vertices {
            start[v as usize + 1] += 1;
        }
    }
    for i in 0..npoints {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut list = vec![0u32; start[npoints]];
    for (b, face) in topology.boundary_faces.iter().enumerate() {
        for &v in &face.vertices {
            list[fill[v as usize]] = b as u32;
            fill[v as usize] += 1;
        }
    }
    (start, list)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tree built in parallel (above `PARALLEL_FACES`) is the one built
    /// serially, node for node, and its queries visit every face whose
    /// grown box holds the point.
    #[test]
    fn parallel_face_tree_is_the_serial_one() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let corners: Vec<[DVec3; 3]> = (0..3 * PARALLEL_FACES)
            .map(|_| {
                let c = DVec3::new(next(), next(), next()) * 100.0;
                [0, 1, 2].map(|_| c + DVec3::new(next(), next(), next()))
            })
            .collect();
        let tree = FaceTree::build(&corners);
        let mut order: Vec<u32> = (0..corners.len() as u32).collect();
        let mut nodes = Vec::new();
        split(&corners, &mut order, 0, &mut nodes);
        assert_eq!(tree.order, order);
        assert_eq!(tree.nodes.len(), nodes.len());
        for (a, b) in tree.nodes.iter().zip(&nodes) {
            assert_eq!(
                (a.lo, a.hi, a.start, a.end, a.leaf),
                (b.lo, b.hi, b.start, b.end, b.leaf)
            );
        }
        let tol = 0.01;
        for _ in 0..200 {
            let p = DVec3::new(next(), next(), next()) * 100.0;
            let mut visited = vec![false; corners.len()];
            tree.any_near(p, tol, |f| {
                visited[f as usize] = true;
                false
            });
            for (f, t) in corners.iter().enumerate() {
                let lo = t[0].min(t[1]).min(t[2]) - tol;
                let hi = t[0].max(t[1]).max(t[2]) + tol;
                if p.cmpge(lo).all() && p.cmple(hi).all() {
                    assert!(visited[f], "face {f} near {p}");
                }
            }
        }
    }

    /// Long thin faces (an image of 11012 x 3 x 2 points, spacing 1.5e-4
    /// along x and 1 along z: found by the `hdf5_formats` fuzz target, whose
    /// 22 k-cell image took 90 s to check) are separated along x by the
    /// splits: a query visits a few leaves' faces, not a share of all of
    /// them. Counted, not timed.
    #[test]
    fn thin_faces_are_split_along_their_short_axis() {
        let dx = 1.0 / 65536.0 * 10.0;
        let n = 11011;
        let mut corners = Vec::new();
        for i in 0..n {
            let (x0, x1) = (i as f64 * dx, (i + 1) as f64 * dx);
            for y in [0.0, 0.25, 0.5] {
                let quad =
                    [(x0, 0.0), (x1, 0.0), (x1, 1.0), (x0, 1.0)].map(|(x, z)| DVec3::new(x, y, z));
                corners.push([quad[0], quad[1], quad[2]]);
                corners.push([quad[0], quad[2], quad[3]]);
            }
        }
        let tree = FaceTree::build(&corners);
        let mut visits = 0usize;
        let queries = 1000;
        for q in 0..queries {
            let p = DVec3::new((q * n / queries) as f64 * dx, 0.25, 0.5);
            tree.any_near(p, 1e-9, |_| {
                visits += 1;
                false
            });
        }
        // The faces whose boxes hold a point: at most the 2 triangles of
        // each of 2 cells on its plane; a leaf holds 8 faces.
        let mean = visits as f64 / queries as f64;
        assert!(mean <= 4.0 * LEAF as f64, "{mean} faces visited per query");
    }
}
