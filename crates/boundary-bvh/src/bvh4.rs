//! The binary tree collapsed into a tree of up to four children per node,
//! for the CPU's entry queries.
//!
//! A query of the binary tree tests two boxes per visited node and descends
//! one level at a time; on a mesh whose boundary is too large for the
//! caches, every level is a dependent load of a node pair. Here a node
//! holds the boxes of up to four children (grandchildren of the binary
//! tree, where a child is inner) as four lanes per coordinate, tested in
//! one vector operation per axis, so a query descends half as many levels.
//! The boxes are the binary tree's own, so the padded slab test prunes the
//! same way (conservatively) and the watertight predicate still decides
//! every crossing: the answers are the binary tree's and the brute-force
//! scan's, bit for bit.

use glam::Vec4;
use obvhs::bvh2::Bvh2;

use crate::BvhError;

/// One node: the boxes of its children in lanes, and where each child is.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(crate) struct Node4 {
    /// Per axis, the children's box minima (lane `i`: child `i`).
    pub min: [Vec4; 3],
    /// Per axis, the children's box maxima.
    pub max: [Vec4; 3],
    /// An inner child's node index; a leaf child's first primitive slot.
    pub index: [u32; 4],
    /// A leaf child's primitive count; 0 for an inner child.
    pub count: [u16; 4],
    /// Bit `i` set where child `i` exists (children fill the lanes from 0).
    pub children: u32,
    _pad: u32,
}

impl Node4 {
    const EMPTY: Node4 = Node4 {
        min: [Vec4::ZERO; 3],
        max: [Vec4::ZERO; 3],
        index: [0; 4],
        count: [0; 4],
        children: 0,
        _pad: 0,
    };
}

/// The collapsed tree; node 0 is the root.
#[derive(Debug, Clone)]
pub(crate) struct Bvh4 {
    pub nodes: Vec<Node4>,
    /// Nodes on the longest root-to-leaf path, the root counted.
    pub levels: u32,
}

impl Bvh4 {
    /// Collapses `bvh` from the root down: each node takes its binary
    /// node's two children, then replaces the inner child of largest
    /// surface area by its own two children while it has fewer than four
    /// (the larger a box, the likelier a ray visits it, so its test is the
    /// one worth merging into the parent's).
    pub fn collapse(bvh: &Bvh2) -> Result<Bvh4, BvhError> {
        let nodes2 = &bvh.nodes;
        let mut nodes = vec![Node4::EMPTY];
        let mut levels = 1;
        // (binary node, wide node, its level): the binary node's children
        // (or itself, for a root that is a leaf) fill the wide node.
        let mut todo = vec![(0usize, 0usize, 1u32)];
        while let Some((node2, node4, level)) = todo.pop() {
            levels = levels.max(level);
            let parent = &nodes2[node2];
            let mut kids = if parent.is_leaf() {
                vec![node2]
            } else {
                let first = parent.first_index as usize;
                vec![first, first + 1]
            };
            while kids.len() < 4 {
                let largest = kids
                    .iter()
                    .enumerate()
                    .filter(|&(_, &kid)| !nodes2[kid].is_leaf())
                    .max_by(|a, b| {
                        let area = |k: usize| nodes2[k].aabb().half_area();
                        area(*a.1).total_cmp(&area(*b.1))
                    })
                    .map(|(slot, _)| slot);
                let Some(slot) = largest else { break };
                let first = nodes2[kids[slot]].first_index as usize;
                kids[slot] = first;
                kids.insert(slot + 1, first + 1);
            }
            let mut wide = Node4::EMPTY;
            for (lane, &kid) in kids.iter().enumerate() {
                let child = &nodes2[kid];
                let aabb = child.aabb();
                for axis in 0..3 {
                    wide.min[axis][lane] = aabb.min[axis];
                    wide.max[axis][lane] = aabb.max[axis];
                }
                if child.is_leaf() {
                    wide.index[lane] = child.first_index;
                    wide.count[lane] =
                        u16::try_from(child.prim_count).map_err(|_| BvhError::LeafTooLarge {
                            prims: child.prim_count,
                        })?;
                } else {
                    let next = nodes.len();
                    // Fewer wide nodes than binary ones, whose indices are
                    // u32.
                    wide.index[lane] = next as u32;
                    nodes.push(Node4::EMPTY);
                    todo.push((kid, next, level + 1));
                }
                wide.children |= 1 << lane;
            }
            nodes[node4] = wide;
        }
        Ok(Bvh4 { nodes, levels })
    }

    /// The most entries a near-first traversal keeps pending: each level
    /// it passes pushes the hit children it does not descend into, at
    /// most three.
    pub fn stack_bound(&self) -> usize {
        3 * self.levels as usize + 1
    }

    /// Bytes of the nodes.
    pub fn bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node4>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BuildPreset;
    use glam::Vec3A;
    use obvhs::bvh2::builder::build_bvh2_from_tris;
    use obvhs::triangle::Triangle;
    use std::time::Duration;

    /// A strip of `count` small triangles along x.
    fn strip(count: usize) -> Bvh2 {
        let tris: Vec<Triangle> = (0..count)
            .map(|i| {
                let x = i as f32;
                let y = (i % 7) as f32 * 0.3;
                Triangle {
                    v0: Vec3A::new(x, y, 0.0),
                    v1: Vec3A::new(x + 0.5, y, 0.1),
                    v2: Vec3A::new(x, y + 0.5, 0.2),
                }
            })
            .collect();
        let mut time = Duration::ZERO;
        build_bvh2_from_tris(&tris, BuildPreset::Medium.params(), &mut time)
    }

    /// Every primitive slot of the binary tree's leaves is in exactly one
    /// leaf child of the wide tree, every wide node is reached once, and
    /// each child's box is a box of the binary tree.
    #[test]
    fn the_wide_tree_holds_every_slot_once() {
        for count in [1, 2, 3, 5, 64, 1000] {
            let bvh = strip(count);
            let wide = Bvh4::collapse(&bvh).unwrap();
            let boxes: Vec<_> = bvh.nodes.iter().map(|n| *n.aabb()).collect();
            let mut slots = vec![0u32; bvh.primitive_indices.len()];
            let mut reached = vec![0u32; wide.nodes.len()];
            let mut stack = vec![(0usize, 1u32)];
            let mut deepest = 0;
            while let Some((index, level)) = stack.pop() {
                reached[index] += 1;
                deepest = deepest.max(level);
                let node = &wide.nodes[index];
                let children = node.children.count_ones() as usize;
                assert_eq!(node.children, (1 << children) - 1, "{count}: lanes from 0");
                assert!((1..=4).contains(&children));
                if count >= 4 && index == 0 {
                    assert_eq!(children, 4, "{count}: the root is full");
                }
                for lane in 0..children {
                    let corner = |c: &[Vec4; 3]| Vec3A::new(c[0][lane], c[1][lane], c[2][lane]);
                    let (min, max) = (corner(&node.min), corner(&node.max));
                    assert!(boxes.iter().any(|b| b.min == min && b.max == max));
                    let first = node.index[lane] as usize;
                    match node.count[lane] {
                        0 => stack.push((first, level + 1)),
                        prims => slots[first..first + prims as usize]
                            .iter_mut()
                            .for_each(|s| *s += 1),
                    }
                }
            }
            assert!(slots.iter().all(|&s| s == 1), "{count}: {slots:?}");
            assert!(reached.iter().all(|&r| r == 1), "{count}: nodes reached");
            assert_eq!(deepest, wide.levels, "{count}");
        }
    }
}
