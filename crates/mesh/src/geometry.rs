//! Geometric helpers on [`TetMesh`]: bounds, volumes, orientation.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::{FACE_VERTICES, ScalarField, TetMesh};

/// A tetrahedron is degenerate when its smallest height is at most
/// `DEGENERATE_HEIGHT_ULPS` f32 ulps (`f32::EPSILON` relative) of the
/// largest coordinate magnitude among its corners.
///
/// Points are stored as f32: each coordinate carries a rounding error of
/// half an ulp of its magnitude, and a ray walk's plane tests in f32 add a
/// few ulps more. Once a vertex is that close to the plane of its opposite
/// face the sign of the volume, and every entry/exit decision inside the
/// tetrahedron, is rounding noise; 16 ulps leaves a margin above that. The
/// test is on height, not on `volume / edge^3`, so thin but well-resolved
/// cells (CFD boundary layers, aspect ratios in the thousands) pass, while
/// a tetrahedron with two coincident points (volume exactly 0) never does.
pub const DEGENERATE_HEIGHT_ULPS: f64 = 16.0;

/// The origin a mesh read from a file is stored relative to: the centre of
/// its bounds `lo..hi` (in f64) when the mesh lies far from the origin,
/// else zero.
///
/// Points are stored as f32, with 24 bits relative to their magnitude: a
/// mesh of 10 m cells at 7e6 m (a reservoir in UTM coordinates) keeps
/// 0.5 m of resolution, and its thin cells look flat. Stored relative to
/// its centre, its coordinates are at most its half extent and keep all 24
/// bits for the geometry. Meshes whose largest coordinate is at most four
/// times their half extent (those around the origin, where centring would
/// gain less than 2 bits) keep their coordinates as given.
pub fn centring_origin(lo: DVec3, hi: DVec3) -> DVec3 {
    let centre = (lo + hi) * 0.5;
    let half = ((hi - lo) * 0.5).max_element();
    let largest = lo.abs().max(hi.abs()).max_element();
    if centre.is_finite() && largest > 4.0 * half {
        centre
    } else {
        DVec3::ZERO
    }
}

/// Bounds in f64 of points given as `x, y, z` triples; `None` when there
/// are none.
pub fn bounds_f64(points: impl Iterator<Item = DVec3>) -> Option<(DVec3, DVec3)> {
    points.fold(None, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}

/// Size and flatness of one tetrahedron, computed in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TetShape {
    /// Six times the signed volume: `(p1 - p0) . ((p2 - p0) x (p3 - p0))`.
    pub volume6: f64,
    /// Twice the area of the largest face.
    pub max_face_area2: f64,
    /// Largest absolute coordinate of the four corners.
    pub max_coordinate: f64,
}

impl TetShape {
    /// The smallest height: from a vertex to the plane of the largest face
    /// (`3 V / area`); 0 when all points coincide.
    pub fn min_height(&self) -> f64 {
        if self.max_face_area2 > 0.0 {
            self.volume6.abs() / self.max_face_area2
        } else {
            0.0
        }
    }

    /// The height at or below which the tetrahedron is degenerate (see
    /// [`DEGENERATE_HEIGHT_ULPS`]).
    pub fn height_threshold(&self) -> f64 {
        DEGENERATE_HEIGHT_ULPS * f64::from(f32::EPSILON) * self.max_coordinate
    }

    /// Whether the tetrahedron is too flat to walk (see
    /// [`DEGENERATE_HEIGHT_ULPS`]). Zero volume is always degenerate.
    pub fn is_degenerate(&self) -> bool {
        self.volume6 == 0.0 || self.min_height() <= self.height_threshold()
    }
}

/// Shape of the tetrahedron with corners `p`.
pub fn tet_shape(p: [Vec3; 4]) -> TetShape {
    let q = p.map(|v| v.as_dvec3());
    let volume6 = tet_volume6(p);
    // One square root of the largest square: the same bits as the largest
    // of four roots (a correctly rounded root is monotone).
    let max_face_area2 = FACE_VERTICES
        .iter()
        .map(|&[a, b, c]| (q[b] - q[a]).cross(q[c] - q[a]).length_squared())
        .fold(0.0, f64::max)
        .sqrt();
    let max_coordinate = q.iter().map(|v| v.abs().max_element()).fold(0.0, f64::max);
    TetShape {
        volume6,
        max_face_area2,
        max_coordinate,
    }
}

/// Six times the signed volume of the tetrahedron with corners `p`, in f64
/// (the [`TetShape::volume6`] of [`tet_shape`], alone). Swapping two
/// corners negates it exactly: the cross product's components and the dot
/// product are sums whose rounding is symmetric in sign.
pub fn tet_volume6(p: [Vec3; 4]) -> f64 {
    let q = p.map(|v| v.as_dvec3());
    let (e1, e2, e3) = (q[1] - q[0], q[2] - q[0], q[3] - q[0]);
    e1.dot(e2.cross(e3))
}

impl TetMesh {
    /// Axis-aligned bounds `(min, max)` of all points; `(0, 0)` for a mesh
    /// without points.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        if self.points.is_empty() {
            return (Vec3::ZERO, Vec3::ZERO);
        }
        self.points.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
    }

    /// The scalar field called `name`.
    pub fn field(&self, name: &str) -> Option<&ScalarField> {
        self.fields.iter().find(|f| f.name == name)
    }

    /// The four corner positions of tetrahedron `tet`.
    ///
    /// # Panics
    /// If `tet` or one of its point indices is out of range; call
    /// [`crate::validate`] on untrusted meshes first.
    pub fn tet_points(&self, tet: usize) -> [Vec3; 4] {
        self.tets[tet].map(|i| self.points[i as usize])
    }

    /// Signed volume of tetrahedron `tet` (positive when positively
    /// oriented), computed in f64.
    ///
    /// # Panics
    /// As [`TetMesh::tet_points`].
    pub fn signed_volume(&self, tet: usize) -> f64 {
        tet_shape(self.tet_points(tet)).volume6 / 6.0
    }

    /// Makes every tetrahedron positively oriented by swapping its last two
    /// vertices where the signed volume is negative; returns how many were
    /// swapped. Tetrahedra with a point index out of range, or with a volume
    /// of exactly zero, are left alone (validation reports them).
    pub fn orient(&mut self) -> usize {
        let points = &self.points;
        self.tets
            .par_iter_mut()
            .map(|tet| {
                let mut corners = [Vec3::ZERO; 4];
                for (c, &i) in corners.iter_mut().zip(tet.iter()) {
                    match points.get(i as usize) {
                        Some(&p) => *c = p,
                        None => return 0,
                    }
                }
                if tet_volume6(corners) < 0.0 {
                    tet.swap(2, 3);
                    1
                } else {
                    0
                }
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_tet() -> TetMesh {
        TetMesh {
            points: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z],
            tets: vec![[0, 1, 2, 3]],
            fields: vec![ScalarField {
                name: "s".into(),
                values: vec![0.0, 1.0, 2.0, 3.0],
            }],
        }
    }

    #[test]
    fn volume_bounds_field() {
        let mesh = unit_tet();
        // Exact: 1/6 is computed from small integers in f64.
        assert_eq!(mesh.signed_volume(0), 1.0 / 6.0);
        assert_eq!(mesh.bounds(), (Vec3::ZERO, Vec3::ONE));
        assert_eq!(mesh.field("s").map(|f| f.values[3]), Some(3.0));
        assert!(mesh.field("t").is_none());
        assert_eq!(TetMesh::default().bounds(), (Vec3::ZERO, Vec3::ZERO));
    }

    #[test]
    fn orient_swaps_inverted_only() {
        let mut mesh = unit_tet();
        mesh.tets.push([0, 2, 1, 3]);
        assert_eq!(mesh.orient(), 1);
        assert_eq!(mesh.tets[1], [0, 2, 3, 1]);
        assert!(mesh.signed_volume(1) > 0.0);
        assert_eq!(mesh.orient(), 0);
    }

    #[test]
    fn degeneracy_follows_f32_resolution() {
        for scale in [1e-3_f32, 1.0, 1e4] {
            let tet =
                |h: f32| [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.5, 0.5, h)].map(|p| p * scale);
            // Height 1e-6 is below 16 ulps (1.9e-6) of coordinates near 1.
            assert!(tet_shape(tet(1e-6)).is_degenerate(), "scale {scale}");
            assert!(!tet_shape(tet(1e-5)).is_degenerate(), "scale {scale}");
        }
        // A sliver 1000 times longer than thick, well above the rounding.
        let long = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.0, 1e-3, 0.0),
            Vec3::new(0.5, 0.0, 1e-3),
        ];
        assert!(!tet_shape(long).is_degenerate());
        // The same shape far from the origin, where f32 cannot resolve it.
        let far = long.map(|p| p + Vec3::splat(1e4));
        assert!(tet_shape(far).is_degenerate());
        assert!(tet_shape([Vec3::ONE; 4]).is_degenerate());
        assert!(tet_shape([Vec3::ZERO, Vec3::ZERO, Vec3::X, Vec3::Y]).is_degenerate());
    }

    /// The largest face's doubled area, one root of the largest square,
    /// is bit for bit the largest of the four faces' roots.
    #[test]
    fn largest_face_area_is_the_largest_root() {
        let mut state = 0x853c_49e6_748f_ea9bu64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u32 << 24) as f32 * 8.0 - 4.0
        };
        for _ in 0..10_000 {
            let p: [Vec3; 4] = std::array::from_fn(|_| Vec3::new(next(), next(), next()));
            let q = p.map(|v| v.as_dvec3());
            let want = FACE_VERTICES
                .iter()
                .map(|&[a, b, c]| (q[b] - q[a]).cross(q[c] - q[a]).length())
                .fold(0.0, f64::max);
            assert_eq!(tet_shape(p).max_face_area2.to_bits(), want.to_bits());
        }
    }
}
