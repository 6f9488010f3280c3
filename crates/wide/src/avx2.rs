//! Four f64 lanes in one AVX2 register ([`F64x4`]), and the cells of a
//! table gathered eight lanes at a time ([`Avx2::gather_cells`]), safe to
//! use because they exist only where the CPU has AVX2: every value is made
//! through an [`Avx2`] token, which [`Avx2::detect`] returns only after
//! detecting the features. The operations are the IEEE ones of scalar f64
//! code lane by lane (no fused multiply-add), so the bits are the scalar
//! code's.
//!
//! Inlined into [`crate::run`]'s x86-64-v3 copy, each operation is one
//! instruction; elsewhere it is a call (correct, slower).

use std::arch::x86_64::*;

/// Proof that the CPU has AVX and AVX2.
#[derive(Debug, Clone, Copy)]
pub struct Avx2 {
    _detected: (),
}

impl Avx2 {
    /// The token, where the CPU has every feature [`crate::run`] compiles
    /// for (AVX2 among them).
    pub fn detect() -> Option<Avx2> {
        crate::detected().then_some(Avx2 { _detected: () })
    }

    /// Lanes `i..i + 4` of `a`.
    #[inline(always)]
    pub fn load(self, a: &[f64], i: usize) -> F64x4 {
        let lanes: &[f64; 4] = a[i..i + 4].try_into().expect("four lanes");
        // SAFETY: the token proves AVX; the load reads the four lanes
        // borrowed above (unaligned load).
        F64x4(unsafe { _mm256_loadu_pd(lanes.as_ptr()) })
    }

    /// Lanes `i..i + 4` of `a` widened to f64 (exactly).
    #[inline(always)]
    pub fn load_f32(self, a: &[f32], i: usize) -> F64x4 {
        let lanes: &[f32; 4] = a[i..i + 4].try_into().expect("four lanes");
        // SAFETY: as `load`.
        F64x4(unsafe { _mm256_cvtps_pd(_mm_loadu_ps(lanes.as_ptr())) })
    }

    /// Lanes `i..i + 4` of `a`, each below 2^31, as f64 (exactly).
    #[inline(always)]
    pub fn load_u32(self, a: &[u32], i: usize) -> F64x4 {
        let lanes: &[u32; 4] = a[i..i + 4].try_into().expect("four lanes");
        // SAFETY: as `load`; the lanes are read as i32, which they equal
        // below 2^31.
        F64x4(unsafe { _mm256_cvtepi32_pd(_mm_loadu_si128(lanes.as_ptr().cast())) })
    }

    /// [`Avx2::load`] through an address the optimizer cannot follow: a
    /// select between new lanes and these, stored back into `a`, stays a
    /// blend and a plain store. Where it sees the load and the store at
    /// one address, it makes a masked store, which takes many cycles on
    /// some CPUs (AMD's Zen).
    #[inline(always)]
    pub fn load_to_blend(self, a: &[f64], i: usize) -> F64x4 {
        let lanes: &[f64; 4] = a[i..i + 4].try_into().expect("four lanes");
        let mut address = lanes.as_ptr();
        // SAFETY: an empty assembly block that only claims to change the
        // register holding the address; it leaves it as it was, and reads
        // and writes no memory (the lint's concern).
        #[allow(clippy::pointers_in_nomem_asm_block)]
        unsafe {
            std::arch::asm!("/* {0} */", inout(reg) address, options(pure, nomem, nostack))
        };
        // SAFETY: as `load` (the address is the borrowed lanes').
        F64x4(unsafe { _mm256_loadu_pd(address) })
    }

    /// The mask of the lanes whose bit is set in `bits` (bit `i` for lane
    /// `i`; bits from 4 on are ignored).
    #[inline(always)]
    pub fn lane_mask(self, bits: u32) -> F64x4 {
        // SAFETY: the token proves AVX2; register operations only.
        F64x4(unsafe {
            let lane_bits = _mm256_setr_epi64x(1, 2, 4, 8);
            let set = _mm256_and_si256(_mm256_set1_epi64x(i64::from(bits)), lane_bits);
            _mm256_castsi256_pd(_mm256_cmpeq_epi64(set, lane_bits))
        })
    }

    /// Every lane `x`.
    #[inline(always)]
    pub fn splat(self, x: f64) -> F64x4 {
        // SAFETY: the token proves AVX.
        F64x4(unsafe { _mm256_set1_pd(x) })
    }
}

/// Four f64 lanes; a comparison gives a mask (all bits set in a lane
/// where it holds), which [`F64x4::select`] and the bitwise operations
/// take.
#[derive(Debug, Clone, Copy)]
pub struct F64x4(__m256d);

/// Every operation below runs one AVX instruction on values that exist
/// only where the CPU has AVX2 (see [`Avx2`]).
macro_rules! lanewise {
    ($($(#[$doc:meta])* $name:ident => $intrinsic:ident;)*) => {
        $(
            $(#[$doc])*
            #[inline(always)]
            pub fn $name(self, other: F64x4) -> F64x4 {
                // SAFETY: an F64x4 exists only where the CPU has AVX2.
                F64x4(unsafe { $intrinsic(self.0, other.0) })
            }
        )*
    };
}

/// The arithmetic operators, each one AVX instruction (see `lanewise`).
macro_rules! operators {
    ($($trait:ident $name:ident => $intrinsic:ident;)*) => {
        $(
            impl std::ops::$trait for F64x4 {
                type Output = F64x4;
                #[inline(always)]
                fn $name(self, other: F64x4) -> F64x4 {
                    // SAFETY: an F64x4 exists only where the CPU has AVX2.
                    F64x4(unsafe { $intrinsic(self.0, other.0) })
                }
            }
        )*
    };
}

operators! {
    Add add => _mm256_add_pd;
    Sub sub => _mm256_sub_pd;
    Mul mul => _mm256_mul_pd;
    Div div => _mm256_div_pd;
}

impl F64x4 {
    lanewise! {
        /// Bitwise and (of masks, or a mask and values).
        and => _mm256_and_pd;
        /// Bitwise or.
        or => _mm256_or_pd;
        /// Bitwise xor.
        xor => _mm256_xor_pd;
        /// `!self & other`, bitwise.
        and_not => _mm256_andnot_pd;
        /// SSE's minimum: lane `self < other ? self : other` (`other`
        /// where unordered or equal).
        min => _mm256_min_pd;
        /// SSE's maximum: lane `self > other ? self : other`.
        max => _mm256_max_pd;
    }

    /// Each lane rounded to f32 and widened back (`x as f32` as f64).
    #[inline(always)]
    pub fn round_f32(self) -> F64x4 {
        // SAFETY: as `lanewise`.
        F64x4(unsafe { _mm256_cvtps_pd(_mm256_cvtpd_ps(self.0)) })
    }

    /// The mask of `self > other` (false where unordered).
    #[inline(always)]
    pub fn gt(self, other: F64x4) -> F64x4 {
        // SAFETY: as `lanewise`.
        F64x4(unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, other.0) })
    }

    /// The mask of `self < other` (false where unordered).
    #[inline(always)]
    pub fn lt(self, other: F64x4) -> F64x4 {
        // SAFETY: as `lanewise`.
        F64x4(unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self.0, other.0) })
    }

    /// The mask of `self == other` (false where unordered).
    #[inline(always)]
    pub fn eq(self, other: F64x4) -> F64x4 {
        // SAFETY: as `lanewise`.
        F64x4(unsafe { _mm256_cmp_pd::<_CMP_EQ_OQ>(self.0, other.0) })
    }

    /// Lane `a` where this mask is set, `b` elsewhere.
    #[inline(always)]
    pub fn select(self, a: F64x4, b: F64x4) -> F64x4 {
        // SAFETY: as `lanewise`.
        F64x4(unsafe { _mm256_blendv_pd(b.0, a.0, self.0) })
    }

    /// Bit `i` set where lane `i`'s sign bit is (a mask's set lanes).
    #[inline(always)]
    pub fn bits(self) -> u32 {
        // SAFETY: as `lanewise`.
        unsafe { _mm256_movemask_pd(self.0) as u32 }
    }

    /// Stores the lanes into `a[i..i + 4]`.
    #[inline(always)]
    pub fn store(self, a: &mut [f64], i: usize) {
        let lanes: &mut [f64; 4] = (&mut a[i..i + 4]).try_into().expect("four lanes");
        // SAFETY: as `lanewise`; the store writes the four lanes borrowed
        // above.
        unsafe { _mm256_storeu_pd(lanes.as_mut_ptr(), self.0) }
    }

    /// Stores the lanes truncated to i32 (as `x as i32` for lanes inside
    /// its range) into `a[i..i + 4]`, as u32 bits.
    #[inline(always)]
    pub fn store_i32(self, a: &mut [u32], i: usize) {
        let lanes: &mut [u32; 4] = (&mut a[i..i + 4]).try_into().expect("four lanes");
        // SAFETY: as `store`.
        unsafe { _mm_storeu_si128(lanes.as_mut_ptr().cast(), _mm256_cvttpd_epi32(self.0)) }
    }

    /// Stores the lanes rounded to f32 (as `x as f32`) into `a[i..i + 4]`.
    #[inline(always)]
    pub fn store_f32(self, a: &mut [f32], i: usize) {
        let lanes: &mut [f32; 4] = (&mut a[i..i + 4]).try_into().expect("four lanes");
        // SAFETY: as `store`.
        unsafe { _mm_storeu_ps(lanes.as_mut_ptr(), _mm256_cvtpd_ps(self.0)) }
    }
}

impl Avx2 {
    /// The four values of the table cell of each of eight lanes, read with
    /// AVX2 gathers (four in all, where each lane took four loads):
    /// `values[c]`, `values[c + 1]`, `values[c + row]` and
    /// `values[c + row + 1]` for the lane's corner `c = corner[k]`, in that
    /// order; `None` where some lane's cell would reach past `values`.
    #[inline(always)]
    pub fn gather_cells(
        self,
        values: &[f32],
        corner: &[u32; 8],
        row: u32,
    ) -> Option<[[f32; 8]; 4]> {
        // The largest corner whose cell fits, also within the gathers'
        // signed 32-bit offsets.
        let last = values.len().checked_sub(row as usize + 2)?;
        let last =
            u32::try_from(last.min((i32::MAX as usize).saturating_sub(row as usize + 1))).ok()?;
        let mut cell = [[0.0f32; 8]; 4];
        // SAFETY: the token proves AVX2. Every corner is at most `last`
        // (checked below before any gather), so every offset read,
        // `corner + row + 1` at most, is within `values` and fits in i32;
        // the stores write the four arrays of `cell`.
        unsafe {
            let corners = _mm256_loadu_si256(corner.as_ptr().cast());
            let limit = _mm256_set1_epi32(last as i32);
            let within = _mm256_cmpeq_epi32(_mm256_max_epu32(corners, limit), limit);
            if _mm256_movemask_epi8(within) != -1 {
                return None;
            }
            let base = values.as_ptr();
            for (k, offset) in [0, 1, row as usize, row as usize + 1]
                .into_iter()
                .enumerate()
            {
                let lanes = _mm256_i32gather_ps::<4>(base.add(offset), corners);
                _mm256_storeu_ps(cell[k].as_mut_ptr(), lanes);
            }
        }
        Some(cell)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPECIAL: [f64; 8] = [
        0.0,
        -0.0,
        1.5,
        -3.25,
        1e-310,
        f64::NAN,
        f64::INFINITY,
        7e300,
    ];

    /// Every operation gives the scalar operation's bits in every lane,
    /// on special values, in both builds.
    #[test]
    fn lanes_give_the_scalar_bits() {
        let Some(avx2) = Avx2::detect() else {
            return;
        };
        let mask = |b: bool| if b { f64::from_bits(u64::MAX) } else { 0.0 };
        for wide in [false, true] {
            for (k, &x) in SPECIAL.iter().enumerate() {
                let a: Vec<f64> = (0..4).map(|i| SPECIAL[(k + i) % 8]).collect();
                let b: Vec<f64> = (0..4).map(|i| SPECIAL[(k + 3 * i + 1) % 8] - x).collect();
                let got = crate::run(wide, || {
                    let (va, vb) = (avx2.load(&a, 0), avx2.load(&b, 0));
                    let mut out = [[0.0; 4]; 13];
                    let ops = [
                        va + vb,
                        va - vb,
                        va * vb,
                        va / vb,
                        va.min(vb),
                        va.max(vb),
                        va.gt(vb),
                        va.lt(vb),
                        va.eq(vb),
                        va.gt(vb).select(va, vb),
                        va.xor(avx2.splat(-0.0)),
                        va.gt(vb)
                            .and_not(va.lt(vb).or(avx2.splat(0.0)).and(va.eq(va))),
                        va.round_f32(),
                    ];
                    for (o, v) in out.iter_mut().zip(ops) {
                        v.store(o, 0);
                    }
                    let mut narrow = [0.0f32; 4];
                    va.store_f32(&mut narrow, 0);
                    let mut ints = [0u32; 4];
                    va.min(avx2.splat(1e9))
                        .max(avx2.splat(-1e9))
                        .store_i32(&mut ints, 0);
                    let indices = [0, 1, 0x7fff_fffe, 0x7fff_ffff];
                    let mut widened = [0.0; 4];
                    avx2.load_u32(&indices, 0).store(&mut widened, 0);
                    let lane_masks: Vec<u32> = (0..16).map(|b| avx2.lane_mask(b).bits()).collect();
                    (out, narrow, va.lt(vb).bits(), lane_masks, ints, widened)
                });
                for i in 0..4 {
                    let (p, q) = (a[i], b[i]);
                    let expected = [
                        p + q,
                        p - q,
                        p * q,
                        p / q,
                        if p < q { p } else { q },
                        if p > q { p } else { q },
                        mask(p > q),
                        mask(p < q),
                        mask(p == q),
                        if p > q { p } else { q },
                        -p,
                        mask(p < q),
                        f64::from(p as f32),
                    ];
                    for (op, e) in expected.iter().enumerate() {
                        assert_eq!(got.0[op][i].to_bits(), e.to_bits(), "op {op}: {p} {q}");
                    }
                    assert_eq!(got.1[i].to_bits(), (p as f32).to_bits());
                    if !p.is_nan() {
                        assert_eq!(got.4[i], p.clamp(-1e9, 1e9) as i32 as u32, "{p}");
                    }
                    assert_eq!(got.2 >> i & 1 == 1, p < q);
                }
                assert_eq!(got.3, (0..16).collect::<Vec<u32>>());
                assert_eq!(got.5, [0.0, 1.0, 2_147_483_646.0, 2_147_483_647.0]);
            }
        }
    }

    /// The gathered nodes are the table's values at each lane's cell, and
    /// a cell reaching past the table is refused, not read.
    #[test]
    fn gather_cells_reads_each_lanes_cell() {
        let Some(avx2) = Avx2::detect() else {
            eprintln!("note: this CPU lacks AVX2; the gathers were not run");
            return;
        };
        let row = 7u32;
        let values: Vec<f32> = (0..row * row).map(|v| v as f32 * 0.5 - 3.0).collect();
        // The last corner whose cell fits is `row^2 - row - 2`.
        let last = row * row - row - 2;
        let corners = [0, 1, 5, 8, 20, 33, last - 1, last];
        let cell = crate::run(true, || avx2.gather_cells(&values, &corners, row)).expect("cells");
        for (k, &c) in corners.iter().enumerate() {
            let c = c as usize;
            let expected = [c, c + 1, c + row as usize, c + row as usize + 1].map(|i| values[i]);
            assert_eq!([0, 1, 2, 3].map(|node| cell[node][k]), expected, "lane {k}");
        }
        let past = [0, 1, 2, 3, 4, 5, 6, last + 1];
        assert!(avx2.gather_cells(&values, &past, row).is_none());
        assert!(avx2.gather_cells(&values[..3], &[0; 8], row).is_none());
    }
}
