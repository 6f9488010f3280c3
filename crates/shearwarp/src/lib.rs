//! Regular grids rendered with the shear-warp factorization (Lacroute and
//! Levoy 1994) and pre-integrated classification (Schulze, Kraus, Lang and
//! Ertl, *Integrating Pre-Integration into the Shear-Warp Algorithm*, 2003).
//!
//! - [`RegularGrid`]: dims, origin, spacing (anisotropic allowed), f32
//!   point scalars;
//! - [`ShearWarp`]: the renderer for one grid and one transfer function.
//!   It picks the principal viewing axis (the largest component of the
//!   view direction in index space), composites the slabs between
//!   consecutive slices front to back into an intermediate image aligned
//!   with the front slice (sheared slices; for perspective, also scaled),
//!   then warps that image to the final one bilinearly. Slabs are
//!   classified with the full pre-integration table of `tetray-integrate`
//!   plus Schulze et al.'s opacity and colour correction, or post-classified (the
//!   baseline); see [`classify`]. Empty cells are run-length encoded per
//!   scanline and skipped; opaque pixels are skipped by links and stop
//!   their ray early; scanlines are composited in parallel (rayon).
//!
//! Resampling error by design: the rays of the intermediate image pass
//! through the points of the front slice; the scalar is interpolated
//! bilinearly within each slice and linearly between slices (the
//! tetrahedral ray caster interpolates linearly within each of 5
//! tetrahedra per cell); the final image interpolates the intermediate one
//! bilinearly. A ray that crosses a side face of the grid between two
//! slices composites the part of that slab inside the grid, its light
//! scaled to the part's length. On a constant or linear field the first
//! two agree exactly, so only the warp differs from the exact ray caster.

pub mod classify;
mod grid;
mod render;
mod stack;

use std::sync::OnceLock;

pub use classify::Classification;
pub use grid::RegularGrid;
pub use render::{ShearWarpOptions, ShearWarpOutput, ShearWarpStats};

use tetray_core::{CameraError, ImageError};
use tetray_integrate::{
    IntegrateError, OpacityMode, PreintegrationTable, TfKnots, TransferFunction,
};

use classify::Classifier;
use stack::Stack;

/// Why a grid cannot be rendered.
#[derive(Debug, thiserror::Error)]
pub enum ShearWarpError {
    #[error("grid dimensions {0:?}: shear-warp needs at least 2 points along every axis")]
    Dims([usize; 3]),
    #[error("grid origin {0:?} is not finite")]
    Origin([f32; 3]),
    #[error("grid spacing {0:?} must be finite and positive along every axis")]
    Spacing([f32; 3]),
    #[error("grid dimensions {0:?} hold too many points")]
    TooLarge([usize; 3]),
    #[error("the grid has {expected} points but {found} values")]
    ValueCount { expected: usize, found: usize },
    #[error("grid value {index} is not finite ({value})")]
    NonFiniteValue { index: usize, value: f32 },
    #[error("opacity unit distance {0} must be finite and positive")]
    UnitDistance(f32),
    #[error("early termination threshold {0} must be in (0, 1] (1 disables it)")]
    BadEarlyTermination(f32),
    #[error(
        "perspective shear-warp needs the eye outside the grid along its principal axis \
         ({axis}): the eye is at index {index} of 0..={last}; move the camera back or use a \
         parallel projection"
    )]
    EyeInsideSlab { axis: char, index: f64, last: usize },
    #[error(transparent)]
    Camera(#[from] CameraError),
    #[error(transparent)]
    Image(#[from] ImageError),
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
}

/// How the transfer function becomes slab light.
#[derive(Debug, Clone, PartialEq)]
pub struct ClassifyOptions {
    pub classification: Classification,
    /// A transfer-function opacity is the opacity of this length of
    /// material (world units), as in the ray caster.
    pub unit_distance: f32,
    pub opacity_mode: OpacityMode,
    /// Pre-integration table nodes per axis.
    pub table_size: usize,
}

impl Default for ClassifyOptions {
    fn default() -> Self {
        ClassifyOptions {
            classification: Classification::PreIntegrated,
            unit_distance: 1.0,
            opacity_mode: OpacityMode::Exact,
            table_size: 256,
        }
    }
}

/// A grid and a transfer function, ready to render from any view.
#[derive(Debug)]
pub struct ShearWarp {
    grid: RegularGrid,
    classification: Classification,
    classifier: Classifier,
    stacks: [OnceLock<Stack>; 3],
}

impl ShearWarp {
    /// Classifies `tf` for `grid`: builds the pre-integration table (over
    /// the union of the grid's and the transfer function's scalar ranges, for
    /// slabs one smallest grid spacing long) when pre-integrating.
    pub fn new(
        grid: RegularGrid,
        tf: &TransferFunction,
        opts: &ClassifyOptions,
    ) -> Result<ShearWarp, ShearWarpError> {
        let u = opts.unit_distance;
        if !(u.is_finite() && u > 0.0) {
            return Err(ShearWarpError::UnitDistance(u));
        }
        let knots = TfKnots::new(tf, u, opts.opacity_mode);
        let table = match opts.classification {
            Classification::PreIntegrated => {
                let (g_lo, g_hi) = grid.value_range();
                let (t_lo, t_hi) = tf.scalar_range();
                let range = (g_lo.min(t_lo), g_hi.max(t_hi));
                let length = grid.spacing().min_element();
                Some(PreintegrationTable::build(
                    &knots,
                    range,
                    opts.table_size,
                    length,
                )?)
            }
            Classification::PostClassified => None,
        };
        Ok(ShearWarp {
            grid,
            classification: opts.classification,
            classifier: Classifier::new(knots, table),
            stacks: Default::default(),
        })
    }

    pub fn grid(&self) -> &RegularGrid {
        &self.grid
    }

    pub fn classification(&self) -> Classification {
        self.classification
    }

    /// The pre-integration table (none when post-classifying).
    pub fn table(&self) -> Option<&PreintegrationTable> {
        self.classifier.table.as_ref()
    }

    /// Builds the slice copies and run-length encodings of all three axes
    /// now (otherwise the first frame along an axis builds its own).
    pub fn prepare_all_axes(&self) {
        for c in 0..3 {
            self.stack(c);
        }
    }

    pub(crate) fn stack(&self, c: usize) -> &Stack {
        self.stacks[c].get_or_init(|| Stack::build(&self.grid, c, &self.classifier))
    }
}
