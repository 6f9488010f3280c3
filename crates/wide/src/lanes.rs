//! Comparisons of four lanes at once, each answered as a bit mask (bit `i`
//! for lane `i`): the CPU walk's sign tests, one compare and one mask move
//! where scalar code takes a compare, a flag move and a shift per lane.
//! SSE2 is part of the x86-64 baseline; elsewhere the same masks come from
//! scalar compares.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::{
    __m128d, _mm_castsi128_ps, _mm_cmpeq_epi32, _mm_cmpeq_pd, _mm_cmpgt_pd, _mm_movemask_pd,
    _mm_movemask_ps, _mm_set_pd, _mm_set1_epi32, _mm_setr_epi32, _mm_setzero_pd,
};

/// Bit `i` set where `v[i] > 0` (false for a NaN and for either zero).
#[inline(always)]
pub fn positive_mask(v: [f64; 4]) -> u32 {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE2 is part of every x86-64 CPU (the target's baseline);
    // the compare reads and writes registers only.
    return against_zero(v, |lanes, zero| unsafe { _mm_cmpgt_pd(lanes, zero) });
    #[cfg(not(target_arch = "x86_64"))]
    scalar_mask(v, |x| x > 0.0)
}

/// Bit `i` set where `v[i] == 0` (either zero).
#[inline(always)]
pub fn zero_mask(v: [f64; 4]) -> u32 {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: as in `positive_mask`.
    return against_zero(v, |lanes, zero| unsafe { _mm_cmpeq_pd(lanes, zero) });
    #[cfg(not(target_arch = "x86_64"))]
    scalar_mask(v, |x| x == 0.0)
}

/// Bit `i` set where `v[i] == x`.
#[inline(always)]
pub fn equal_mask(v: [u32; 4], x: u32) -> u32 {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: as in `positive_mask`; the `as i32` casts keep the bits.
        unsafe {
            let lanes = _mm_setr_epi32(v[0] as i32, v[1] as i32, v[2] as i32, v[3] as i32);
            let equal = _mm_cmpeq_epi32(lanes, _mm_set1_epi32(x as i32));
            _mm_movemask_ps(_mm_castsi128_ps(equal)) as u32
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    (0..4).fold(0, |mask, i| mask | u32::from(v[i] == x) << i)
}

/// The mask of `compare(lanes, 0)` over the four lanes of `v`, two at a
/// time (`compare`: an SSE2 compare, all ones in a lane where it holds).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn against_zero(v: [f64; 4], compare: impl Fn(__m128d, __m128d) -> __m128d) -> u32 {
    // SAFETY: as in `positive_mask`.
    unsafe {
        let zero = _mm_setzero_pd();
        let (lo, hi) = (_mm_set_pd(v[1], v[0]), _mm_set_pd(v[3], v[2]));
        (_mm_movemask_pd(compare(lo, zero)) | _mm_movemask_pd(compare(hi, zero)) << 2) as u32
    }
}

#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn scalar_mask(v: [f64; 4], test: impl Fn(f64) -> bool) -> u32 {
    (0..4).fold(0, |mask, i| mask | u32::from(test(v[i])) << i)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPECIAL: [f64; 8] = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        f64::MIN_POSITIVE,
        -f64::MIN_POSITIVE * 0.5,
        f64::NAN,
        f64::INFINITY,
    ];

    /// Every combination of special values in every lane gives the masks
    /// of the scalar comparisons, in both builds.
    #[test]
    fn masks_match_scalar_comparisons() {
        for wide in [false, true] {
            for code in 0..SPECIAL.len().pow(4) {
                let v: [f64; 4] = std::array::from_fn(|i| SPECIAL[code / 8usize.pow(i as u32) % 8]);
                let (positive, zero) = crate::run(wide, || (positive_mask(v), zero_mask(v)));
                for (i, &x) in v.iter().enumerate() {
                    assert_eq!(positive >> i & 1 == 1, x > 0.0, "{v:?}");
                    assert_eq!(zero >> i & 1 == 1, x == 0.0, "{v:?}");
                }
                assert!(positive < 16 && zero < 16);
            }
        }
    }

    #[test]
    fn equal_mask_finds_each_lane() {
        let v = [7, u32::MAX, 11, 7];
        assert_eq!(equal_mask(v, 7), 0b1001);
        assert_eq!(equal_mask(v, u32::MAX), 0b0010);
        assert_eq!(equal_mask(v, 11), 0b0100);
        assert_eq!(equal_mask(v, 3), 0);
        assert_eq!(crate::run(true, || equal_mask(v, 7)), 0b1001);
    }
}
