//! MPVO and MPVONC (Williams 1992): a topological sort of the face-neighbour
//! graph. Each shared face orders its two cells: the one on the side of the
//! face the eye is not on is behind and is drawn first. Cells whose
//! behind-neighbours are all drawn are ready; MPVO takes them in the order
//! they became ready, MPVONC farthest centroid first. Cycles (possible in
//! perspective for non-Delaunay meshes) are broken by drawing the farthest
//! waiting cell.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

use rayon::prelude::*;
use tetray_mesh::NO_NEIGHBOR;

use super::{Order, depth_order, far_first_key};
use crate::scene::ProjectScene;
use crate::view::View;

/// Cells ready to draw.
enum Ready {
    Fifo(VecDeque<u32>),
    /// `(far-first key, tet)`, smallest key (farthest) first.
    Farthest(BinaryHeap<Reverse<(u32, u32)>>),
}

impl Ready {
    fn push(&mut self, tet: u32, key: u32) {
        match self {
            Ready::Fifo(queue) => queue.push_back(tet),
            Ready::Farthest(heap) => heap.push(Reverse((key, tet))),
        }
    }

    fn pop(&mut self) -> Option<u32> {
        match self {
            Ready::Fifo(queue) => queue.pop_front(),
            Ready::Farthest(heap) => heap.pop().map(|Reverse((_, tet))| tet),
        }
    }
}

pub fn order(scene: &ProjectScene, view: &View, nonconvex: bool) -> Order {
    let n = scene.tet_count();
    // Per cell: faces whose neighbour is behind it (bits 0-3) and in front
    // of it (bits 4-7).
    let masks: Vec<u8> = scene
        .planes
        .par_iter()
        .zip(&scene.neighbors)
        .map(|(planes, neighbors)| {
            let mut mask = 0u8;
            for j in 0..4 {
                if neighbors[j] == NO_NEIGHBOR {
                    continue;
                }
                let side = view.eye_side(&planes[j]);
                if side < 0.0 {
                    mask |= 1 << j;
                } else if side > 0.0 {
                    mask |= 0x10 << j;
                }
            }
            mask
        })
        .collect();
    let mut waiting: Vec<u8> = masks.iter().map(|m| (m & 0xf).count_ones() as u8).collect();
    let keys: Vec<u32> = if nonconvex {
        scene
            .centroids
            .par_iter()
            .map(|&c| far_first_key(view.depth(c)))
            .collect()
    } else {
        Vec::new()
    };
    let key = |t: u32| keys.get(t as usize).copied().unwrap_or(0);
    let mut ready = if nonconvex {
        Ready::Farthest(BinaryHeap::with_capacity(n / 8))
    } else {
        Ready::Fifo(VecDeque::with_capacity(n / 8))
    };
    for (t, &w) in waiting.iter().enumerate() {
        if w == 0 {
            ready.push(t as u32, key(t as u32));
        }
    }
    let mut drawn = vec![false; n];
    let mut tets = Vec::with_capacity(n);
    let mut cycle_breaks = 0;
    // Farthest-first order of all cells, built only if a cycle needs it.
    let mut fallback: Option<(Vec<u32>, usize)> = None;
    while tets.len() < n {
        let Some(t) = ready.pop() else {
            let (by_depth, cursor) = fallback.get_or_insert_with(|| (depth_order(scene, view), 0));
            while drawn[by_depth[*cursor] as usize] {
                *cursor += 1;
            }
            let t = by_depth[*cursor];
            waiting[t as usize] = 0;
            ready.push(t, key(t));
            cycle_breaks += 1;
            continue;
        };
        if drawn[t as usize] {
            continue;
        }
        drawn[t as usize] = true;
        tets.push(t);
        let front = masks[t as usize] >> 4;
        for j in 0..4 {
            if front & (1 << j) == 0 {
                continue;
            }
            let next = scene.neighbors[t as usize][j];
            if drawn[next as usize] {
                continue;
            }
            let w = &mut waiting[next as usize];
            *w = w.saturating_sub(1);
            if *w == 0 {
                ready.push(next, key(next));
            }
        }
    }
    Order { tets, cycle_breaks }
}
