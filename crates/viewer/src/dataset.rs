//! The mesh being viewed, kept whole so that a scene can be made for any of
//! its scalar fields, with what `tetray render` derives from it by default
//! (ParaView's unit distance, the mean chord that sizes the tables), and,
//! for image data, the regular grid itself for the shear-warp renderer.

use anyhow::Context;
use tetray_boundary_bvh::BuildPreset;
use tetray_mesh::{mean_tet_chord, LoadedMesh, TetMesh, Topology};
use tetray_scene::Scene;
use tetray_shearwarp::RegularGrid;

/// A loaded mesh and its defaults.
pub struct Dataset {
    pub name: String,
    mesh: TetMesh,
    topology: Topology,
    /// ParaView's default ScalarOpacityUnitDistance.
    pub unit_distance: f32,
    /// Mean tetrahedron chord: the pre-integration table's length and four
    /// Riemann steps.
    pub chord: f32,
    /// The file's regular grid, when it is image data (`.vti`, legacy
    /// STRUCTURED_POINTS): what shear-warp renders.
    grid: Option<GridVolume>,
}

/// A regular grid in the mesh's coordinates (relative to the same centring
/// origin), with its point fields by name.
#[derive(Debug, Clone)]
pub struct GridVolume {
    pub dims: [usize; 3],
    pub origin: glam::Vec3,
    pub spacing: glam::Vec3,
    pub fields: Vec<(String, Vec<f32>)>,
}

impl Dataset {
    /// The mesh as loaded, with its defaults computed as `tetray render`
    /// computes them (src/cli/scene.rs; a test of the CLI checks they agree).
    pub fn from_loaded(name: impl Into<String>, loaded: LoadedMesh) -> Dataset {
        let unit_distance = loaded.paraview_unit_distance();
        let chord = mean_tet_chord(&loaded.mesh);
        Dataset {
            name: name.into(),
            mesh: loaded.mesh,
            topology: loaded.topology,
            unit_distance,
            chord,
            grid: None,
        }
    }

    /// The same dataset with its regular grid, for the shear-warp renderer.
    pub fn with_grid(mut self, grid: GridVolume) -> Dataset {
        self.grid = Some(grid);
        self
    }

    /// Whether the dataset is image data that shear-warp can render.
    pub fn has_grid(&self) -> bool {
        self.grid.is_some()
    }

    /// The regular grid with `field` as its values.
    pub fn regular_grid(&self, field: &str) -> anyhow::Result<RegularGrid> {
        let grid = self.grid.as_ref().with_context(|| {
            format!(
                "{} is not image data: shear-warp renders regular grids (.vti, legacy \
                 STRUCTURED_POINTS)",
                self.name
            )
        })?;
        let values = grid
            .fields
            .iter()
            .find(|(name, _)| name == field)
            .map(|(_, values)| values.clone())
            .with_context(|| format!("{}: the grid has no point field {field:?}", self.name))?;
        RegularGrid::new(grid.dims, grid.origin, grid.spacing, values)
            .with_context(|| format!("{}: not a grid shear-warp can render", self.name))
    }

    pub fn field_names(&self) -> Vec<String> {
        self.mesh.fields.iter().map(|f| f.name.clone()).collect()
    }

    pub fn tet_count(&self) -> usize {
        self.mesh.tets.len()
    }

    /// A scene with `field` active.
    pub fn scene(&self, field: &str) -> anyhow::Result<Scene> {
        Scene::new(
            self.mesh.clone(),
            self.topology.clone(),
            field,
            BuildPreset::default(),
        )
        .with_context(|| format!("{}: preparing field {field:?}", self.name))
    }
}

/// Counts of `values` in `bins` equal bins over `[lo, hi]`.
pub fn histogram(values: &[f32], (lo, hi): (f32, f32), bins: usize) -> Vec<u32> {
    let mut counts = vec![0u32; bins.max(1)];
    let width = hi - lo;
    for &v in values {
        let t = if width > 0.0 { (v - lo) / width } else { 0.0 };
        let bin = ((t * bins as f32) as usize).min(bins.max(1) - 1);
        counts[bin] += 1;
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histogram_puts_the_ends_in_the_end_bins() {
        let counts = histogram(&[0.0, 0.5, 0.99, 1.0, 0.25], (0.0, 1.0), 4);
        assert_eq!(counts, vec![1, 1, 1, 2]);
        assert_eq!(histogram(&[3.0, 3.0], (3.0, 3.0), 2), vec![2, 0]);
    }
}
