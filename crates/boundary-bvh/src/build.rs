//! Building the BVH over the boundary faces with obvhs.

use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::triangle::Triangle;
use tetray_mesh::{TetMesh, Topology};

use crate::bvh4::Bvh4;
use crate::{BuildPreset, BvhError};

/// A BVH2 over the boundary faces of one mesh, with the face vertices copied
/// in leaf order so a query needs neither the mesh nor the topology.
#[derive(Clone)]
pub struct BoundaryBvh {
    pub(crate) bvh: Bvh2,
    /// `bvh` collapsed to four children per node, for the CPU's queries.
    pub(crate) bvh4: Bvh4,
    /// Per primitive slot of `bvh` (what leaves index): the boundary face.
    /// With spatial pre-splits a face can own several slots.
    pub(crate) prim_faces: Vec<u32>,
    /// Per primitive slot: the face's vertices, outward counter-clockwise.
    pub(crate) prim_tris: Vec<[Vec3; 3]>,
    /// Each face's first primitive slot, ascending: every face once, in
    /// leaf order.
    pub(crate) face_slots: Vec<u32>,
    /// Per boundary face: its point indices (for the flat GPU layout).
    pub(crate) face_vertices: Vec<[u32; 3]>,
    /// Largest coordinate magnitude of any boundary point (box padding scale).
    pub(crate) scene_abs_max: f32,
    pub(crate) stats: BvhStats,
}

/// Size and cost of a built [`BoundaryBvh`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BvhStats {
    pub preset: BuildPreset,
    /// Boundary faces indexed.
    pub faces: usize,
    /// Primitive references in leaves (more than `faces` with pre-splits).
    pub primitive_refs: usize,
    /// Nodes reachable from the root, inner and leaf.
    pub nodes: usize,
    pub leaves: usize,
    /// Edges on the longest root-to-leaf path (0 for a single leaf).
    pub max_depth: u32,
    pub max_leaf_size: u32,
    /// obvhs' core build time (spatial pre-splits, PLOC, reinsertion,
    /// collapse); excludes input checks, per-face boxes, the leaf-order copy
    /// and obvhs' debug-build validation, so it is comparable across
    /// profiles.
    pub build_time: Duration,
}

impl BoundaryBvh {
    /// Builds over `topology.boundary_faces` (vertices counter-clockwise from
    /// outside, points from `mesh`). Face `i` of the topology is face `i` in
    /// every query result.
    pub fn build(
        mesh: &TetMesh,
        topology: &Topology,
        preset: BuildPreset,
    ) -> Result<BoundaryBvh, BvhError> {
        let faces = &topology.boundary_faces;
        if faces.is_empty() {
            return Err(BvhError::NoBoundaryFaces);
        }
        if u32::try_from(faces.len()).is_err() {
            return Err(BvhError::TooManyFaces { faces: faces.len() });
        }
        let mut tris = Vec::with_capacity(faces.len());
        let mut scene_abs_max = 0.0f32;
        for (face_index, face) in (0u32..).zip(faces) {
            let mut tri = [Vec3::ZERO; 3];
            for (slot, &point) in tri.iter_mut().zip(&face.vertices) {
                let p = *mesh
                    .points
                    .get(point as usize)
                    .ok_or(BvhError::PointOutOfRange {
                        face: face_index,
                        point,
                        points: mesh.points.len(),
                    })?;
                if !p.is_finite() {
                    return Err(BvhError::NonFinitePoint {
                        face: face_index,
                        point,
                        coords: p.to_array(),
                    });
                }
                scene_abs_max = scene_abs_max.max(p.abs().max_element());
                *slot = p;
            }
            tris.push(tri);
        }

        let obvhs_tris: Vec<Triangle> = tris
            .iter()
            .map(|&[a, b, c]| Triangle {
                v0: Vec3A::from(a),
                v1: Vec3A::from(b),
                v2: Vec3A::from(c),
            })
            .collect();
        let mut build_time = Duration::ZERO;
        let bvh = build_bvh2_from_tris(&obvhs_tris, preset.params(), &mut build_time);

        // obvhs leaves index `primitive_indices`, whose entries are input
        // (face) indices; copy the faces into that order for locality.
        let prim_faces = bvh.primitive_indices.clone();
        let prim_tris = prim_faces.iter().map(|&f| tris[f as usize]).collect();
        let face_slots = first_slots(&prim_faces, faces.len());
        let shape = tree_shape(&bvh);
        let stats = BvhStats {
            preset,
            faces: faces.len(),
            primitive_refs: shape.primitive_refs,
            nodes: shape.nodes,
            leaves: shape.leaves,
            max_depth: shape.max_depth,
            max_leaf_size: shape.max_leaf_size,
            build_time,
        };
        Ok(BoundaryBvh {
            bvh4: Bvh4::collapse(&bvh)?,
            bvh,
            face_vertices: faces.iter().map(|f| f.vertices).collect(),
            prim_faces,
            prim_tris,
            face_slots,
            scene_abs_max,
            stats,
        })
    }

    /// Node count, depth and build time.
    pub fn stats(&self) -> BvhStats {
        self.stats
    }

    /// Number of boundary faces indexed.
    /// Largest coordinate magnitude of any boundary point.
    pub fn scene_abs_max(&self) -> f32 {
        self.scene_abs_max
    }

    pub fn face_count(&self) -> usize {
        self.stats.faces
    }

    /// The `i`-th boundary face in leaf order (`i < face_count()`) and its
    /// vertices, outward counter-clockwise (the mesh's points): a pass over
    /// every face that needs only its points reads them in this order from
    /// one array, faces near in space near in memory, where the faces'
    /// point indices would gather them from the whole mesh.
    #[inline]
    pub fn face_in_leaf_order(&self, i: usize) -> (u32, [Vec3; 3]) {
        let slot = self.face_slots[i] as usize;
        (self.prim_faces[slot], self.prim_tris[slot])
    }

    /// Bytes of the arrays the CPU's queries read: the wide tree's nodes,
    /// and the faces' vertices and indices in leaf order.
    pub fn query_bytes(&self) -> usize {
        self.bvh4.bytes()
            + self.prim_tris.len() * std::mem::size_of::<[Vec3; 3]>()
            + self.prim_faces.len() * std::mem::size_of::<u32>()
    }
}

/// Each of `faces` faces' first slot in `prim_faces`, in ascending order.
fn first_slots(prim_faces: &[u32], faces: usize) -> Vec<u32> {
    let mut seen = vec![false; faces];
    (0u32..)
        .zip(prim_faces)
        .filter(|&(_, &face)| !std::mem::replace(&mut seen[face as usize], true))
        .map(|(slot, _)| slot)
        .collect()
}

struct TreeShape {
    nodes: usize,
    leaves: usize,
    primitive_refs: usize,
    max_depth: u32,
    max_leaf_size: u32,
}

/// Walks the tree from the root (obvhs may keep unreachable nodes around).
fn tree_shape(bvh: &Bvh2) -> TreeShape {
    let mut shape = TreeShape {
        nodes: 0,
        leaves: 0,
        primitive_refs: 0,
        max_depth: 0,
        max_leaf_size: 0,
    };
    if bvh.nodes.is_empty() {
        return shape;
    }
    let mut stack = vec![(0usize, 0u32)];
    while let Some((index, depth)) = stack.pop() {
        let node = &bvh.nodes[index];
        shape.nodes += 1;
        shape.max_depth = shape.max_depth.max(depth);
        if node.is_leaf() {
            shape.leaves += 1;
            shape.primitive_refs += node.prim_count as usize;
            shape.max_leaf_size = shape.max_leaf_size.max(node.prim_count);
        } else {
            let first = node.first_index as usize;
            stack.push((first, depth + 1));
            stack.push((first + 1, depth + 1));
        }
    }
    shape
}
