//! Length scales and ranges that the renderers derive from a mesh by
//! default: ParaView's opacity unit distance and the mean tetrahedron
//! chord (the pre-integration table's length, the Riemann step).

use crate::{LoadedMesh, TetMesh};
use rayon::prelude::*;

impl LoadedMesh {
    /// Cells of the dataset as read, before non-tetrahedral cells were
    /// split: what ParaView counts (hexahedra for a PLOT3D grid).
    pub fn input_cells(&self) -> usize {
        let report = &self.report;
        // Every tetrahedron read, those left out of the walk included.
        let read = self.mesh.tets.len() + report.excluded.tets + report.excluded.flat_tets;
        read.saturating_sub(report.tets_from_split) + report.cells_split
    }

    /// ParaView's default ScalarOpacityUnitDistance (vtkSMBoundsDomain,
    /// mode APPROXIMATE_CELL_LENGTH): the bounds diagonal divided by the
    /// cube root of the dataset's cell count, the diagonal itself for no
    /// cells; 1 (VTK's default) for a mesh without a length scale.
    pub fn paraview_unit_distance(&self) -> f32 {
        paraview_unit_distance(self.mesh.bounds(), self.input_cells())
    }
}

/// ParaView's default unit distance of a dataset of `cells` input cells
/// within `bounds` (see [`LoadedMesh::paraview_unit_distance`]; a mesh
/// split over processes passes its global bounds and cell count).
pub fn paraview_unit_distance((lo, hi): (glam::Vec3, glam::Vec3), cells: usize) -> f32 {
    tetray_core::defaults::unit_distance((hi - lo).as_dvec3().length(), cells as f64)
}

/// Mean chord length of the tetrahedra: for random lines through a convex
/// body it is 4 V / S (Cauchy), the typical length of a ray segment; 1 for
/// a degenerate mesh.
pub fn mean_tet_chord(mesh: &TetMesh) -> f32 {
    mean_chord(tet_chord_sum(mesh), mesh.tets.len())
}

/// The sum over the tetrahedra of their mean chords (those of a mesh split
/// over processes add up to the whole mesh's).
///
/// Summed in parallel over fixed blocks of tetrahedra, each block in order
/// and the block sums in order: the same bits whatever the thread count.
pub fn tet_chord_sum(mesh: &TetMesh) -> f64 {
    const BLOCK: usize = 1 << 14;
    let block_sums: Vec<f64> = mesh
        .tets
        .par_chunks(BLOCK)
        .map(|tets| {
            let mut sum = 0.0f64;
            for tet in tets {
                let [a, b, c, d] = tet.map(|v| mesh.points[v as usize].as_dvec3());
                let volume = (b - a).dot((c - a).cross(d - a)).abs() / 6.0;
                let area = |p: glam::DVec3, q: glam::DVec3, r: glam::DVec3| {
                    (q - p).cross(r - p).length() / 2.0
                };
                let surface = area(a, b, c) + area(a, b, d) + area(a, c, d) + area(b, c, d);
                if surface > 0.0 {
                    sum += 4.0 * volume / surface;
                }
            }
            sum
        })
        .collect();
    block_sums.iter().sum()
}

/// [`mean_tet_chord`] from [`tet_chord_sum`] over `tets` tetrahedra.
pub fn mean_chord(chord_sum: f64, tets: usize) -> f32 {
    let chord = (chord_sum / tets.max(1) as f64) as f32;
    if chord > 0.0 && chord.is_finite() {
        chord
    } else {
        1.0
    }
}

/// Smallest and largest value (finite values: validated on load).
pub fn value_range(values: &[f32]) -> (f32, f32) {
    values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// The field a user expects to see first: the first that is not constant
/// (the readers put point fields before cell fields averaged to points,
/// and vectors as magnitudes), else the first; `None` without fields.
pub fn default_field(mesh: &TetMesh) -> Option<&crate::ScalarField> {
    default_field_of(&mesh.fields)
}

/// [`default_field`] among `fields` (a regular grid's, say).
pub fn default_field_of(fields: &[crate::ScalarField]) -> Option<&crate::ScalarField> {
    let varies = |f: &&crate::ScalarField| {
        let (lo, hi) = value_range(&f.values);
        lo < hi
    };
    fields.iter().find(varies).or_else(|| fields.first())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn chord_of_a_regular_tetrahedron_and_ranges() {
        // Regular tetrahedron of edge 1: V = 1/(6 sqrt 2), S = sqrt 3,
        // chord 4 V / S = sqrt(2/3) / 3.
        let h = (2.0f32 / 3.0).sqrt();
        let mesh = TetMesh {
            points: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.5, 3f32.sqrt() / 2.0, 0.0),
                Vec3::new(0.5, 3f32.sqrt() / 6.0, h),
            ],
            tets: vec![[0, 1, 2, 3]],
            ..TetMesh::default()
        };
        let expected = (2.0f32 / 3.0).sqrt() / 3.0;
        assert!((mean_tet_chord(&mesh) - expected).abs() < 1e-6);
        assert_eq!(value_range(&[2.0, -1.0, 5.0]), (-1.0, 5.0));
    }

    #[test]
    fn default_field_is_the_first_that_varies() {
        let field = |name: &str, values: Vec<f32>| crate::ScalarField {
            name: name.into(),
            values,
        };
        let mut mesh = TetMesh::default();
        assert!(default_field(&mesh).is_none());
        mesh.fields = vec![field("flat", vec![1.0, 1.0]), field("also", vec![2.0, 2.0])];
        assert_eq!(default_field(&mesh).map(|f| f.name.as_str()), Some("flat"));
        mesh.fields.push(field("p", vec![0.0, 3.0]));
        mesh.fields.push(field("q", vec![1.0, 3.0]));
        assert_eq!(default_field(&mesh).map(|f| f.name.as_str()), Some("p"));
    }
}
