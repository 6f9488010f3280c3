//! A hint to the cache: start loading a value that will be read soon.

/// Asks the processor to bring the cache line holding `value` into all
/// cache levels, without waiting for it. The CPU walk calls it on the
/// records of the three cells a ray may enter next, at the start of the
/// step that decides which, so the record is on its way while the step
/// computes. A no-op where there is no such instruction.
#[inline(always)]
pub fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads nothing and cannot fault; `value` is a live
    // reference besides. SSE is part of the x86-64 baseline.
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>((value as *const T).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}
