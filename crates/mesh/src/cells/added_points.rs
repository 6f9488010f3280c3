//! Points the cell splitter adds (face and cell centres), each a weighted
//! sum of points of the file. `assemble` appends them after the file's
//! points and applies the same weights to the coordinates and to every
//! point array, so positions and fields stay consistent.

use std::collections::HashMap;

/// What an added point is keyed by: points on a face are shared by the two
/// cells of the face, so the subdivision of the face is the same from both
/// sides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PointKey {
    /// The centre of a quadratic quadrilateral face (8-node serendipity
    /// weights), by its four sorted corner ids.
    QuadCentre([u32; 4]),
}

/// The points added so far, as weights over the file's points.
#[derive(Debug, Default)]
pub struct AddedPoints {
    /// Index of the first added point: the number of points in the file.
    first: usize,
    shared: HashMap<PointKey, u32>,
    /// Shared polygon centroids, by their sorted vertex ids.
    polygons: HashMap<Vec<u32>, u32>,
    /// (file point, weight) per added point; the weights sum to 1.
    weights: Vec<Vec<(u32, f64)>>,
}

impl AddedPoints {
    pub fn new(first: usize) -> Self {
        AddedPoints {
            first,
            ..AddedPoints::default()
        }
    }

    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// The point for `key`, made with the weights of `make` the first time.
    pub fn shared(&mut self, key: PointKey, make: impl FnOnce() -> Vec<(u32, f64)>) -> u32 {
        if let Some(&id) = self.shared.get(&key) {
            return id;
        }
        let id = self.push(make());
        self.shared.insert(key, id);
        id
    }

    /// The centroid of a polygon face, shared by the cells using the face
    /// (keyed by its vertex set, whatever the order each cell lists it in).
    pub fn polygon_centroid(&mut self, vertices: &[u32]) -> u32 {
        let mut key = vertices.to_vec();
        key.sort_unstable();
        if let Some(&id) = self.polygons.get(&key) {
            return id;
        }
        let id = self.push(mean_of(&key));
        self.polygons.insert(key, id);
        id
    }

    /// A point of one cell only (a body centre).
    pub fn private(&mut self, weights: Vec<(u32, f64)>) -> u32 {
        self.push(weights)
    }

    fn push(&mut self, weights: Vec<(u32, f64)>) -> u32 {
        let id = self.first + self.weights.len();
        self.weights.push(weights);
        // Checked by `assemble` against u32 once the split is done.
        u32::try_from(id).unwrap_or(u32::MAX)
    }

    /// Appends the interpolated tuples of the added points to `values`
    /// (`components` values per point, the file's points first).
    pub fn extend(&self, values: &mut Vec<f64>, components: usize) {
        let k = components.max(1);
        values.reserve(self.weights.len() * k);
        for weights in &self.weights {
            for c in 0..k {
                let v = weights
                    .iter()
                    .map(|&(p, w)| w * values[p as usize * k + c])
                    .sum();
                values.push(v);
            }
        }
    }
}

/// Equal weights over distinct points.
pub fn mean_of(points: &[u32]) -> Vec<(u32, f64)> {
    let w = 1.0 / points.len() as f64;
    points.iter().map(|&p| (p, w)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_points_are_made_once_and_interpolate_every_component() {
        let mut added = AddedPoints::new(3);
        let key = PointKey::QuadCentre([0, 1, 2, 3]);
        let a = added.shared(key, || vec![(0, 0.5), (2, 0.5)]);
        let b = added.shared(key, || unreachable!("made twice"));
        assert_eq!((a, b), (3, 3));
        let c = added.polygon_centroid(&[2, 0, 1]);
        assert_eq!(added.polygon_centroid(&[1, 2, 0]), c);
        assert_eq!(added.private(vec![(1, 1.0)]), 5);
        let mut xy = vec![0.0, 10.0, 2.0, 20.0, 4.0, 60.0];
        added.extend(&mut xy, 2);
        assert_eq!(&xy[6..], &[2.0, 35.0, 2.0, 30.0, 2.0, 20.0]);
    }
}
