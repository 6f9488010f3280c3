//! A plain BVH2 node array for the GPU kernel, and its CPU twin traversal.
//!
//! Layout (all little-endian `u32` / `f32`, WGSL-compatible):
//! - `nodes: array<FlatNode>`, root at 0. An inner node's children are
//!   `index` and `index + 1`; a leaf (`count > 0`) holds primitive slots
//!   `index .. index + count`.
//! - `prims: array<FlatPrim>`: per slot, the face's three point indices
//!   (outward counter-clockwise) and its boundary face index.
//! - The kernel also needs the mesh points, `scene_abs_max` (box padding
//!   scale, see the slab module) and a stack of [`FLAT_STACK_SIZE`] entries.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::build::BoundaryBvh;
use crate::slab::RaySlab;
use crate::{BvhError, EntryHit, is_better, query_is_valid};
use tetray_core::watertight::{RayFrame, cross_triangle};

/// Traversal stack entries of the GPU kernel. The stack never holds more
/// than the tree depth (one pending far child per inner node on the current
/// path), and [`BoundaryBvh::flatten`] refuses deeper trees.
pub const FLAT_STACK_SIZE: usize = 64;

/// One BVH2 node; matches WGSL `struct { min: vec3<f32>, index: u32,
/// max: vec3<f32>, count: u32 }` (32 bytes, align 16).
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct FlatNode {
    pub min: [f32; 3],
    /// First child (inner node) or first primitive slot (leaf).
    pub index: u32,
    pub max: [f32; 3],
    /// Primitives in a leaf; 0 marks an inner node.
    pub count: u32,
}

/// One primitive slot; matches WGSL `vec4<u32>` (16 bytes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
#[repr(C)]
pub struct FlatPrim {
    /// Point indices, counter-clockwise seen from outside.
    pub vertices: [u32; 3],
    /// Index into `Topology::boundary_faces`.
    pub face: u32,
}

/// The GPU-ready form of a [`BoundaryBvh`].
#[derive(Debug, Clone, PartialEq)]
pub struct FlatBvh {
    nodes: Vec<FlatNode>,
    prims: Vec<FlatPrim>,
    scene_abs_max: f32,
    max_depth: u32,
}

impl BoundaryBvh {
    /// The node and primitive arrays for the GPU kernel. Fails when the tree
    /// is deeper than the kernel's fixed stack ([`FLAT_STACK_SIZE`]).
    pub fn flatten(&self) -> Result<FlatBvh, BvhError> {
        let depth = self.stats.max_depth;
        if depth as usize > FLAT_STACK_SIZE {
            return Err(BvhError::TooDeepForGpu {
                depth,
                limit: FLAT_STACK_SIZE as u32,
            });
        }
        let nodes = self
            .bvh
            .nodes
            .iter()
            .map(|node| FlatNode {
                min: node.aabb().min.to_array(),
                index: node.first_index,
                max: node.aabb().max.to_array(),
                count: node.prim_count,
            })
            .collect();
        let prims = self
            .prim_faces
            .iter()
            .map(|&face| FlatPrim {
                vertices: self.face_vertices[face as usize],
                face,
            })
            .collect();
        Ok(FlatBvh {
            nodes,
            prims,
            scene_abs_max: self.scene_abs_max,
            max_depth: depth,
        })
    }
}

impl FlatBvh {
    pub fn nodes(&self) -> &[FlatNode] {
        &self.nodes
    }

    pub fn prims(&self) -> &[FlatPrim] {
        &self.prims
    }

    /// Largest coordinate magnitude of the boundary (the kernel's padding
    /// scale).
    pub fn scene_abs_max(&self) -> f32 {
        self.scene_abs_max
    }

    /// Depth of the tree, at most [`FLAT_STACK_SIZE`].
    pub fn max_depth(&self) -> u32 {
        self.max_depth
    }

    /// CPU twin of the GPU entry kernel: same contract as
    /// [`BoundaryBvh::first_entry`], over `points` (the mesh points the BVH
    /// was built from), written as the kernel is: fixed stack, flat indices.
    pub fn first_entry(
        &self,
        points: &[Vec3],
        ray: &RayFrame,
        t_min: f32,
        t_max: f32,
        skip: &[u32],
    ) -> Option<EntryHit> {
        if !query_is_valid(ray, t_min, t_max) || self.nodes.is_empty() {
            return None;
        }
        let slab = RaySlab::new(ray.origin, ray.dir, self.scene_abs_max);
        let hit_box = |node: &FlatNode, t_hi: f32| slab.entry(node.min, node.max, t_min, t_hi);
        let mut stack_node = [0u32; FLAT_STACK_SIZE];
        let mut stack_t = [0f32; FLAT_STACK_SIZE];
        let mut stack_len = 0usize;
        let mut best: Option<EntryHit> = None;
        let t_hi = |best: Option<EntryHit>| best.map_or(t_max, |b| b.t);

        hit_box(&self.nodes[0], t_max)?;
        let mut current = 0usize;
        loop {
            let node = self.nodes[current];
            let mut next = None;
            if node.count > 0 {
                for slot in node.index..node.index + node.count {
                    let prim = self.prims[slot as usize];
                    let [a, b, c] = prim.vertices.map(|v| points.get(v as usize));
                    let (Some(&a), Some(&b), Some(&c)) = (a, b, c) else {
                        continue;
                    };
                    let Some(x) = cross_triangle(ray.project(a), ray.project(b), ray.project(c))
                    else {
                        continue;
                    };
                    if x.entering
                        && x.t >= t_min
                        && x.t <= t_max
                        && is_better(x.t, prim.face, best)
                        && !skip.contains(&prim.face)
                    {
                        best = Some(EntryHit {
                            face: prim.face,
                            t: x.t,
                        });
                    }
                }
            } else {
                let left = node.index as usize;
                let hi = t_hi(best);
                let tl = hit_box(&self.nodes[left], hi);
                let tr = hit_box(&self.nodes[left + 1], hi);
                next = match (tl, tr) {
                    (Some(tl), Some(tr)) => {
                        let (near, far, t_far) = if tr < tl {
                            (left + 1, left, tl)
                        } else {
                            (left, left + 1, tr)
                        };
                        // In bounds: depth <= FLAT_STACK_SIZE (flatten checks).
                        stack_node[stack_len] = far as u32;
                        stack_t[stack_len] = t_far;
                        stack_len += 1;
                        Some(near)
                    }
                    (Some(_), None) => Some(left),
                    (None, Some(_)) => Some(left + 1),
                    (None, None) => None,
                };
            }
            if next.is_none() {
                while stack_len > 0 {
                    stack_len -= 1;
                    if stack_t[stack_len] <= t_hi(best) {
                        next = Some(stack_node[stack_len] as usize);
                        break;
                    }
                }
            }
            match next {
                Some(n) => current = n,
                None => return best,
            }
        }
    }
}
