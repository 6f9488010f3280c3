//! A regular grid: `dims` points along x, y and z, point `(i, j, k)` at
//! `origin + spacing * (i, j, k)` (spacing may differ per axis), one f32
//! scalar per point, `values[i + nx * (j + ny * k)]` (VTK's order).

use glam::Vec3;
use tetray_mesh::{ScalarField, TetMesh};

use crate::ShearWarpError;

/// A uniform (axis-aligned, possibly anisotropic) grid of point scalars.
#[derive(Debug, Clone, PartialEq)]
pub struct RegularGrid {
    dims: [usize; 3],
    origin: Vec3,
    spacing: Vec3,
    values: Vec<f32>,
}

impl RegularGrid {
    /// Checks and wraps the arrays: at least two points along every axis
    /// (shear-warp composites slabs between slices), finite origin, finite
    /// positive spacing, one finite value per point.
    pub fn new(
        dims: [usize; 3],
        origin: Vec3,
        spacing: Vec3,
        values: Vec<f32>,
    ) -> Result<RegularGrid, ShearWarpError> {
        if dims.iter().any(|&n| n < 2) {
            return Err(ShearWarpError::Dims(dims));
        }
        if !origin.is_finite() {
            return Err(ShearWarpError::Origin(origin.to_array()));
        }
        if !(spacing.is_finite() && spacing.min_element() > 0.0) {
            return Err(ShearWarpError::Spacing(spacing.to_array()));
        }
        let expected = dims
            .iter()
            .try_fold(1usize, |n, &d| n.checked_mul(d))
            .filter(|&n| n < u32::MAX as usize)
            .ok_or(ShearWarpError::TooLarge(dims))?;
        if values.len() != expected {
            return Err(ShearWarpError::ValueCount {
                expected,
                found: values.len(),
            });
        }
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(ShearWarpError::NonFiniteValue {
                index,
                value: values[index],
            });
        }
        Ok(RegularGrid {
            dims,
            origin,
            spacing,
            values,
        })
    }

    /// A grid sampling `f(position)` at every point.
    pub fn from_fn(
        dims: [usize; 3],
        origin: Vec3,
        spacing: Vec3,
        f: impl Fn(Vec3) -> f32,
    ) -> Result<RegularGrid, ShearWarpError> {
        let n = dims.iter().product::<usize>();
        let values = (0..n)
            .map(|p| {
                let (i, j, k) = (
                    p % dims[0],
                    (p / dims[0]) % dims[1].max(1),
                    p / (dims[0] * dims[1]).max(1),
                );
                f(origin + spacing * Vec3::new(i as f32, j as f32, k as f32))
            })
            .collect();
        RegularGrid::new(dims, origin, spacing, values)
    }

    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    pub fn spacing(&self) -> Vec3 {
        self.spacing
    }

    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// The value at point `(i, j, k)` (indices in range).
    #[inline]
    pub fn value(&self, i: usize, j: usize, k: usize) -> f32 {
        self.values[i + self.dims[0] * (j + self.dims[1] * k)]
    }

    /// Smallest and largest corner.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let extent = Vec3::new(
            (self.dims[0] - 1) as f32,
            (self.dims[1] - 1) as f32,
            (self.dims[2] - 1) as f32,
        );
        (self.origin, self.origin + self.spacing * extent)
    }

    /// Smallest and largest value.
    pub fn value_range(&self) -> (f32, f32) {
        self.values
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// The same grid as tetrahedra (5 per cell, the split the mesh readers
    /// use for structured data) with the values as field `name`: what the
    /// tetrahedral renderers see of it.
    pub fn to_tet_mesh(&self, name: &str) -> TetMesh {
        let [nx, ny, nz] = self.dims;
        let mut points = Vec::with_capacity(nx * ny * nz);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let index = Vec3::new(i as f32, j as f32, k as f32);
                    points.push(self.origin + self.spacing * index);
                }
            }
        }
        TetMesh {
            points,
            tets: tetray_mesh::structured::structured_tets(self.dims, 1),
            fields: vec![ScalarField {
                name: name.to_string(),
                values: self.values.clone(),
            }],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_input() {
        let ok = |dims, spacing: Vec3, n| {
            RegularGrid::new(dims, Vec3::ZERO, spacing, vec![0.0; n]).map(|_| ())
        };
        assert!(ok([2, 2, 2], Vec3::ONE, 8).is_ok());
        assert!(matches!(
            ok([1, 2, 2], Vec3::ONE, 4),
            Err(ShearWarpError::Dims(_))
        ));
        assert!(matches!(
            ok([2, 2, 2], Vec3::new(1.0, 0.0, 1.0), 8),
            Err(ShearWarpError::Spacing(_))
        ));
        assert!(matches!(
            ok([2, 2, 2], Vec3::ONE, 7),
            Err(ShearWarpError::ValueCount { .. })
        ));
        let nan = RegularGrid::new([2, 2, 2], Vec3::ZERO, Vec3::ONE, vec![f32::NAN; 8]);
        assert!(matches!(nan, Err(ShearWarpError::NonFiniteValue { .. })));
    }

    #[test]
    fn from_fn_orders_like_vtk() {
        let g = RegularGrid::from_fn([3, 2, 2], Vec3::ONE, Vec3::new(1.0, 2.0, 4.0), |p| {
            p.x + 10.0 * p.y + 100.0 * p.z
        })
        .unwrap();
        assert_eq!(g.value(2, 1, 1), 3.0 + 30.0 + 500.0);
        assert_eq!(g.bounds().1, Vec3::new(3.0, 3.0, 5.0));
        assert_eq!(g.to_tet_mesh("s").tets.len(), 2 * 5);
    }
}
