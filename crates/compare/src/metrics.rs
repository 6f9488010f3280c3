//! Per-pixel error against a reference and its summary.

use serde::Serialize;
use tetray_core::Image;

use crate::CompareError;

/// One 8-bit step: a difference a PNG can show.
pub const ONE_LEVEL: f32 = 1.0 / 255.0;

/// Per pixel, the largest absolute difference over the premultiplied RGBA
/// channels.
pub fn abs_error(test: &Image, reference: &Image) -> Result<Vec<f32>, CompareError> {
    same_size(test, reference)?;
    Ok(test
        .rgba
        .iter()
        .zip(&reference.rgba)
        .map(|(a, b)| (0..4).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max))
        .collect())
}

/// An error unless `test` is as large as `reference`.
pub fn same_size(test: &Image, reference: &Image) -> Result<(), CompareError> {
    if (test.width, test.height) != (reference.width, reference.height) {
        return Err(CompareError::SizeMismatch {
            test: (test.width, test.height),
            reference: (reference.width, reference.height),
        });
    }
    Ok(())
}

/// Summary of a per-pixel error map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ErrorStats {
    pub max: f32,
    pub mean: f64,
    /// 99th percentile (nearest rank).
    pub p99: f32,
    /// Pixels whose error exceeds [`ONE_LEVEL`].
    pub over_one_level: usize,
    pub pixels: usize,
}

impl ErrorStats {
    pub fn of(errors: &[f32]) -> ErrorStats {
        let n = errors.len();
        let mut sorted = errors.to_vec();
        sorted.sort_by(f32::total_cmp);
        let rank = ((0.99 * n as f64).ceil() as usize).clamp(1, n.max(1)) - 1;
        ErrorStats {
            max: sorted.last().copied().unwrap_or(0.0),
            mean: errors.iter().map(|&e| f64::from(e)).sum::<f64>() / n.max(1) as f64,
            p99: sorted.get(rank).copied().unwrap_or(0.0),
            over_one_level: errors.iter().filter(|&&e| e > ONE_LEVEL).count(),
            pixels: n,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_of_known_errors() {
        let mut errors = vec![0.0f32; 200];
        errors[3] = 0.5;
        errors[7] = 0.01;
        errors[9] = 0.003;
        let s = ErrorStats::of(&errors);
        assert_eq!(s.max, 0.5);
        assert!((s.mean - 0.513 / 200.0).abs() < 1e-9);
        // Nearest rank: the ceil(0.99 * 200) = 198th smallest of 200, the
        // third largest.
        assert_eq!(s.p99, 0.003);
        assert_eq!(s.over_one_level, 2);
    }

    #[test]
    fn channels_and_sizes() {
        let a = Image::from_pixels(2, 1, vec![[0.1, 0.2, 0.3, 0.4], [0.0; 4]]).unwrap();
        let b =
            Image::from_pixels(2, 1, vec![[0.1, 0.5, 0.3, 0.4], [0.0, 0.0, 0.0, 0.25]]).unwrap();
        let e = abs_error(&a, &b).unwrap();
        assert!((e[0] - 0.3).abs() < 1e-6 && e[1] == 0.25);
        let c = Image::new(1, 1).unwrap();
        assert!(abs_error(&a, &c).is_err());
    }
}
