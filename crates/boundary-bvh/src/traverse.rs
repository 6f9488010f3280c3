//! `first_entry`: nearest-first traversal of the obvhs BVH2 nodes.

use glam::Vec3;

use crate::build::BoundaryBvh;
use crate::slab::RaySlab;
use crate::{EntryHit, is_better, query_is_valid};
use tetray_core::watertight::{RayFrame, entry_distance};

/// Inline stack capacity. Traversal descends into the nearer child and
/// pushes the farther one, so at most one entry per inner node of the current
/// root-to-node path is pending: the stack never holds more than the tree
/// depth. PLOC trees over mesh boundaries are ~2-3 log2(faces) deep (about 40
/// for the 50k faces of the Oxygen Post); deeper trees use a heap stack.
const INLINE_STACK: usize = 64;

/// Pending subtrees with the distance at which the ray enters their box.
trait NodeStack {
    fn push(&mut self, node: u32, t_enter: f32);
    fn pop(&mut self) -> Option<(u32, f32)>;
}

struct ArrayStack {
    items: [(u32, f32); INLINE_STACK],
    len: usize,
}

impl NodeStack for ArrayStack {
    #[inline(always)]
    fn push(&mut self, node: u32, t_enter: f32) {
        // Cannot overflow: only used when the tree depth is <= INLINE_STACK.
        self.items[self.len] = (node, t_enter);
        self.len += 1;
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<(u32, f32)> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }
}

impl NodeStack for Vec<(u32, f32)> {
    #[inline(always)]
    fn push(&mut self, node: u32, t_enter: f32) {
        Vec::push(self, (node, t_enter));
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<(u32, f32)> {
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
        if self.stats.max_depth as usize <= INLINE_STACK {
            let mut stack = ArrayStack {
                items: [(0, 0.0); INLINE_STACK],
                len: 0,
            };
            self.walk(&mut search, &mut stack);
        } else {
            let mut stack = Vec::with_capacity(self.stats.max_depth as usize);
            self.walk(&mut search, &mut stack);
        }
        search.best
    }

    #[inline(always)]
    fn walk(&self, search: &mut Search<'_>, stack: &mut impl NodeStack) {
        let nodes = &self.bvh.nodes;
        let slab = RaySlab::new(search.ray.origin, search.ray.dir, self.scene_abs_max);
        let bounds = |index: u32| {
            let aabb = nodes[index as usize].aabb();
            (aabb.min, aabb.max)
        };
        let (root_min, root_max) = bounds(0);
        if slab
            .entry_lanes(root_min, root_max, search.t_min, search.t_hi())
            .is_none()
        {
            return;
        }
        let mut current = 0u32;
        loop {
            let node = &nodes[current as usize];
            let next = if node.is_leaf() {
                let first = node.first_index as usize;
                for slot in first..first + node.prim_count as usize {
                    search.consider(self.prim_faces[slot], self.prim_tris[slot]);
                }
                None
            } else {
                let left = node.first_index;
                let right = left + 1;
                let t_hi = search.t_hi();
                let (l_min, l_max) = bounds(left);
                let (r_min, r_max) = bounds(right);
                let hit_left = slab.entry_lanes(l_min, l_max, search.t_min, t_hi);
                let hit_right = slab.entry_lanes(r_min, r_max, search.t_min, t_hi);
                match (hit_left, hit_right) {
                    (Some(tl), Some(tr)) => {
                        let (near, far, t_far) = if tr < tl {
                            (right, left, tl)
                        } else {
                            (left, right, tr)
                        };
                        stack.push(far, t_far);
                        Some(near)
                    }
                    (Some(_), None) => Some(left),
                    (None, Some(_)) => Some(right),
                    (None, None) => None,
                }
            };
            current = match next {
                Some(child) => child,
                None => loop {
                    let Some((node, t_enter)) = stack.pop() else {
                        return;
                    };
                    // Inclusive: a subtree entered exactly at the best
                    // distance may still hold a lower face index.
                    if t_enter <= search.t_hi() {
                        break node;
                    }
                },
            };
        }
    }
}
