//! Comparisons of four lanes at once, each answered as a bit mask (bit `i`
//! for lane `i`) or counted: the CPU walk's sign tests and vertex ranks,
//! one compare and one mask move where scalar code takes a compare, a flag
//! move and a shift per lane. SSE2 is part of the x86-64 baseline;
//! elsewhere the same answers come from scalar compares.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::{
    __m128d, _mm_castsi128_ps, _mm_cmpgt_pd, _mm_cmplt_epi32, _mm_cvtps_pd, _mm_loadu_ps,
    _mm_loadu_si128, _mm_movemask_pd, _mm_movemask_ps, _mm_set_pd, _mm_set1_epi32, _mm_setzero_pd,
    _mm_storeu_pd,
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

/// How many lanes of `v` are below `x`, all of them below `2^31`: there
/// signed and unsigned order agree, so SSE2's signed compare counts them.
#[inline(always)]
pub fn count_below(v: [u32; 4], x: u32) -> u32 {
    debug_assert!(v.iter().chain([&x]).all(|&lane| lane < 1 << 31));
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: as in `positive_mask`.
        let mask = unsafe {
            let lanes = _mm_loadu_si128(v.as_ptr().cast());
            _mm_movemask_ps(_mm_castsi128_ps(_mm_cmplt_epi32(
                lanes,
                _mm_set1_epi32(x as i32),
            )))
        };
        mask.count_ones()
    }
    #[cfg(not(target_arch = "x86_64"))]
    v.iter().map(|&lane| u32::from(lane < x)).sum()
}

/// The first two lanes of `v` widened to f64 (exactly): one conversion of
/// both on x86-64, where two scalar conversions take a shuffle between.
#[inline(always)]
pub fn widen_pair(v: [f32; 4]) -> [f64; 2] {
    #[cfg(target_arch = "x86_64")]
    {
        let mut pair = [0.0; 2];
        // SAFETY: as in `positive_mask`; the load reads the four lanes of
        // `v` and the store writes the two of `pair`.
        unsafe { _mm_storeu_pd(pair.as_mut_ptr(), _mm_cvtps_pd(_mm_loadu_ps(v.as_ptr()))) };
        pair
    }
    #[cfg(not(target_arch = "x86_64"))]
    [f64::from(v[0]), f64::from(v[1])]
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

    /// Every combination of special values in every lane gives the mask
    /// of the scalar comparison, in both builds.
    #[test]
    fn mask_matches_scalar_comparisons() {
        for wide in [false, true] {
            for code in 0..SPECIAL.len().pow(4) {
                let v: [f64; 4] = std::array::from_fn(|i| SPECIAL[code / 8usize.pow(i as u32) % 8]);
                let positive = crate::run(wide, || positive_mask(v));
                for (i, &x) in v.iter().enumerate() {
                    assert_eq!(positive >> i & 1 == 1, x > 0.0, "{v:?}");
                }
                assert!(positive < 16);
            }
        }
    }

    /// The scalar count, for lanes and bounds up to the largest below
    /// `2^31`, in both builds.
    #[test]
    fn count_below_counts_smaller_lanes() {
        let v = [0, 7, 0x4000_0000, 0x7fff_ffff];
        for x in [
            0,
            1,
            7,
            8,
            0x3fff_ffff,
            0x4000_0000,
            0x4000_0001,
            0x7fff_ffff,
        ] {
            let expected = v.iter().filter(|&&lane| lane < x).count() as u32;
            for wide in [false, true] {
                assert_eq!(crate::run(wide, || count_below(v, x)), expected, "{x:#x}");
            }
        }
    }

    /// The pair is each lane's own widening, bit for bit, for special
    /// values (a subnormal, both zeros, infinities, a NaN) and ordinary
    /// ones, in both builds.
    #[test]
    fn widen_pair_is_each_lane_widened() {
        let special = [
            0.0,
            -0.0,
            1.5,
            -3.25e-7,
            f32::MIN_POSITIVE * 0.25,
            f32::MAX,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        for (i, &x) in special.iter().enumerate() {
            for &y in &special[i..] {
                for wide in [false, true] {
                    let pair = crate::run(wide, || widen_pair([x, y, 7.0, f32::NAN]));
                    let bits = pair.map(f64::to_bits);
                    assert_eq!(bits, [f64::from(x), f64::from(y)].map(f64::to_bits));
                }
            }
        }
    }
}
