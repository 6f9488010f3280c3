//! `first_entry`: nearest-first traversal of the wide tree
//! ([`crate::bvh4`]) collapsed from the obvhs BVH2.

use glam::Vec3;

use crate::build::BoundaryBvh;
use crate::slab::RaySlab;
use crate::{EntryHit, is_better, query_is_valid};
use tetray_core::watertight::{RayFrame, entry_distance};

/// Inline stack capacity. Traversal descends into the nearest hit child
/// and pushes the others, so at most three entries per node of the current
/// root-to-node path are pending ([`crate::bvh4::Bvh4::stack_bound`]).
/// PLOC trees over mesh boundaries are ~2-3 log2(faces) binary levels deep,
/// half as many wide ones (about 20 for the 50k faces of the Oxygen Post);
/// deeper trees use a heap stack.
const INLINE_STACK: usize = 64;

/// A subtree not yet visited: a wide node (`count` 0) or a leaf's
/// primitive slots, with the distance at which the ray enters its box.
#[derive(Clone, Copy)]
struct Pending {
    index: u32,
    count: u32,
    t_enter: f32,
}

impl Pending {
    /// A placeholder that fills the fixed arrays.
    const NONE: Pending = Pending {
        index: 0,
        count: 0,
        t_enter: 0.0,
    };
}

/// Pending subtrees, nearest on top.
trait NodeStack {
    fn push(&mut self, pending: Pending);
    fn pop(&mut self) -> Option<Pending>;
}

struct ArrayStack {
    items: [Pending; INLINE_STACK],
    len: usize,
}

impl NodeStack for ArrayStack {
    #[inline(always)]
    fn push(&mut self, pending: Pending) {
        // Cannot overflow: only used when the stack bound is <= INLINE_STACK.
        self.items[self.len] = pending;
        self.len += 1;
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<Pending> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }
}

impl NodeStack for Vec<Pending> {
    #[inline(always)]
    fn push(&mut self, pending: Pending) {
        Vec::push(self, pending);
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<Pending> {
        Vec::pop(self)
    }
}

/// The query interval narrowed by the best hit so far.
struct Search<'a> {
    ray: &'a RayFrame,
    t_min: f32,
    t_max: f32,
    skip: &'a [u32],
    best: Option<EntryHit>,
}

impl Search<'_> {
    /// Farthest distance a better hit can have (ties in t still count: a
    /// lower face index at the same distance wins).
    #[inline]
    fn t_hi(&self) -> f32 {
        self.best.map_or(self.t_max, |b| b.t)
    }

    /// Tests one face with the shared predicate and keeps it if it is better.
    #[inline(always)]
    fn consider(&mut self, face: u32, [a, b, c]: [Vec3; 3]) {
        let ray = self.ray;
        let Some(t) = entry_distance(ray.project(a), ray.project(b), ray.project(c)) else {
            return;
        };
        if t >= self.t_min
            && t <= self.t_max
            && is_better(t, face, self.best)
            && !self.skip.contains(&face)
        {
            self.best = Some(EntryHit { face, t });
        }
    }
}

impl BoundaryBvh {
    /// The nearest boundary face that the ray crosses from outside to inside
    /// with `t_min <= t <= t_max`, ignoring the faces in `skip`; ties in `t`
    /// go to the lowest face index. Same result, bit for bit, as
    /// [`crate::brute_force_first_entry`].
    ///
    /// Inlined whole into its caller, so that a walk compiled for wider
    /// instruction sets (`tetray-wide`) runs its queries in that set too.
    #[inline(always)]
    pub fn first_entry(
        &self,
        ray: &RayFrame,
        t_min: f32,
        t_max: f32,
        skip: &[u32],
    ) -> Option<EntryHit> {
        if !query_is_valid(ray, t_min, t_max) {
            return None;
        }
        let mut search = Search {
            ray,
            t_min,
            t_max,
            skip,
            best: None,
        };
        let bound = self.bvh4.stack_bound();
        if bound <= INLINE_STACK {
            let mut stack = ArrayStack {
                items: [Pending::NONE; INLINE_STACK],
                len: 0,
            };
            self.walk(&mut search, &mut stack);
        } else {
            let mut stack = Vec::with_capacity(bound);
            self.walk(&mut search, &mut stack);
        }
        search.best
    }

    /// Near-first through the wide tree: of a node's hit children, ordered
    /// by the distance at which the ray enters their boxes, the nearest is
    /// visited next and the others are pushed, farthest first; a pending
    /// subtree entered beyond the best hit so far is dropped.
    #[inline(always)]
    fn walk(&self, search: &mut Search<'_>, stack: &mut impl NodeStack) {
        let nodes = &self.bvh4.nodes;
        let slab = RaySlab::new(search.ray.origin, search.ray.dir, self.scene_abs_max);
        let mut current = 0u32;
        loop {
            let node = &nodes[current as usize];
            let (mask, near) = slab.entry_four(&node.min, &node.max, search.t_min, search.t_hi());
            let child = |lane: usize| Pending {
                index: node.index[lane],
                count: u32::from(node.count[lane]),
                t_enter: near[lane],
            };
            let mut bits = mask & node.children;
            let nearest = if bits & bits.wrapping_sub(1) == 0 {
                // One child hit (or none): no order to find.
                (bits != 0).then(|| child(bits.trailing_zeros() as usize))
            } else {
                let mut hits = [Pending::NONE; 4];
                let mut len = 0;
                while bits != 0 {
                    let hit = child(bits.trailing_zeros() as usize);
                    bits &= bits - 1;
                    // Insertion into the hits so far, farthest first.
                    let mut at = len;
                    while at > 0 && hits[at - 1].t_enter < hit.t_enter {
                        hits[at] = hits[at - 1];
                        at -= 1;
                    }
                    hits[at] = hit;
                    len += 1;
                }
                for &hit in &hits[..len - 1] {
                    stack.push(hit);
                }
                Some(hits[len - 1])
            };
            // The nearest child next: an inner node is descended into, a
            // leaf's faces are tested at once.
            if let Some(hit) = nearest {
                if hit.count == 0 {
                    current = hit.index;
                    continue;
                }
                self.test_leaf(search, hit);
            }
            current = loop {
                let Some(pending) = stack.pop() else {
                    return;
                };
                // Inclusive: a subtree entered exactly at the best
                // distance may still hold a lower face index.
                if pending.t_enter > search.t_hi() {
                    continue;
                }
                if pending.count == 0 {
                    break pending.index;
                }
                self.test_leaf(search, pending);
            };
        }
    }

    /// Tests the faces of a leaf.
    #[inline(always)]
    fn test_leaf(&self, search: &mut Search<'_>, leaf: Pending) {
        let first = leaf.index as usize;
        for slot in first..first + leaf.count as usize {
            search.consider(self.prim_faces[slot], self.prim_tris[slot]);
        }
    }
}
