//! A mesh made ready for projection, once per mesh and independent of the
//! view: positively oriented tetrahedra (so one index pattern winds every
//! face outward), face neighbours and outward face planes for MPVO,
//! centroids for the depth sort, and scalar gradients for ordering the
//! pieces of adaptive transfer-function sampling.

use glam::{DVec3, Vec3};
use rayon::prelude::*;
use tetray_scene::Scene;

use crate::ProjectError;

/// Local vertices of face `j`, the face opposite vertex `j`, wound
/// counter-clockwise seen from outside a positively oriented tetrahedron
/// (tetray_mesh::FACE_VERTICES, the walk's numbering).
pub const FACE_VERTS: [[usize; 3]; 4] = tetray_mesh::FACE_VERTICES;

/// What the projection reads of a mesh.
#[derive(Debug, Clone)]
pub struct ProjectScene {
    /// Per point: position and active scalar.
    pub points: Vec<[f32; 4]>,
    /// Point indices, positively oriented.
    pub tets: Vec<[u32; 4]>,
    /// Across face `j` (opposite vertex `j`): the neighbouring tetrahedron,
    /// or [`tetray_mesh::NO_NEIGHBOR`].
    pub neighbors: Vec<[u32; 4]>,
    /// Outward plane of face `j`: unit normal and offset (`n . x = offset`
    /// on the face). Both tetrahedra of a shared face hold the same plane
    /// negated, bit for bit, so their side tests can never both say
    /// "behind".
    pub planes: Vec<[[f32; 4]; 4]>,
    pub centroids: Vec<Vec3>,
    /// Scalar gradient (xyz) and the scalar at the centroid (w).
    pub gradients: Vec<[f32; 4]>,
    /// Per tetrahedron: smallest and largest vertex scalar.
    pub scalar_ranges: Vec<[f32; 2]>,
    pub bounds: (Vec3, Vec3),
}

impl ProjectScene {
    pub fn new(scene: &Scene) -> Result<ProjectScene, ProjectError> {
        let points = scene.point_records().to_vec();
        let (cells, neighbors) = (&scene.mesh.tets, &scene.topology.neighbors);
        if cells.is_empty() {
            return Err(ProjectError::Empty);
        }
        let position = |v: u32| {
            let p = points[v as usize];
            DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
        };
        let oriented: Vec<([u32; 4], [u32; 4])> = cells
            .par_iter()
            .zip(neighbors)
            .map(|(&verts, &next)| {
                let (mut verts, mut next) = (verts, next);
                let [a, b, c, d] = verts.map(position);
                if (b - a).dot((c - a).cross(d - a)) < 0.0 {
                    // Swapping vertices 2 and 3 swaps the faces opposite them.
                    verts.swap(2, 3);
                    next.swap(2, 3);
                }
                (verts, next)
            })
            .collect();
        let (tets, neighbors): (Vec<_>, Vec<_>) = oriented.into_iter().unzip();
        let planes = tets
            .par_iter()
            .map(|t| std::array::from_fn(|j| outward_plane(&points, t, j)))
            .collect();
        let centroids = tets
            .par_iter()
            .map(|t| (t.map(position).iter().sum::<DVec3>() * 0.25).as_vec3())
            .collect::<Vec<_>>();
        let gradients = tets.par_iter().map(|t| gradient(&points, t)).collect();
        let scalar_ranges = tets
            .par_iter()
            .map(|t| {
                let s = t.map(|v| points[v as usize][3]);
                [
                    s[0].min(s[1]).min(s[2].min(s[3])),
                    s[0].max(s[1]).max(s[2].max(s[3])),
                ]
            })
            .collect();
        Ok(ProjectScene {
            points,
            tets,
            neighbors,
            planes,
            centroids,
            gradients,
            scalar_ranges,
            bounds: scene.bounds(),
        })
    }

    pub fn tet_count(&self) -> usize {
        self.tets.len()
    }
}

/// The plane of face `j` of `tet`, from its points in ascending index order
/// (so the neighbour across computes the very same numbers), turned to
/// point away from the tetrahedron's fourth vertex.
fn outward_plane(points: &[[f32; 4]], tet: &[u32; 4], j: usize) -> [f32; 4] {
    let mut face = FACE_VERTS[j].map(|v| tet[v]);
    face.sort_unstable();
    let p = |v: u32| {
        let q = points[v as usize];
        DVec3::new(f64::from(q[0]), f64::from(q[1]), f64::from(q[2]))
    };
    let [a, b, c] = face.map(p);
    let normal = (b - a).cross(c - a).normalize_or_zero();
    let offset = normal.dot(a);
    let mut plane = [
        normal.x as f32,
        normal.y as f32,
        normal.z as f32,
        offset as f32,
    ];
    if normal.dot(p(tet[j])) - offset > 0.0 {
        plane = plane.map(|x| -x);
    }
    plane
}

/// The linear field's gradient (zero for a flat tetrahedron) and its value
/// at the centroid.
fn gradient(points: &[[f32; 4]], tet: &[u32; 4]) -> [f32; 4] {
    let q = tet.map(|v| {
        let p = points[v as usize];
        (
            DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])),
            f64::from(p[3]),
        )
    });
    let (e1, e2, e3) = (q[1].0 - q[0].0, q[2].0 - q[0].0, q[3].0 - q[0].0);
    let det = e1.dot(e2.cross(e3));
    let g = if det.abs() > 0.0 {
        ((q[1].1 - q[0].1) * e2.cross(e3)
            + (q[2].1 - q[0].1) * e3.cross(e1)
            + (q[3].1 - q[0].1) * e1.cross(e2))
            / det
    } else {
        DVec3::ZERO
    };
    let mean = (q[0].1 + q[1].1 + q[2].1 + q[3].1) * 0.25;
    let g = if g.is_finite() { g } else { DVec3::ZERO };
    [g.x as f32, g.y as f32, g.z as f32, mean as f32]
}
