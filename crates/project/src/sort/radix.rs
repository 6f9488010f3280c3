//! A parallel least-significant-digit radix sort of `(key << 32) | value`
//! words by their key: four passes of 8 bits, each pass histograms chunks
//! in parallel, then every chunk scatters into its own disjoint slices of
//! the output (split off safely, bucket by bucket), so no pass needs locks
//! or unsafe writes. Stable; passes in which every key has the same digit
//! are skipped.

use rayon::prelude::*;

/// Below this many items one thread's `sort_unstable` is faster.
const SERIAL_BELOW: usize = 1 << 14;
const BUCKETS: usize = 256;

/// Sorts `items` by their high 32 bits, ascending, keeping the order of
/// equal keys.
pub fn sort_by_high_word(items: &mut Vec<u64>) {
    let n = items.len();
    if n < SERIAL_BELOW {
        items.sort_by_key(|&x| x >> 32);
        return;
    }
    let chunks = (rayon::current_num_threads() * 4).max(1);
    let chunk_len = n.div_ceil(chunks);
    let mut buffer = vec![0u64; n];
    for pass in 0..4 {
        let shift = 32 + 8 * pass;
        let digit = move |x: u64| ((x >> shift) & 0xff) as usize;
        let histograms: Vec<[usize; BUCKETS]> = items
            .par_chunks(chunk_len)
            .map(|chunk| {
                let mut h = [0usize; BUCKETS];
                for &x in chunk {
                    h[digit(x)] += 1;
                }
                h
            })
            .collect();
        let all_one_bucket =
            (0..BUCKETS).any(|b| histograms.iter().map(|h| h[b]).sum::<usize>() == n);
        if all_one_bucket {
            continue;
        }
        // Output slices bucket-major, chunk-minor: chunk c's items of
        // bucket b follow those of chunks before it, so the pass is stable.
        let mut slices: Vec<Vec<&mut [u64]>> = (0..histograms.len())
            .map(|_| Vec::with_capacity(BUCKETS))
            .collect();
        let mut rest: &mut [u64] = &mut buffer;
        for b in 0..BUCKETS {
            for (c, h) in histograms.iter().enumerate() {
                let (head, tail) = std::mem::take(&mut rest).split_at_mut(h[b]);
                slices[c].push(head);
                rest = tail;
            }
        }
        items
            .par_chunks(chunk_len)
            .zip(slices.into_par_iter())
            .for_each(|(chunk, mut outs)| {
                let mut cursor = [0usize; BUCKETS];
                for &x in chunk {
                    let b = digit(x);
                    outs[b][cursor[b]] = x;
                    cursor[b] += 1;
                }
            });
        std::mem::swap(items, &mut buffer);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_a_stable_sort() {
        for n in [0usize, 1, 5, 1000, SERIAL_BELOW + 7, 200_003] {
            let mut state = 0x1234_5678_9abc_def0u64 ^ n as u64;
            let mut items: Vec<u64> = (0..n)
                .map(|i| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    // Few distinct keys in the small cases, to test stability.
                    let key = if n < 2000 { state % 17 } else { state >> 32 };
                    (key << 32) | i as u64
                })
                .collect();
            let mut expected = items.clone();
            expected.sort_by_key(|&x| x >> 32);
            sort_by_high_word(&mut items);
            assert_eq!(items, expected, "n = {n}");
        }
    }

    #[test]
    fn skips_a_digit_every_key_shares() {
        let mut items: Vec<u64> = (0..50_000u64)
            .map(|i| ((0xAB00_0000 | (49_999 - i)) << 32) | i)
            .collect();
        sort_by_high_word(&mut items);
        assert!(items.windows(2).all(|w| w[0] >> 32 <= w[1] >> 32));
        assert_eq!(items[0] as u32, 49_999);
    }
}
