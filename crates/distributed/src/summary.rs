//! What every rank must agree on to render its piece as the whole mesh
//! would be rendered: the bounds (camera fit, ParaView's unit distance),
//! the input cell count, the mean tetrahedron chord and the range of each
//! field (transfer function, default field). Each rank summarises its
//! piece; the summaries combine by min, max and sum (an allreduce over
//! [`MeshSummary::to_reduce`]).

use glam::Vec3;
use tetray_mesh::{TetMesh, mean_chord, paraview_unit_distance, tet_chord_sum, value_range};

/// One rank's piece, or (combined) the whole mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSummary {
    /// Bounds of the points (relative to the common origin); inverted
    /// (`+inf`, `-inf`) for an empty piece.
    pub bounds: (Vec3, Vec3),
    /// Cells as read, before splitting (what ParaView counts).
    pub input_cells: u64,
    pub tets: u64,
    /// Sum of the tetrahedra's mean chords.
    pub chord_sum: f64,
    /// Smallest and largest value of each field, in the order of the
    /// field names every rank shares.
    pub field_ranges: Vec<(f32, f32)>,
}

/// Values an allreduce combines: elementwise minima, maxima and sums.
#[derive(Debug, Clone, PartialEq)]
pub struct Reduce {
    pub min: Vec<f64>,
    pub max: Vec<f64>,
    pub sum: Vec<f64>,
}

impl MeshSummary {
    /// The summary of a piece; `input_cells` as its loader counted them,
    /// `fields` the names of the fields to range (missing ones are empty).
    pub fn of(mesh: &TetMesh, input_cells: usize, fields: &[String]) -> MeshSummary {
        let bounds = if mesh.points.is_empty() {
            (Vec3::INFINITY, Vec3::NEG_INFINITY)
        } else {
            mesh.bounds()
        };
        let field_ranges = fields
            .iter()
            .map(|name| {
                mesh.field(name)
                    .map_or((f32::INFINITY, f32::NEG_INFINITY), |f| {
                        value_range(&f.values)
                    })
            })
            .collect();
        MeshSummary {
            bounds,
            input_cells: input_cells as u64,
            tets: mesh.tets.len() as u64,
            chord_sum: tet_chord_sum(mesh),
            field_ranges,
        }
    }

    /// The values to reduce across ranks (f32 values are exact in f64).
    pub fn to_reduce(&self) -> Reduce {
        let (lo, hi) = self.bounds;
        let mut min: Vec<f64> = lo.to_array().iter().map(|&v| f64::from(v)).collect();
        let mut max: Vec<f64> = hi.to_array().iter().map(|&v| f64::from(v)).collect();
        for &(a, b) in &self.field_ranges {
            min.push(f64::from(a));
            max.push(f64::from(b));
        }
        Reduce {
            min,
            max,
            sum: vec![self.input_cells as f64, self.tets as f64, self.chord_sum],
        }
    }

    /// The summary of the reduced values (inverse of [`Self::to_reduce`]).
    pub fn from_reduced(r: &Reduce) -> MeshSummary {
        let v3 = |v: &[f64]| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
        MeshSummary {
            bounds: (v3(&r.min[..3]), v3(&r.max[..3])),
            input_cells: r.sum[0] as u64,
            tets: r.sum[1] as u64,
            chord_sum: r.sum[2],
            field_ranges: r.min[3..]
                .iter()
                .zip(&r.max[3..])
                .map(|(&a, &b)| (a as f32, b as f32))
                .collect(),
        }
    }

    /// Two summaries combined, as the allreduce combines them.
    pub fn combine(&self, other: &MeshSummary) -> MeshSummary {
        let (a, b) = (self.to_reduce(), other.to_reduce());
        let zip = |x: &[f64], y: &[f64], f: fn(f64, f64) -> f64| {
            x.iter().zip(y).map(|(&p, &q)| f(p, q)).collect()
        };
        MeshSummary::from_reduced(&Reduce {
            min: zip(&a.min, &b.min, f64::min),
            max: zip(&a.max, &b.max, f64::max),
            sum: zip(&a.sum, &b.sum, |p, q| p + q),
        })
    }

    /// ParaView's default unit distance of the whole mesh.
    pub fn paraview_unit_distance(&self) -> f32 {
        paraview_unit_distance(self.bounds, self.input_cells as usize)
    }

    /// The mean tetrahedron chord of the whole mesh.
    pub fn mean_chord(&self) -> f32 {
        mean_chord(self.chord_sum, self.tets as usize)
    }

    /// The index of the field a user expects first (as
    /// [`tetray_mesh::default_field`]: the first that varies, else the
    /// first), decided on the whole mesh's ranges.
    pub fn default_field(&self) -> Option<usize> {
        let ranges = &self.field_ranges;
        ranges
            .iter()
            .position(|&(lo, hi)| lo < hi)
            .or_else(|| (!ranges.is_empty()).then_some(0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tetray_mesh::ScalarField;

    fn mesh(offset: f32, values: [f32; 4]) -> TetMesh {
        TetMesh {
            points: vec![
                Vec3::new(offset, 0.0, 0.0),
                Vec3::new(offset + 1.0, 0.0, 0.0),
                Vec3::new(offset, 1.0, 0.0),
                Vec3::new(offset, 0.0, 1.0),
            ],
            tets: vec![[0, 1, 2, 3]],
            fields: vec![
                ScalarField {
                    name: "flat".into(),
                    values: vec![2.0; 4],
                },
                ScalarField {
                    name: "s".into(),
                    values: values.to_vec(),
                },
            ],
        }
    }

    #[test]
    fn combined_summaries_equal_the_whole_meshs() {
        // Two tetrahedra apart: the combined summary is that of the two in
        // one mesh (bounds and ranges exact; the chord sum to 1e-12, the
        // order of an f64 sum).
        let (a, b) = (
            mesh(0.0, [0.0, 1.0, 2.0, 3.0]),
            mesh(5.0, [2.0, 2.0, 2.0, 9.0]),
        );
        let names = vec!["flat".to_string(), "s".to_string()];
        let mut whole = a.clone();
        whole.points.extend(&b.points);
        whole.tets.push([4, 5, 6, 7]);
        for (f, g) in whole.fields.iter_mut().zip(&b.fields) {
            f.values.extend(&g.values);
        }
        let combined = MeshSummary::of(&a, 1, &names).combine(&MeshSummary::of(&b, 1, &names));
        let expected = MeshSummary::of(&whole, 2, &names);
        assert_eq!(combined.bounds, expected.bounds);
        assert_eq!(combined.field_ranges, expected.field_ranges);
        assert_eq!((combined.input_cells, combined.tets), (2, 2));
        assert!((combined.chord_sum - expected.chord_sum).abs() < 1e-12);
        assert_eq!(combined.default_field(), Some(1));
        assert_eq!(
            combined.paraview_unit_distance(),
            paraview_unit_distance(whole.bounds(), 2)
        );
    }

    #[test]
    fn an_empty_piece_changes_nothing() {
        let names = vec!["s".to_string()];
        let a = MeshSummary::of(&mesh(0.0, [0.0, 1.0, 2.0, 3.0]), 1, &names);
        let empty = MeshSummary::of(&TetMesh::default(), 0, &names);
        assert_eq!(a.combine(&empty), a);
        // A field the piece lacks is empty, not zero.
        let other = MeshSummary::of(&mesh(0.0, [0.0; 4]), 1, &["none".to_string()]);
        assert_eq!(other.field_ranges, vec![(f32::INFINITY, f32::NEG_INFINITY)]);
        assert_eq!(other.default_field(), Some(0));
    }
}
