//! From a structured grid to tetrahedra: the diagonal parity, blanked
//! hexahedra, flat and inverted tetrahedra. The counts come from a pass that
//! holds no tetrahedra, so the size of a grid's mesh is known exactly
//! before (or without) building it.

use glam::Vec3;
use rayon::prelude::*;

use super::grid::Plot3dSource;
use tetray_mesh::structured::{Templates, hex_count, hex_tets, templates};
use tetray_mesh::tet_shape;

/// What splitting a grid into tetrahedra gives, without the tetrahedra.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SplitCounts {
    /// The face diagonals join points with `(i + j + k) % 2 ==
    /// diagonal_parity` (see [`tetray_mesh::structured::structured_tets`]).
    pub diagonal_parity: usize,
    /// Hexahedra of the grid (before blanking).
    pub hexahedra: usize,
    /// Hexahedra left out because a corner has IBLANK 0.
    pub blanked_hexahedra: usize,
    /// Flat tetrahedra (collapsed hexahedra), dropped.
    pub degenerate_dropped: usize,
    /// Those of them with four distinct corners: too thin for f32 rather
    /// than collapsed. Dropping one can leave a point on another's face (a
    /// hanging node), which validation rejects.
    pub thin: usize,
    /// Inverted tetrahedra (a left-handed grid, a folded cell), reoriented.
    pub reoriented: usize,
    /// Tetrahedra of the mesh: 5 per kept hexahedron less the flat ones.
    pub tets: usize,
}

/// The counts of splitting `source` as the reader does. Its points are
/// computed once into memory (12 bytes each, about 2.4 per tetrahedron),
/// not once per hexahedron using them.
pub fn plot3d_split_counts(source: &impl Plot3dSource) -> SplitCounts {
    let n = source.point_count();
    let points: Vec<Vec3> = (0..n).into_par_iter().map(|p| source.point(p)).collect();
    let point = |p: usize| points[p];
    if source.has_iblank() {
        let blanked: Vec<bool> = (0..n)
            .into_par_iter()
            .map(|p| source.iblank(p) == 0)
            .collect();
        choose(source.dims(), &point, Some(&|p: usize| blanked[p]))
    } else {
        choose(source.dims(), &point, None)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shape {
    Positive,
    Inverted,
    Flat,
}

/// Whether two corners of a tetrahedron coincide.
fn collapsed(p: [Vec3; 4]) -> bool {
    (0..4).any(|a| (a + 1..4).any(|b| p[a] == p[b]))
}

fn shape(p: [Vec3; 4]) -> Shape {
    let shape = tet_shape(p);
    if shape.is_degenerate() {
        Shape::Flat
    } else if shape.volume6 < 0.0 {
        Shape::Inverted
    } else {
        Shape::Positive
    }
}

type PointFn<'a> = &'a (dyn Fn(usize) -> Vec3 + Sync);
type BlankFn<'a> = Option<&'a (dyn Fn(usize) -> bool + Sync)>;

/// Whether hexahedron tetrahedra `tets` have a blanked corner (the 5
/// tetrahedra of a hexahedron use all 8 corners).
fn is_blanked(tets: &[[u32; 4]; 5], blanked: BlankFn<'_>) -> bool {
    blanked.is_some_and(|b| tets.iter().flatten().any(|&p| b(p as usize)))
}

/// What one parity's split gives.
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    blanked: usize,
    inverted: usize,
    flat: usize,
    thin: usize,
}

impl std::ops::Add for Tally {
    type Output = Tally;
    fn add(self, o: Tally) -> Tally {
        Tally {
            blanked: self.blanked + o.blanked,
            inverted: self.inverted + o.inverted,
            flat: self.flat + o.flat,
            thin: self.thin + o.thin,
        }
    }
}

fn count(
    t: &Templates,
    dims: [usize; 3],
    parity: usize,
    point: PointFn<'_>,
    blanked: BlankFn<'_>,
) -> Tally {
    (0..hex_count(dims))
        .into_par_iter()
        .map(|h| {
            let tets = hex_tets(t, dims, h, parity);
            let mut tally = Tally::default();
            if is_blanked(&tets, blanked) {
                tally.blanked = 1;
                return tally;
            }
            for tet in tets {
                let p = tet.map(|p| point(p as usize));
                match shape(p) {
                    Shape::Positive => {}
                    Shape::Inverted => tally.inverted += 1,
                    Shape::Flat => {
                        tally.flat += 1;
                        tally.thin += usize::from(!collapsed(p));
                    }
                }
            }
            tally
        })
        .reduce(Tally::default, |a, b| a + b)
}

/// Counts both conforming splits and keeps the one with the fewest
/// inverted tetrahedra, then the fewest flat ones (parity 0 on a tie). A
/// hexahedron with a concave corner can give an inverted corner
/// tetrahedron with one diagonal choice and none with the other (the
/// Combustor has two such cells); since both choices are conforming the
/// better one costs nothing.
fn choose(dims: [usize; 3], point: PointFn<'_>, blanked: BlankFn<'_>) -> SplitCounts {
    let t = templates();
    let counts = |parity: usize| {
        let tally = count(&t, dims, parity, point, blanked);
        let hexahedra = hex_count(dims);
        SplitCounts {
            diagonal_parity: parity,
            hexahedra,
            blanked_hexahedra: tally.blanked,
            degenerate_dropped: tally.flat,
            thin: tally.thin,
            reoriented: tally.inverted,
            tets: 5 * (hexahedra - tally.blanked) - tally.flat,
        }
    };
    let score = |c: &SplitCounts| (c.reoriented, c.degenerate_dropped);
    let first = counts(0);
    // A perfect first split cannot be beaten: skip the second.
    if score(&first) == (0, 0) {
        return first;
    }
    let second = counts(1);
    if score(&second) < score(&first) {
        second
    } else {
        first
    }
}

/// The tetrahedra of a grid, and what was done to get them.
pub(crate) struct Split {
    pub tets: Vec<[u32; 4]>,
    pub counts: SplitCounts,
}

/// Splits the grid with the parity [`choose`] picks, in one pass.
///
/// Flat tetrahedra are dropped. A hexahedron collapsed to a prism (grid
/// lines merging at a wall or an axis, duplicated points) splits into some
/// tetrahedra of zero volume: they hold no volume, so the rendering
/// integral does not change without them, while their faces are slivers a
/// ray cannot walk through reliably. Removing whole tetrahedra keeps the
/// boundary closed; it only exposes faces lying on faces of the remaining
/// tetrahedra, which the walk crosses by leaving and re-entering the mesh.
/// Inverted tetrahedra left over (a folded grid) are reoriented here, and
/// validation then rejects the overlap they make. The 5 tetrahedra of every
/// hexahedron with a blanked corner (IBLANK 0: no valid data there) are
/// left out.
pub(crate) fn split_grid(dims: [usize; 3], points: &[Vec3], iblank: Option<&[i32]>) -> Split {
    let point = |p: usize| points[p];
    let blanked_at = |p: usize| iblank.is_some_and(|b| b[p] == 0);
    let blanked: BlankFn<'_> = iblank.map(|_| &blanked_at as &(dyn Fn(usize) -> bool + Sync));
    let counts = choose(dims, &point, blanked);
    let t = templates();
    let tets: Vec<[u32; 4]> = (0..hex_count(dims))
        .into_par_iter()
        .flat_map_iter(|h| {
            let tets = hex_tets(&t, dims, h, counts.diagonal_parity);
            let keep = !is_blanked(&tets, blanked);
            tets.into_iter().filter(move |_| keep).filter_map(|tet| {
                match shape(tet.map(|p| points[p as usize])) {
                    Shape::Flat => None,
                    Shape::Inverted => Some([tet[0], tet[1], tet[3], tet[2]]),
                    Shape::Positive => Some(tet),
                }
            })
        })
        .collect();
    debug_assert_eq!(tets.len(), counts.tets);
    Split { tets, counts }
}
