//! [`Recycling`] as the global allocator of this test binary, as it is the
//! CLI's: rayon's worker threads allocate, grow, shrink and free vectors on
//! both sides of the large-block threshold at once, each checking that its
//! contents survive every move, while the main thread releases the kept
//! blocks now and then.

use rayon::prelude::*;
use tetray_memory::{LARGE, Recycling};

#[global_allocator]
static ALLOCATOR: Recycling = Recycling::new();

/// A value that depends on the job, the round and the index.
fn value(job: usize, round: usize, i: usize) -> u32 {
    (job as u32)
        .wrapping_mul(2_654_435_761)
        .wrapping_add((round as u32).wrapping_mul(40_503))
        .wrapping_add(i as u32)
}

/// Sizes (in u32s) around the threshold: small, just below, just above,
/// several large blocks.
fn sizes(job: usize) -> [usize; 6] {
    let large = LARGE / 4;
    [
        1000 + job,
        large - 1,
        large + 1 + job,
        3 * large + job * 17,
        large / 3,
        7 * large + job,
    ]
}

#[test]
fn threads_allocate_grow_and_free_across_the_threshold() {
    let stop = std::sync::atomic::AtomicBool::new(false);
    std::thread::scope(|scope| {
        // The main program's release, concurrent with the workers.
        scope.spawn(|| {
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                ALLOCATOR.release();
                std::thread::yield_now();
            }
        });
        let checked: usize = (0..64usize)
            .into_par_iter()
            .map(|job| {
                let mut kept: Vec<Vec<u32>> = Vec::new();
                let mut checked = 0;
                for (round, &n) in sizes(job).iter().enumerate() {
                    let mut v: Vec<u32> = (0..n).map(|i| value(job, round, i)).collect();
                    // Grow past the threshold (realloc), then shrink.
                    v.extend((n..2 * n + 5).map(|i| value(job, round, i)));
                    assert!(
                        v.iter()
                            .enumerate()
                            .all(|(i, &x)| x == value(job, round, i))
                    );
                    v.truncate(n / 2 + 1);
                    v.shrink_to_fit();
                    assert!(
                        v.iter()
                            .enumerate()
                            .all(|(i, &x)| x == value(job, round, i))
                    );
                    checked += v.len();
                    // Some blocks outlive the round, freed later.
                    if round % 2 == 0 {
                        kept.push(v);
                    }
                    let zeroed = vec![0u32; n];
                    assert!(zeroed.iter().all(|&x| x == 0), "alloc_zeroed gives zeros");
                }
                for (k, v) in kept.iter().enumerate() {
                    let round = 2 * k;
                    assert!(
                        v.iter()
                            .enumerate()
                            .all(|(i, &x)| x == value(job, round, i))
                    );
                }
                checked
            })
            .sum();
        stop.store(true, std::sync::atomic::Ordering::Relaxed);
        assert!(checked > 64 * LARGE / 4, "{checked}");
    });
    ALLOCATOR.release();
    assert_eq!(ALLOCATOR.kept_bytes(), 0);
}
