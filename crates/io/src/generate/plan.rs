//! Which refinement of a grid to write for a requested tetrahedron count:
//! the smallest near-uniform factors reaching it whose split the reader can
//! validate, with the exact counts of that split (a counting pass over the
//! refined grid, holding its points only).
//!
//! Two things can make a refinement unusable although the source is fine,
//! and the counts see both: a folded cell refined with unequal factors
//! inverts a few tetrahedra (see `folded.rs`), and cells next to a
//! collapsed edge shrink quadratically (Blunt Fin's wall: the j-k
//! cross-section of a collapsed cell is a triangle, cut `rj x rk` times)
//! until some tetrahedra are thinner than f32 can resolve. Those the reader
//! drops, and a dropped tetrahedron that is thin but not collapsed leaves a
//! point on a neighbour's face, which validation rejects. A request then
//! falls back to other factors of a similar product (at most 2:1 between
//! axes), and fails with the reasons if none of a few is clean.

use std::path::Path;

use super::refine::Refinement;
use super::{GenerateError, MAX_TETS};
use crate::plot3d::{
    Plot3dGrid, Plot3dSource, SplitCounts, plot3d_split_counts, write_plot3d_files,
};

/// Refinements counted at most for one request before giving up.
const MAX_COUNTED: usize = 8;

/// Factors for a grid's refinement, with the exact counts of its split.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RefinementPlan {
    pub factors: [usize; 3],
    /// Points along i, j, k of the refined grid.
    pub dims: [usize; 3],
    /// What the reader's split of the refined grid gives (exact).
    pub counts: SplitCounts,
}

impl RefinementPlan {
    /// The plan of given factors: counts the refined grid's split.
    ///
    /// # Errors
    /// As [`Refinement::new`], and [`GenerateError::TooLarge`] beyond
    /// [`MAX_TETS`] tetrahedra.
    pub fn for_factors(source: &Plot3dGrid, factors: [usize; 3]) -> Result<Self, GenerateError> {
        let refinement = Refinement::new(source, factors)?;
        let dims = refinement.dims();
        let hexahedra: usize = dims.iter().map(|d| d - 1).product();
        if hexahedra.saturating_mul(5) > MAX_TETS.saturating_mul(2) {
            // Far too large: do not spend a counting pass to say so.
            return Err(too_many(source, factors, 5 * hexahedra));
        }
        let counts = plot3d_split_counts(&refinement);
        if counts.tets > MAX_TETS {
            return Err(too_many(source, factors, counts.tets));
        }
        Ok(RefinementPlan {
            factors,
            dims,
            counts,
        })
    }

    /// The level-`level` doubling (factors `2^level`).
    ///
    /// # Errors
    /// As [`Refinement::levels`] and [`RefinementPlan::for_factors`].
    pub fn for_level(source: &Plot3dGrid, level: u32) -> Result<Self, GenerateError> {
        let factors = Refinement::levels(source, level)?.factors();
        RefinementPlan::for_factors(source, factors)
    }

    /// The smallest near-uniform factors (see [`near_uniform_factors`])
    /// whose refinement has at least `requested` tetrahedra and no
    /// [`RefinementPlan::defect`]; failing that, the first clean one of
    /// the factor triples at most 2:1 between axes, by product, up to 1.5
    /// times the first one's.
    ///
    /// # Errors
    /// [`GenerateError::TetCount`] for 0 or more than [`MAX_TETS`];
    /// [`GenerateError::NoCleanRefinement`] when the first
    /// 8 candidates counted all have a defect; as
    /// [`RefinementPlan::for_factors`].
    pub fn for_tets(source: &Plot3dGrid, requested: usize) -> Result<Self, GenerateError> {
        check_requested(requested)?;
        // The flat tetrahedra of collapsed cells grow more slowly than the
        // hexahedra, so the source's count times the factors' product is a
        // close lower estimate; only candidates reaching it are counted.
        let base = plot3d_split_counts(source).tets.max(1) as f64;
        let enough = |f: &[usize; 3]| base * f.iter().product::<usize>() as f64 >= requested as f64;
        let first = near_uniform_factors(source.dims)
            .find(enough)
            .unwrap_or([1; 3]);
        let mut tried = Vec::new();
        for factors in std::iter::once(first).chain(fallbacks(source.dims, first, &enough)) {
            let plan = RefinementPlan::for_factors(source, factors)?;
            if plan.counts.tets < requested {
                continue;
            }
            match plan.defect() {
                None => return Ok(plan),
                Some(why) => tried.push(format!("{factors:?}: {why}")),
            }
            if tried.len() == MAX_COUNTED {
                break;
            }
        }
        Err(GenerateError::NoCleanRefinement {
            dims: source.dims,
            requested,
            tried: tried.join("; "),
        })
    }

    /// Why the reader will reject the refined mesh, when the counts say
    /// so: some but not all tetrahedra inverted (folded cells; all: a
    /// left-handed grid, reoriented whole), or flat tetrahedra that are
    /// thin rather than collapsed.
    pub fn defect(&self) -> Option<String> {
        let c = &self.counts;
        if c.reoriented > 0 && c.reoriented < c.tets {
            return Some(format!(
                "{} tetrahedra come out inverted at folded cells, overlapping their neighbours",
                c.reoriented
            ));
        }
        if c.thin > 0 {
            return Some(format!(
                "{} tetrahedra are thinner than f32 resolves (beside collapsed cells); dropping \
                 them leaves hanging nodes",
                c.thin
            ));
        }
        None
    }

    /// Writes the refined grid (and its solution when `q` is given and the
    /// source has one) as PLOT3D files. Returns the bytes of each.
    ///
    /// # Errors
    /// As [`Refinement::new`]; [`GenerateError::Read`] naming a file that
    /// could not be written.
    pub fn write(
        &self,
        source: &Plot3dGrid,
        xyz: &Path,
        q: Option<&Path>,
    ) -> Result<(u64, Option<u64>), GenerateError> {
        let refinement = Refinement::new(source, self.factors)?;
        Ok(write_plot3d_files(&refinement, xyz, q)?)
    }
}

fn too_many(source: &Plot3dGrid, factors: [usize; 3], tets: usize) -> GenerateError {
    GenerateError::TooLarge {
        dims: source.dims,
        factors,
        what: format!("{tets} tetrahedra"),
        max: MAX_TETS,
    }
}

/// A requested count must be 1..=[`MAX_TETS`].
pub(crate) fn check_requested(requested: usize) -> Result<(), GenerateError> {
    if requested == 0 {
        return Err(GenerateError::TetCount {
            requested,
            reason: "at least 1 is needed".into(),
        });
    }
    if requested > MAX_TETS {
        return Err(GenerateError::TetCount {
            requested,
            reason: format!("at most {MAX_TETS} can be loaded (32-bit face ids)"),
        });
    }
    Ok(())
}

/// Factors in increasing product, each within 1 of the others: `(r, r, r)`,
/// then `r + 1` on one axis, then on two, then `(r + 1, r + 1, r + 1)`. The
/// axes with the fewest cells get the extra cut first (ties: i before j
/// before k), which evens out the refined grid.
pub fn near_uniform_factors(dims: [usize; 3]) -> impl Iterator<Item = [usize; 3]> {
    let mut axes = [0, 1, 2];
    axes.sort_by_key(|&a| dims[a]);
    (1usize..).flat_map(move |r| {
        (0..3).map(move |extra| {
            let mut f = [r; 3];
            for &a in &axes[..extra] {
                f[a] = r + 1;
            }
            f
        })
    })
}

/// The other factor triples worth trying after `first`: at most 2:1
/// between axes, `enough` by the estimate, product up to 1.5 times
/// `first`'s; by product, then the least anisotropic, then the
/// near-uniform axis order.
fn fallbacks(
    dims: [usize; 3],
    first: [usize; 3],
    enough: &dyn Fn(&[usize; 3]) -> bool,
) -> Vec<[usize; 3]> {
    let limit = first.iter().product::<usize>() * 3 / 2;
    let largest = first.iter().max().copied().unwrap_or(1) * 2 + 1;
    let mut out = Vec::new();
    for i in 1..=largest {
        for j in 1..=largest {
            for k in 1..=largest {
                let f = [i, j, k];
                let (lo, hi) = (i.min(j).min(k), i.max(j).max(k));
                let product = i * j * k;
                if f != first && hi <= 2 * lo && product <= limit && enough(&f) {
                    out.push(f);
                }
            }
        }
    }
    let mut axes = [0, 1, 2];
    axes.sort_by_key(|&a| dims[a]);
    // Extra cuts on the axes with the fewest cells first, as above.
    let preference = |f: &[usize; 3]| axes.map(|a| std::cmp::Reverse(f[a]));
    out.sort_by_key(|f| {
        let (lo, hi) = (f.iter().min().copied(), f.iter().max().copied());
        (
            f.iter().product::<usize>(),
            hi.zip(lo).map(|(h, l)| h * 1000 / l),
            preference(f),
        )
    });
    out
}
