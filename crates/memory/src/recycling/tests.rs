//! Each test has its own [`Recycling`], so the kept blocks it checks are
//! its own.

use super::*;

const MIB: usize = 1 << 20;

fn layout(size: usize) -> Layout {
    Layout::from_size_align(size, 8).unwrap()
}

/// Fills `size` bytes at `ptr` with a pattern of `seed`.
fn fill(ptr: *mut u8, size: usize, seed: u8) {
    // SAFETY: the tests pass live blocks of at least `size` bytes.
    let bytes = unsafe { std::slice::from_raw_parts_mut(ptr, size) };
    for (i, b) in bytes.iter_mut().enumerate() {
        *b = (i as u8).wrapping_mul(31).wrapping_add(seed);
    }
}

/// Whether `size` bytes at `ptr` hold the pattern of `seed`.
fn holds(ptr: *const u8, size: usize, seed: u8) -> bool {
    // SAFETY: as in `fill`.
    let bytes = unsafe { std::slice::from_raw_parts(ptr, size) };
    bytes
        .iter()
        .enumerate()
        .all(|(i, &b)| b == (i as u8).wrapping_mul(31).wrapping_add(seed))
}

fn all_zero(ptr: *const u8, size: usize) -> bool {
    // SAFETY: as in `fill`.
    unsafe { std::slice::from_raw_parts(ptr, size) }
        .iter()
        .all(|&b| b == 0)
}

#[test]
fn a_freed_large_block_serves_the_next_and_zeroed_means_zeroed() {
    let a = Recycling::new();
    let size = 20 * MIB + 123;
    // SAFETY: layouts of non-zero size; every block is freed once, with the
    // layout it was allocated with (so in every test below).
    unsafe {
        let p = a.alloc(layout(size));
        assert!(!p.is_null());
        fill(p, size, 7);
        a.dealloc(p, layout(size));
        assert_eq!(a.kept_bytes(), page_round(size));
        let q = a.alloc_zeroed(layout(size));
        assert_eq!(q, p, "the kept block is reused");
        assert_eq!(a.kept_bytes(), 0);
        assert!(
            all_zero(q, size),
            "a recycled block is cleared for alloc_zeroed"
        );
        a.dealloc(q, layout(size));
    }
    a.release();
    assert_eq!(a.kept_bytes(), 0);
}

#[test]
fn the_smallest_block_that_fits_is_chosen_and_its_surplus_kept() {
    let a = Recycling::new();
    // SAFETY: as above.
    unsafe {
        let big = a.alloc(layout(64 * MIB));
        let small = a.alloc(layout(32 * MIB));
        a.dealloc(big, layout(64 * MIB));
        a.dealloc(small, layout(32 * MIB));
        let p = a.alloc(layout(20 * MIB));
        assert_eq!(p, small);
        // The 12 MiB surplus is kept apart.
        assert_eq!(a.kept_bytes(), 76 * MIB);
        // A request larger than every kept block takes their pages.
        let q = a.alloc_zeroed(layout(80 * MIB));
        assert!(!q.is_null());
        assert_eq!(a.kept_bytes(), 0);
        assert!(all_zero(q, 80 * MIB));
        fill(q, 80 * MIB, 3);
        assert!(holds(q, 80 * MIB, 3));
        a.dealloc(p, layout(20 * MIB));
        a.dealloc(q, layout(80 * MIB));
    }
    a.release();
}

#[test]
fn a_request_larger_than_any_kept_block_takes_the_pages_of_several() {
    let a = Recycling::new();
    // SAFETY: as above.
    unsafe {
        let x = a.alloc(layout(20 * MIB));
        let y = a.alloc(layout(30 * MIB));
        fill(x, 20 * MIB, 1);
        fill(y, 30 * MIB, 2);
        a.dealloc(x, layout(20 * MIB));
        a.dealloc(y, layout(30 * MIB));
        let p = a.alloc_zeroed(layout(45 * MIB));
        assert!(!p.is_null());
        assert!(
            all_zero(p, 45 * MIB),
            "moved pages are cleared for alloc_zeroed"
        );
        // 30 MiB moved whole, 15 of the 20 MiB block; its last 5 are kept.
        assert_eq!(a.kept_bytes(), 5 * MIB);
        fill(p, 45 * MIB, 9);
        let q = a.alloc(layout(60 * MIB));
        assert_eq!(a.kept_bytes(), 0);
        fill(q, 60 * MIB, 4);
        assert!(holds(p, 45 * MIB, 9), "the first block is untouched");
        assert!(holds(q, 60 * MIB, 4));
        a.dealloc(p, layout(45 * MIB));
        a.dealloc(q, layout(60 * MIB));
    }
    a.release();
}

#[test]
fn realloc_keeps_the_contents_across_every_size_class() {
    let a = Recycling::new();
    // SAFETY: as above; each realloc's result replaces the old pointer.
    unsafe {
        // Small to large, large to larger, larger to smaller, large to small.
        let mut size = MIB;
        let mut p = a.alloc(layout(size));
        fill(p, size, 11);
        for next in [24 * MIB, 100 * MIB + 5, 17 * MIB, 3 * MIB] {
            p = a.realloc(p, layout(size), next);
            assert!(!p.is_null());
            assert!(holds(p, size.min(next), 11), "{size} -> {next}");
            size = next;
            fill(p, size, 11);
        }
        a.dealloc(p, layout(size));
    }
    a.release();
}

#[test]
fn realloc_copies_between_the_systems_blocks_and_mapped_ones() {
    let a = Recycling::new();
    // SAFETY: as above; each realloc's result replaces the old pointer.
    unsafe {
        // Small (System's) to large (mapped here): a copy.
        let mut size = 1000;
        let mut p = a.alloc(layout(size));
        fill(p, size, 21);
        for next in [LARGE + 7, 5000, LARGE - 1, 2 * LARGE] {
            p = a.realloc(p, layout(size), next);
            assert!(!p.is_null());
            assert!(holds(p, size.min(next), 21), "{size} -> {next}");
            size = next;
            fill(p, size, 21);
        }
        // Large back to small frees the mapped block into the cache.
        p = a.realloc(p, layout(size), 64);
        assert!(holds(p, 64, 21));
        assert!(a.kept_bytes() >= page_round(2 * LARGE));
        a.dealloc(p, layout(64));
    }
    a.release();
}

#[test]
fn a_block_assembled_from_several_mappings_reallocates() {
    let a = Recycling::new();
    let parts = [9 * MIB, 7 * MIB, 5 * MIB];
    let size = 21 * MIB;
    for next in [40 * MIB + 3, 12 * MIB, 30 * MIB, 100] {
        a.release();
        // SAFETY: as above; `p` is replaced by realloc's result.
        unsafe {
            // Three kept blocks moved into one fresh mapping: a block the
            // kernel may hold as several mappings, which mremap refuses to
            // resize (realloc then copies).
            let blocks: Vec<*mut u8> = parts.iter().map(|&s| a.alloc(layout(s))).collect();
            for (&p, &s) in blocks.iter().zip(&parts) {
                a.dealloc(p, layout(s));
            }
            let p = a.alloc(layout(size));
            assert_eq!(a.kept_bytes(), 0, "every kept page moved into the block");
            fill(p, size, 33);
            let q = a.realloc(p, layout(size), next);
            assert!(!q.is_null());
            assert!(holds(q, size.min(next), 33), "{size} -> {next}");
            fill(q, next, 34);
            assert!(holds(q, next, 34));
            a.dealloc(q, layout(next));
        }
    }
    a.release();
}

#[test]
fn at_most_slots_blocks_are_kept_and_the_smallest_go_first() {
    let a = Recycling::new();
    let sizes: Vec<usize> = (0..SLOTS + 2).map(|i| (17 + i) * MIB).collect();
    // SAFETY: as above.
    unsafe {
        let blocks: Vec<*mut u8> = sizes.iter().map(|&s| a.alloc(layout(s))).collect();
        for (&p, &s) in blocks.iter().zip(&sizes) {
            a.dealloc(p, layout(s));
        }
    }
    let kept: usize = sizes[2..].iter().sum();
    assert_eq!(a.kept_bytes(), kept);
    a.release();
    assert_eq!(a.kept_bytes(), 0);
}

#[test]
fn small_and_overaligned_allocations_are_the_systems() {
    let a = Recycling::new();
    let over = Layout::from_size_align(LARGE, 2 * page_size()).unwrap();
    // SAFETY: as above.
    unsafe {
        let p = a.alloc(layout(LARGE - 1));
        let q = a.alloc(over);
        assert_eq!(q as usize % over.align(), 0);
        a.dealloc(p, layout(LARGE - 1));
        a.dealloc(q, over);
    }
    assert_eq!(a.kept_bytes(), 0, "neither is kept");
}
