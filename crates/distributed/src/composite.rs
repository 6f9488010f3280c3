//! Compositing fragments, in plain Rust over slices: bucketing them by the
//! rank that owns their pixel (the counts and displacements of an
//! all-to-all exchange), sorting each pixel's fragments by depth, blending
//! them front to back, and placing the composited tiles in the image.

use std::time::{Duration, Instant};

use tetray_raycast::Fragment;

use crate::layout::TileLayout;

/// Fragments ordered by destination rank, as an all-to-all sends them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Buckets {
    /// All fragments, those for rank 0 first, then rank 1's...; within a
    /// rank in their original order.
    pub fragments: Vec<Fragment>,
    /// Fragments for each rank.
    pub counts: Vec<usize>,
    /// Where each rank's fragments start in `fragments`.
    pub displacements: Vec<usize>,
}

/// Orders `fragments` by the rank owning their pixel (a stable counting
/// sort: one pass to count, one to place).
pub fn bucket_by_owner(fragments: &[Fragment], layout: &TileLayout) -> Buckets {
    let ranks = layout.ranks;
    let owners: Vec<usize> = fragments.iter().map(|f| layout.owner(f.pixel)).collect();
    let mut counts = vec![0usize; ranks];
    for &o in &owners {
        counts[o] += 1;
    }
    let displacements = prefix_sums(&counts);
    let mut next = displacements.clone();
    let mut sorted = vec![Fragment::default(); fragments.len()];
    for (f, &o) in fragments.iter().zip(&owners) {
        sorted[next[o]] = *f;
        next[o] += 1;
    }
    Buckets {
        fragments: sorted,
        counts,
        displacements,
    }
}

/// Where each run of `counts` starts.
pub fn prefix_sums(counts: &[usize]) -> Vec<usize> {
    counts
        .iter()
        .scan(0, |at, &n| {
            let start = *at;
            *at += n;
            Some(start)
        })
        .collect()
}

/// The premultiplied RGBA of one pixel from its fragments in depth order:
/// `C += T c_i`, `T *= t_i` front to back (the ray integral's product of
/// transmittances and sum of attenuated emissions, split at the interval
/// boundaries), alpha `1 - mean(T)` as the single-process renderer
/// writes it.
pub fn blend(sorted: &[Fragment]) -> [f32; 4] {
    let mut color = [0.0f32; 3];
    let mut transmittance = [1.0f32; 3];
    for f in sorted {
        for c in 0..3 {
            color[c] += transmittance[c] * f.color[c];
            transmittance[c] *= f.transmittance[c];
        }
    }
    let alpha = 1.0 - (transmittance[0] + transmittance[1] + transmittance[2]) / 3.0;
    [color[0], color[1], color[2], alpha]
}

/// The composited pixels one rank owns, and the time each stage took.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OwnedPixels {
    /// Premultiplied RGBA per owned pixel, in [`TileLayout::owned_pixels`]
    /// order.
    pub rgba: Vec<[f32; 4]>,
    pub sort_time: Duration,
    pub blend_time: Duration,
}

/// Composites the fragments `rank` received (for its own pixels only, in
/// any order): groups them by pixel (counting sort), sorts each pixel's by
/// depth and blends them front to back. Equal depths keep their order in
/// `received` (ranks send in rank order), so the result is deterministic.
///
/// # Panics
/// If a fragment's pixel is not one `rank` owns (the exchange is wrong).
pub fn composite_owned(received: &[Fragment], layout: &TileLayout, rank: usize) -> OwnedPixels {
    let start = Instant::now();
    let owned = layout.slots(rank);
    let slots: Vec<usize> = received
        .iter()
        .map(|f| {
            owned
                .slot(f.pixel)
                .unwrap_or_else(|| panic!("pixel {} is not owned by rank {rank}", f.pixel))
        })
        .collect();
    let mut counts = vec![0usize; layout.owned_count(rank)];
    for &s in &slots {
        counts[s] += 1;
    }
    let starts = prefix_sums(&counts);
    let mut next = starts.clone();
    let mut grouped = vec![Fragment::default(); received.len()];
    for (f, &s) in received.iter().zip(&slots) {
        grouped[next[s]] = *f;
        next[s] += 1;
    }
    for (&at, &n) in starts.iter().zip(&counts) {
        // Stable: equal depths stay in arrival order.
        grouped[at..at + n].sort_by(|a, b| a.depth.total_cmp(&b.depth));
    }
    let sort_time = start.elapsed();
    let start = Instant::now();
    let rgba = starts
        .iter()
        .zip(&counts)
        .map(|(&at, &n)| blend(&grouped[at..at + n]))
        .collect();
    OwnedPixels {
        rgba,
        sort_time,
        blend_time: start.elapsed(),
    }
}

/// The image from every rank's composited pixels (`per_rank[r]` in
/// [`TileLayout::owned_pixels`]`(r)` order): premultiplied RGBA per pixel,
/// row 0 at the top.
///
/// # Panics
/// If a rank sent another number of pixels than it owns.
pub fn assemble(per_rank: &[&[[f32; 4]]], layout: &TileLayout) -> Vec<[f32; 4]> {
    let mut image = vec![[0.0f32; 4]; layout.pixels()];
    for (rank, pixels) in per_rank.iter().enumerate() {
        let owned = layout.owned_pixels(rank);
        assert_eq!(owned.len(), pixels.len(), "rank {rank}: pixel count");
        for (&p, &rgba) in owned.iter().zip(pixels.iter()) {
            image[p as usize] = rgba;
        }
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fragment(pixel: u32, depth: f32, color: [f32; 3], t: [f32; 3]) -> Fragment {
        Fragment {
            pixel,
            depth,
            color,
            transmittance: t,
        }
    }

    /// One homogeneous slab of attenuation `tau` and emitted colour
    /// `light` per unit length, from depth `a` to `b`: exactly
    /// `c = light (1 - e^{-tau l}) / tau`, `t = e^{-tau l}`.
    fn slab(pixel: u32, a: f32, b: f32, tau: f32, light: [f32; 3]) -> Fragment {
        let t = (-tau * (b - a)).exp();
        let c = light.map(|l| l * (1.0 - t) / tau);
        fragment(pixel, a, c, [t; 3])
    }

    #[test]
    fn a_split_homogeneous_ray_composites_to_the_unsplit_integral() {
        // One slab [0, 3] against the same cut at 0.7, 1.1 and 2.5 (the
        // pieces given out of order): equal to f32 rounding, 1e-6.
        let whole = blend(&[slab(0, 0.0, 3.0, 0.8, [0.2, 0.5, 0.9])]);
        let cuts = [0.0, 0.7, 1.1, 2.5, 3.0];
        let mut pieces: Vec<Fragment> = cuts
            .windows(2)
            .map(|w| slab(0, w[0], w[1], 0.8, [0.2, 0.5, 0.9]))
            .collect();
        pieces.reverse();
        pieces.swap(0, 2);
        let layout = TileLayout::new(1, 1, 16, 1).unwrap();
        let split = composite_owned(&pieces, &layout, 0).rgba[0];
        for c in 0..4 {
            assert!((whole[c] - split[c]).abs() < 1e-6, "{whole:?} {split:?}");
        }
    }

    #[test]
    fn blending_is_associative() {
        // (a over b) over c == a over (b over c), as fragments: the outer
        // one made of the two inner ones composited (1e-6, f32 rounding).
        let [a, b, c] = [
            fragment(0, 0.0, [0.1, 0.2, 0.3], [0.9, 0.8, 0.7]),
            fragment(0, 1.0, [0.3, 0.1, 0.0], [0.5, 0.6, 0.4]),
            fragment(0, 2.0, [0.05, 0.4, 0.2], [0.2, 0.9, 0.95]),
        ];
        let over = |x: Fragment, y: Fragment| {
            let mut f = x;
            for i in 0..3 {
                f.color[i] = x.color[i] + x.transmittance[i] * y.color[i];
                f.transmittance[i] = x.transmittance[i] * y.transmittance[i];
            }
            f
        };
        let left = blend(&[over(over(a, b), c)]);
        let right = blend(&[over(a, over(b, c))]);
        let flat = blend(&[a, b, c]);
        for i in 0..4 {
            assert!((left[i] - right[i]).abs() < 1e-6);
            assert!((left[i] - flat[i]).abs() < 1e-6);
        }
    }

    #[test]
    fn empty_pixels_are_clear_and_ties_keep_arrival_order() {
        let layout = TileLayout::new(2, 1, 1, 2).unwrap();
        // Rank 1 owns pixel 1 only; nothing arrives: transparent black.
        let none = composite_owned(&[], &layout, 1);
        assert_eq!(none.rgba, vec![[0.0; 4]]);
        // Two fragments at equal depth: the one received first is in front
        // (exactly, the blend of that order).
        let first = fragment(1, 0.5, [0.4, 0.0, 0.0], [0.5; 3]);
        let second = fragment(1, 0.5, [0.0, 0.4, 0.0], [0.5; 3]);
        let got = composite_owned(&[first, second], &layout, 1).rgba[0];
        assert_eq!(got, blend(&[first, second]));
        assert_eq!(got[0], 0.4);
        assert_eq!(got[1], 0.2);
        // A clear fragment anywhere changes nothing (exactly).
        let clear = fragment(1, 0.5, [0.0; 3], [1.0; 3]);
        assert!(clear.is_clear());
        assert_eq!(
            composite_owned(&[first, clear, second], &layout, 1).rgba[0],
            got
        );
    }

    #[test]
    fn buckets_are_the_counts_and_displacements_of_an_exchange() {
        // 4x1 image, tiles of 1 pixel over 3 ranks: owners 0, 1, 2, 0.
        let layout = TileLayout::new(4, 1, 1, 3).unwrap();
        let frags: Vec<Fragment> = [3, 1, 0, 2, 3, 1]
            .iter()
            .enumerate()
            .map(|(i, &p)| fragment(p, i as f32, [0.0; 3], [1.0; 3]))
            .collect();
        let b = bucket_by_owner(&frags, &layout);
        assert_eq!(b.counts, vec![3, 2, 1]);
        assert_eq!(b.displacements, vec![0, 3, 5]);
        let order: Vec<(u32, f32)> = b.fragments.iter().map(|f| (f.pixel, f.depth)).collect();
        assert_eq!(
            order,
            vec![(3, 0.0), (0, 2.0), (3, 4.0), (1, 1.0), (1, 5.0), (2, 3.0)]
        );
    }

    #[test]
    fn assembling_every_ranks_pixels_gives_the_image() {
        // Each rank composites its own share of a 20x10 image with one
        // fragment per pixel whose colour encodes the pixel: the assembled
        // image holds each pixel's own value (exact).
        let layout = TileLayout::new(20, 10, 4, 3).unwrap();
        let frags: Vec<Fragment> = (0..200)
            .map(|p| fragment(p, 0.0, [p as f32, 0.0, 0.0], [0.5; 3]))
            .collect();
        let b = bucket_by_owner(&frags, &layout);
        let per_rank: Vec<Vec<[f32; 4]>> = (0..3)
            .map(|r| {
                let own = &b.fragments[b.displacements[r]..b.displacements[r] + b.counts[r]];
                composite_owned(own, &layout, r).rgba
            })
            .collect();
        let refs: Vec<&[[f32; 4]]> = per_rank.iter().map(Vec::as_slice).collect();
        let image = assemble(&refs, &layout);
        for (p, rgba) in image.iter().enumerate() {
            assert_eq!(*rgba, [p as f32, 0.0, 0.0, 0.5]);
        }
    }
}
