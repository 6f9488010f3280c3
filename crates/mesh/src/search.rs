//! The first element of a large slice that fails a check, found in
//! parallel.
//!
//! Rayon's `position_first` keeps the search's order by consulting the
//! shared "found so far" state at every element, which costs about as much
//! as a cheap check itself (40 M point indices: 0.41 s on 2 cores). Here
//! each task scans a block of elements with a plain loop and the blocks are
//! searched in order.

use rayon::prelude::*;

/// Elements per block: large enough that the per-block bookkeeping
/// vanishes, small enough to share the work of a few million elements.
const BLOCK: usize = 1 << 14;

/// Index of the first element of `items` for which `bad` holds.
pub fn first_position<T: Sync>(items: &[T], bad: impl Fn(&T) -> bool + Sync) -> Option<usize> {
    items
        .par_chunks(BLOCK)
        .enumerate()
        .find_map_first(|(block, chunk)| chunk.iter().position(&bad).map(|i| block * BLOCK + i))
}

/// The first index in `0..n` for which `bad` holds.
pub fn first_index(n: usize, bad: impl Fn(usize) -> bool + Sync) -> Option<usize> {
    (0..n.div_ceil(BLOCK))
        .into_par_iter()
        .find_map_first(|block| {
            let start = block * BLOCK;
            (start..(start + BLOCK).min(n)).find(|&i| bad(i))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_first_as_a_serial_search() {
        for n in [0, 1, BLOCK - 1, BLOCK, BLOCK + 1, 5 * BLOCK + 17] {
            let values: Vec<usize> = (0..n).collect();
            for bad_at in [0, 1, BLOCK - 1, BLOCK, 3 * BLOCK + 5, n.saturating_sub(1)] {
                // Every multiple of 7 from `bad_at` on fails: the first is
                // the first such element, not any.
                let bad = |&v: &usize| v >= bad_at && v % 7 == 0;
                let want = values.iter().position(bad);
                assert_eq!(first_position(&values, bad), want, "n {n}, from {bad_at}");
                assert_eq!(first_index(n, |i| bad(&i)), want, "n {n}, from {bad_at}");
            }
            assert_eq!(first_position(&values, |_| false), None);
        }
    }
}
