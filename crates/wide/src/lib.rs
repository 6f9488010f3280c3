//! Runs a closure compiled for x86-64-v3 (AVX2, FMA, BMI1/2, LZCNT, MOVBE)
//! where the CPU has those features, and as the baseline build elsewhere.
//!
//! The release build targets baseline x86-64 (SSE2), so that it runs on
//! any x86-64 CPU. [`run`] inlines the closure into a function compiled
//! with the x86-64-v3 features, where the same operations take fewer
//! instructions (three-operand AVX forms of the SSE arithmetic, no
//! register copies). Rust never fuses a multiplication and an addition
//! into an FMA on its own, so the results are the same bits.
//!
//! [`lanes`] answers comparisons of four lanes as bit masks (SSE2, part
//! of every x86-64 CPU); [`avx2`] holds four f64 lanes in one AVX2
//! register, for code that [`run`] compiles for x86-64-v3.

#[cfg(target_arch = "x86_64")]
pub mod avx2;
pub mod lanes;

/// Proof that code may use AVX2 ([`avx2::Avx2`]); off x86-64 a type with
/// no values, so an `Option<Wide>` there is always `None`.
#[cfg(target_arch = "x86_64")]
pub type Wide = avx2::Avx2;
/// No AVX2 off x86-64.
#[cfg(not(target_arch = "x86_64"))]
pub type Wide = std::convert::Infallible;

/// The token of the vectors where the caller runs [`run`]'s x86-64-v3 copy
/// (`wide`, as passed to [`run`]) on a CPU that has it; `None` otherwise,
/// and the caller takes its scalar path (the same bits).
pub fn token(wide: bool) -> Option<Wide> {
    #[cfg(target_arch = "x86_64")]
    return if wide { avx2::Avx2::detect() } else { None };
    #[cfg(not(target_arch = "x86_64"))]
    {
        let _ = wide;
        None
    }
}

/// Whether [`run`] takes the x86-64-v3 copy: on a CPU with the features,
/// unless the environment variable `TETRAY_CPU_BASELINE` is set (to time
/// the two builds against each other).
pub fn available() -> bool {
    std::env::var_os("TETRAY_CPU_BASELINE").is_none() && detected()
}

/// Whether this CPU has every x86-64-v3 feature [`run`] compiles for.
pub fn detected() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        is_x86_feature_detected!("avx2")
            && is_x86_feature_detected!("fma")
            && is_x86_feature_detected!("bmi1")
            && is_x86_feature_detected!("bmi2")
            && is_x86_feature_detected!("lzcnt")
            && is_x86_feature_detected!("movbe")
            && is_x86_feature_detected!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// Calls `work`, compiled for x86-64-v3 when `wide` is true and
/// [`detected`] (the caller decides once, by [`available`], and may ask for
/// the baseline to compare); as the baseline build otherwise. Mark the
/// closure's callees `#[inline(always)]`: only code inlined into it is
/// compiled for the wider instruction set.
#[inline(always)]
pub fn run<R>(wide: bool, work: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if wide && detected() {
        // SAFETY: the CPU has every feature `v3` is compiled for
        // (`detected` checked each one).
        return unsafe { v3(work) };
    }
    let _ = wide;
    work()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx,avx2,fma,bmi1,bmi2,lzcnt,movbe,popcnt")]
unsafe fn v3<R>(work: impl FnOnce() -> R) -> R {
    work()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Float arithmetic gives the same bits in both builds (no fused
    /// multiply-add appears where the source has none).
    #[test]
    fn both_builds_give_the_same_bits() {
        let sum = |values: &[f32]| {
            let mut acc = 0.0f32;
            for (i, &v) in values.iter().enumerate() {
                acc = acc * 0.999_9 + v * (i as f32).sqrt() - v / 3.0;
            }
            acc
        };
        let values: Vec<f32> = (0..10_000)
            .map(|i| ((i * 7919) % 1000) as f32 * 1.1e-3)
            .collect();
        let narrow = run(false, || sum(&values));
        let wide = run(true, || sum(&values));
        assert_eq!(narrow.to_bits(), wide.to_bits());
        if !detected() {
            eprintln!("note: this CPU lacks x86-64-v3; only the baseline build ran");
        }
    }
}
