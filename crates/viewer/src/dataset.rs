//! The mesh being viewed, kept whole so that a scene can be made for any of
//! its scalar fields, with what `tetray render` derives from it by default
//! (ParaView's unit distance, the mean chord that sizes the tables).

use anyhow::Context;
use tetray_boundary_bvh::BuildPreset;
use tetray_mesh::{LoadedMesh, TetMesh, Topology};
use tetray_raycast::Scene;

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
}

impl Dataset {
    /// The mesh as loaded, with its defaults computed as `tetray render`
    /// computes them (src/cli/scene.rs; a test of the CLI checks they agree).
    pub fn from_loaded(name: impl Into<String>, loaded: LoadedMesh) -> Dataset {
        let report = &loaded.report;
        let input_cells = loaded.mesh.tets.len() - report.tets_from_split + report.cells_split;
        let unit_distance = paraview_unit_distance(&loaded.mesh, input_cells);
        let chord = mean_tet_chord(&loaded.mesh);
        Dataset {
            name: name.into(),
            mesh: loaded.mesh,
            topology: loaded.topology,
            unit_distance,
            chord,
        }
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

/// ParaView's default ScalarOpacityUnitDistance (vtkSMBoundsDomain,
/// APPROXIMATE_CELL_LENGTH): the bounds diagonal over the cube root of the
/// cells as read; 1 (VTK's default) for a mesh without a length scale.
pub fn paraview_unit_distance(mesh: &TetMesh, input_cells: usize) -> f32 {
    let (lo, hi) = mesh.bounds();
    let diagonal = (hi - lo).as_dvec3().length();
    let cells = input_cells as f64;
    let u = if cells > 0.0 {
        diagonal / cells.cbrt()
    } else {
        diagonal
    };
    if u > 0.0 && u.is_finite() {
        u as f32
    } else {
        1.0
    }
}

/// Mean chord of the tetrahedra, 4 V / S (Cauchy); 1 for a degenerate mesh.
pub fn mean_tet_chord(mesh: &TetMesh) -> f32 {
    let mut sum = 0.0f64;
    for tet in &mesh.tets {
        let [a, b, c, d] = tet.map(|v| mesh.points[v as usize].as_dvec3());
        let volume = (b - a).dot((c - a).cross(d - a)).abs() / 6.0;
        let area =
            |p: glam::DVec3, q: glam::DVec3, r: glam::DVec3| (q - p).cross(r - p).length() / 2.0;
        let surface = area(a, b, c) + area(a, b, d) + area(a, c, d) + area(b, c, d);
        if surface > 0.0 {
            sum += 4.0 * volume / surface;
        }
    }
    let chord = (sum / mesh.tets.len().max(1) as f64) as f32;
    if chord > 0.0 && chord.is_finite() {
        chord
    } else {
        1.0
    }
}

/// Smallest and largest value.
pub fn value_range(values: &[f32]) -> (f32, f32) {
    values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
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
        assert_eq!(value_range(&[2.0, -1.0, 5.0]), (-1.0, 5.0));
    }
}
