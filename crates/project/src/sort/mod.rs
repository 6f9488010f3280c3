//! Visibility sorts: the order in which the tetrahedra are composited, back
//! to front.
//!
//! - [`SortKind::Centroid`]: by the depth of the centroid along the view
//!   direction (VTK's vtkCellCenterDepthSort, behind its projected
//!   tetrahedra mapper), with a parallel radix sort. Not a visibility
//!   order for large or elongated cells, convex mesh or not.
//! - [`SortKind::Mpvo`]: Williams' meshed polyhedra visibility order (1992):
//!   a topological order of the face-neighbour graph, each shared face
//!   pointing from the cell behind it to the cell in front (the side of the
//!   face the eye is on). Exact for convex, connected, acyclic meshes;
//!   across the empty space of a nonconvex mesh it knows nothing.
//! - [`SortKind::Mpvonc`]: Williams' heuristic for nonconvex meshes: the
//!   same graph, but of the cells ready to draw the farthest (centroid
//!   depth) goes first, so cells that no face relates come out roughly in
//!   depth order.

mod mpvo;
pub mod radix;

use std::fmt;
use std::str::FromStr;

use rayon::prelude::*;

use crate::scene::ProjectScene;
use crate::view::View;

/// Which visibility sort.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SortKind {
    Centroid,
    Mpvo,
    Mpvonc,
}

impl SortKind {
    pub const ALL: [SortKind; 3] = [SortKind::Centroid, SortKind::Mpvo, SortKind::Mpvonc];

    pub fn name(self) -> &'static str {
        match self {
            SortKind::Centroid => "centroid",
            SortKind::Mpvo => "mpvo",
            SortKind::Mpvonc => "mpvonc",
        }
    }
}

impl fmt::Display for SortKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown sort name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown sort {0:?}: expected one of centroid, mpvo, mpvonc")]
pub struct UnknownSort(pub String);

impl FromStr for SortKind {
    type Err = UnknownSort;
    fn from_str(text: &str) -> Result<SortKind, UnknownSort> {
        SortKind::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(text.trim()))
            .ok_or_else(|| UnknownSort(text.to_string()))
    }
}

/// Tetrahedra back to front.
#[derive(Debug, Clone, PartialEq)]
pub struct Order {
    pub tets: Vec<u32>,
    /// Times the topological sorts found no cell ready (a cycle in the
    /// visibility relation) and drew the farthest waiting one.
    pub cycle_breaks: usize,
}

/// The tetrahedra of `scene` in back-to-front order for `view`.
pub fn visibility_order(scene: &ProjectScene, view: &View, kind: SortKind) -> Order {
    match kind {
        SortKind::Centroid => Order {
            tets: depth_order(scene, view),
            cycle_breaks: 0,
        },
        SortKind::Mpvo => mpvo::order(scene, view, false),
        SortKind::Mpvonc => mpvo::order(scene, view, true),
    }
}

/// Tetrahedra by decreasing centroid depth (ties by index).
pub fn depth_order(scene: &ProjectScene, view: &View) -> Vec<u32> {
    let mut pairs: Vec<u64> = scene
        .centroids
        .par_iter()
        .enumerate()
        .map(|(i, &c)| (u64::from(far_first_key(view.depth(c))) << 32) | i as u64)
        .collect();
    radix::sort_by_high_word(&mut pairs);
    pairs.into_par_iter().map(|p| p as u32).collect()
}

/// A key that orders depths farthest first as unsigned integers.
pub fn far_first_key(depth: f32) -> u32 {
    let bits = depth.to_bits();
    let ascending = if bits >> 31 == 1 {
        !bits
    } else {
        bits | 0x8000_0000
    };
    !ascending
}
