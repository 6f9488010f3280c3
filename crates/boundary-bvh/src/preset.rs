//! The obvhs build presets, by name.

use std::fmt;
use std::str::FromStr;

use obvhs::BvhBuildParams;

use crate::BvhError;

/// One of obvhs' BVH build parameter presets, fastest build to best tree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum BuildPreset {
    Fastest,
    VeryFast,
    Fast,
    Medium,
    Slow,
    /// Default. The BVH is built once per mesh and queried for every pixel of
    /// every frame: on the dissertation grids (14k-28k boundary faces) this
    /// builds in under 0.1 s and answers entry queries 1.05-1.6x and
    /// queries from inside the mesh 1.1-3.4x faster than `medium`
    /// (measured then; now `cargo bench --bench mesh -- bvh`). Pick a faster preset for meshes with millions of
    /// boundary faces (about 3 us per face here, single-threaded).
    #[default]
    VerySlow,
}

impl BuildPreset {
    /// Every preset, fastest build first.
    pub const ALL: [BuildPreset; 6] = [
        BuildPreset::Fastest,
        BuildPreset::VeryFast,
        BuildPreset::Fast,
        BuildPreset::Medium,
        BuildPreset::Slow,
        BuildPreset::VerySlow,
    ];

    /// The command-line name (`very-fast`, ...).
    pub fn name(self) -> &'static str {
        match self {
            BuildPreset::Fastest => "fastest",
            BuildPreset::VeryFast => "very-fast",
            BuildPreset::Fast => "fast",
            BuildPreset::Medium => "medium",
            BuildPreset::Slow => "slow",
            BuildPreset::VerySlow => "very-slow",
        }
    }

    /// The obvhs parameters of this preset.
    pub fn params(self) -> BvhBuildParams {
        match self {
            BuildPreset::Fastest => BvhBuildParams::fastest_build(),
            BuildPreset::VeryFast => BvhBuildParams::very_fast_build(),
            BuildPreset::Fast => BvhBuildParams::fast_build(),
            BuildPreset::Medium => BvhBuildParams::medium_build(),
            BuildPreset::Slow => BvhBuildParams::slow_build(),
            BuildPreset::VerySlow => BvhBuildParams::very_slow_build(),
        }
    }

    /// All names, comma separated, for error messages and `--help`.
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }
}

impl fmt::Display for BuildPreset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for BuildPreset {
    type Err = BvhError;

    /// Accepts the [`BuildPreset::name`]s, case-insensitively, with `_` for `-`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase().replace('_', "-");
        Self::ALL
            .into_iter()
            .find(|p| p.name() == wanted)
            .ok_or_else(|| BvhError::UnknownPreset(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for p in BuildPreset::ALL {
            assert_eq!(p.to_string().parse::<BuildPreset>(), Ok(p));
        }
        assert_eq!(
            "VERY_SLOW".parse::<BuildPreset>(),
            Ok(BuildPreset::VerySlow)
        );
        assert!(matches!(
            "ludicrous".parse::<BuildPreset>(),
            Err(BvhError::UnknownPreset(_))
        ));
    }
}
