//! A mesh made ready for ray casting: topology, boundary BVH, the active
//! scalar field, and a compact copy of what the walk reads per step.
use glam::Vec3;
use tetray_boundary_bvh::{BoundaryBvh, BuildPreset, BvhError};
use tetray_mesh::{
    FACE_VERTICES, LoadedMesh, NO_NEIGHBOR, ScalarField, TetMesh, Topology, first_position,
};

use crate::order::{Reorder, inverse, morton_reorder};
use crate::overlaps::Overlaps;
use crate::records::{FINAL_EXIT, WalkTet, check_neighbors_in_range, vertex_rank, walk_tets};

/// Why a [`Scene`] could not be made from a mesh.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    #[error("the mesh has no point field {name:?} (fields: {available})")]
    UnknownField { name: String, available: String },
    #[error("field {name:?} has {values} values for {points} points")]
    FieldLength {
        name: String,
        values: usize,
        points: usize,
    },
    #[error("field {name:?} is not finite at point {point} ({value})")]
    NonFiniteScalar {
        name: String,
        point: usize,
        value: f32,
    },
    #[error("point {point} is not finite: {coords:?}")]
    NonFinitePoint { point: usize, coords: [f32; 3] },
    #[error("tetrahedron {tet} refers to point {point}, but the mesh has {points} points")]
    PointOutOfRange {
        tet: usize,
        point: u32,
        points: usize,
    },
    #[error("the topology has {topology} tetrahedra, the mesh {mesh}")]
    TopologyMismatch { topology: usize, mesh: usize },
    #[error("the mesh has {0} tetrahedra; the walk indexes at most 2^30 - 1")]
    TooManyTets(usize),
    #[error("the mesh has {0} points; the walk indexes at most 2^31")]
    TooManyPoints(usize),
    #[error(
        "face {face} of tetrahedron {tet} has neighbour {neighbor}, which does not share its three points"
    )]
    BadNeighbor {
        tet: usize,
        face: usize,
        neighbor: u32,
    },
    #[error("boundary face {face} does not match face {local_face} of tetrahedron {tet}")]
    BadBoundaryFace {
        face: usize,
        tet: u32,
        local_face: u8,
    },
    #[error("the mesh has no tetrahedra")]
    Empty,
    #[error(transparent)]
    Bvh(#[from] BvhError),
}

/// A mesh ready to be ray cast with one active scalar field.
#[derive(Clone)]
pub struct Scene {
    pub mesh: TetMesh,
    pub topology: Topology,
    pub bvh: BoundaryBvh,
    /// The active field's name and values (one per point).
    pub field: String,
    pub scalar: Vec<f32>,
    walk: Vec<WalkTet>,
    /// Per point: position and active scalar, read together.
    points: Vec<[f32; 4]>,
    bounds: (Vec3, Vec3),
    /// The renumbering applied to the input mesh, if any.
    order: Option<Reorder>,
    /// The cells left out of the walk, composited in their holes.
    overlaps: Overlaps,
}

/// How [`Scene::new_with_order`] numbers points and tetrahedra.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CellOrder {
    /// As given (the file's numbering).
    File,
    /// Along a Morton curve ([`crate::order`]): rays walk through
    /// tetrahedra and points close together in memory. The default.
    #[default]
    Morton,
}

impl Scene {
    /// Validates what the walk relies on (indices in range, finite data,
    /// face neighbours sharing their face, boundary faces matching their
    /// tetrahedra), so that rendering cannot fail on the mesh, and builds
    /// the boundary BVH with `preset`.
    ///
    /// Points and tetrahedra are renumbered along a Morton curve
    /// ([`CellOrder::Morton`]); [`Scene::input_tet`] and
    /// [`Scene::input_point`] map the scene's ids back to the input's.
    /// Errors name input ids (validation runs first).
    pub fn new(
        mesh: TetMesh,
        topology: Topology,
        field: &str,
        preset: BuildPreset,
    ) -> Result<Scene, SceneError> {
        Scene::new_with_order(mesh, topology, field, preset, CellOrder::default())
    }

    /// [`Scene::new`] with the numbering chosen.
    pub fn new_with_order(
        mesh: TetMesh,
        topology: Topology,
        field: &str,
        preset: BuildPreset,
        cell_order: CellOrder,
    ) -> Result<Scene, SceneError> {
        let scalar = active_field(&mesh, field)?;
        if mesh.tets.is_empty() {
            return Err(SceneError::Empty);
        }
        check_sizes(mesh.tets.len(), mesh.points.len())?;
        if topology.neighbors.len() != mesh.tets.len() {
            return Err(SceneError::TopologyMismatch {
                topology: topology.neighbors.len(),
                mesh: mesh.tets.len(),
            });
        }
        if let Some(point) = first_position(&mesh.points, |p| !p.is_finite()) {
            return Err(SceneError::NonFinitePoint {
                point,
                coords: mesh.points[point].to_array(),
            });
        }
        check_points_in_range(&mesh.tets, mesh.points.len())?;
        // With the Morton order the records are built (and checked) after
        // the renumbering, which needs only the neighbours in range; an
        // error names the input's ids.
        if let CellOrder::Morton = cell_order {
            check_neighbors_in_range(&topology)?;
        }
        check_boundary_faces(&mesh, &topology)?;
        let (mut mesh, mut topology, mut scalar) = (mesh, topology, scalar);
        let order = match cell_order {
            CellOrder::File => None,
            CellOrder::Morton => Some(morton_reorder(&mut mesh, &mut topology, &mut scalar)),
        };
        // A boundary face's points in its tetrahedron's order (a rotation
        // of them was checked above): the CPU walk enters by the
        // tetrahedron, the GPU kernel by the points the BVH tested, and
        // both then cross the face with the same bits.
        for bf in &mut topology.boundary_faces {
            let tet = mesh.tets[bf.tet as usize];
            bf.vertices = FACE_VERTICES[usize::from(bf.local_face)].map(|v| tet[v]);
        }
        // The BVH build is serial (obvhs): it runs beside the parallel
        // walk records.
        let (walk, bvh) = rayon::join(
            || walk_tets(&mesh, &topology, order.as_ref()),
            || BoundaryBvh::build(&mesh, &topology, preset),
        );
        let (mut walk, bvh) = (walk?, bvh?);
        for (face, is_final) in topology.boundary_faces.iter().zip(bvh.final_exit_faces()) {
            if is_final {
                let verts = mesh.tets[face.tet as usize];
                let rank = vertex_rank(verts, verts[usize::from(face.local_face)]);
                walk[face.tet as usize].next[rank] = FINAL_EXIT;
            }
        }
        let points = mesh
            .points
            .iter()
            .zip(&scalar)
            .map(|(p, &s)| [p.x, p.y, p.z, s])
            .collect();
        let bounds = mesh.bounds();
        Ok(Scene {
            mesh,
            topology,
            bvh,
            field: field.to_string(),
            scalar,
            walk,
            points,
            bounds,
            order,
            overlaps: Overlaps::default(),
        })
    }

    /// [`Scene::new`] on a mesh loaded by `tetray_io::load` / `prepare`
    /// (its load report is dropped; keep it beforehand if needed).
    pub fn from_loaded(
        loaded: LoadedMesh,
        field: &str,
        preset: BuildPreset,
    ) -> Result<Scene, SceneError> {
        let mut scene = Scene::new(loaded.mesh, loaded.topology, field, preset)?;
        scene.set_overlaps(&loaded.overlaps)?;
        Ok(scene)
    }

    /// Takes the tetrahedra of the cells left out of the walk
    /// ([`LoadedMesh::overlaps`], over the input's points), to be
    /// composited in the holes they leave (see [`crate::overlaps`]).
    ///
    /// # Errors
    /// [`SceneError::PointOutOfRange`] (its `tet` the index in `tets`).
    pub fn set_overlaps(&mut self, tets: &[[u32; 4]]) -> Result<(), SceneError> {
        check_points_in_range(tets, self.points.len())?;
        let renumbered = match &self.order {
            None => tets.to_vec(),
            Some(order) => {
                let point_to = inverse(&order.point_from);
                tets.iter()
                    .map(|t| t.map(|v| point_to[v as usize]))
                    .collect()
            }
        };
        self.overlaps = Overlaps::new(renumbered, &self.points);
        Ok(())
    }

    /// The tetrahedra of the cells left out of the walk.
    pub fn overlaps(&self) -> &Overlaps {
        &self.overlaps
    }

    /// The same scene with another point field of its mesh active: the
    /// topology, the BVH and the walk records are kept, nothing is rebuilt
    /// (the fields were renumbered with the points). Errors name the
    /// input's point ids.
    pub fn with_field(&self, field: &str) -> Result<Scene, SceneError> {
        self.with_mesh(self.mesh.clone(), field)
    }

    /// This scene's topology, BVH and walk records over `mesh` (this
    /// scene's points and tetrahedra, perhaps other fields), with `field`
    /// active.
    fn with_mesh(&self, mesh: TetMesh, field: &str) -> Result<Scene, SceneError> {
        let scalar = active_field(&mesh, field).map_err(|e| self.in_input_numbering(e))?;
        let points = mesh
            .points
            .iter()
            .zip(&scalar)
            .map(|(p, &s)| [p.x, p.y, p.z, s])
            .collect();
        Ok(Scene {
            mesh,
            topology: self.topology.clone(),
            bvh: self.bvh.clone(),
            field: field.to_string(),
            scalar,
            walk: self.walk.clone(),
            points,
            bounds: self.bounds,
            order: self.order.clone(),
            overlaps: self.overlaps.clone(),
        })
    }

    /// Takes `fields`, the point fields of another time step of the same
    /// points and tetrahedra, in the input's numbering (one value per
    /// point as read): the fields are renumbered as the points were and
    /// the active one taken again, by name; the topology, the BVH and the
    /// walk records stay. The caller vouches that the geometry is this
    /// scene's (`tetray_engine::TimeSteps` compares it as read). On an
    /// error the scene is unchanged.
    pub fn set_input_fields(&mut self, fields: Vec<ScalarField>) -> Result<(), SceneError> {
        let n = self.mesh.points.len();
        if let Some(f) = fields.iter().find(|f| f.values.len() != n) {
            return Err(SceneError::FieldLength {
                name: f.name.clone(),
                values: f.values.len(),
                points: n,
            });
        }
        let fields: Vec<ScalarField> = match &self.order {
            None => fields,
            Some(order) => fields
                .into_iter()
                .map(|f| ScalarField {
                    values: order
                        .point_from
                        .iter()
                        .map(|&p| f.values[p as usize])
                        .collect(),
                    name: f.name,
                })
                .collect(),
        };
        let scalar =
            active_values(&fields, n, &self.field).map_err(|e| self.in_input_numbering(e))?;
        for (record, &s) in self.points.iter_mut().zip(&scalar) {
            record[3] = s;
        }
        self.scalar = scalar;
        self.mesh.fields = fields;
        Ok(())
    }

    /// `error` with the point it names (in the scene's numbering) given in
    /// the input's.
    fn in_input_numbering(&self, error: SceneError) -> SceneError {
        match error {
            SceneError::NonFiniteScalar { name, point, value } => SceneError::NonFiniteScalar {
                name,
                point: self.input_point(point as u32) as usize,
                value,
            },
            other => other,
        }
    }

    /// The renumbering applied to the input (`None`: input order).
    pub fn reorder(&self) -> Option<&Reorder> {
        self.order.as_ref()
    }

    /// The input's (file's) id of the scene's tetrahedron `tet`.
    pub fn input_tet(&self, tet: u32) -> u32 {
        self.order
            .as_ref()
            .map_or(tet, |o| o.tet_from[tet as usize])
    }

    /// The input's (file's) id of the scene's point `point`.
    pub fn input_point(&self, point: u32) -> u32 {
        self.order
            .as_ref()
            .map_or(point, |o| o.point_from[point as usize])
    }

    /// Axis-aligned bounds of the mesh points.
    #[inline]
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.bounds
    }

    /// Number of tetrahedra.
    pub fn tet_count(&self) -> usize {
        self.walk.len()
    }

    /// What the walk reads per tetrahedron ([`WalkTet`]): the XOR of its
    /// points and its neighbours by the rank of the vertex opposite each
    /// (or a boundary marker, `NO_NEIGHBOR`, [`FINAL_EXIT`]). The GPU
    /// kernel uploads this.
    #[inline]
    pub fn walk_records(&self) -> &[WalkTet] {
        &self.walk
    }

    /// Per point: position and active scalar, `[x, y, z, s]`.
    #[inline]
    pub fn point_records(&self) -> &[[f32; 4]] {
        &self.points
    }
}

/// Checks that the walk can index `tets` tetrahedra and `points` points.
///
/// # Errors
/// [`SceneError::TooManyTets`] from 2^30 tetrahedra on (the limit of the
/// face-neighbour graph, `tetray_mesh::Topology::build`),
/// [`SceneError::TooManyPoints`] past 2^31 points (point indices below
/// 2^31 rank with one signed compare).
fn check_sizes(tets: usize, points: usize) -> Result<(), SceneError> {
    if tets >= 1 << 30 {
        return Err(SceneError::TooManyTets(tets));
    }
    if points > 1 << 31 {
        return Err(SceneError::TooManyPoints(points));
    }
    Ok(())
}

/// Checks every tetrahedron of `tets` refers to one of `points` points.
///
/// # Errors
/// [`SceneError::PointOutOfRange`] for the first that does not.
fn check_points_in_range(tets: &[[u32; 4]], points: usize) -> Result<(), SceneError> {
    let out_of_range = |verts: &[u32; 4]| verts.iter().copied().find(|&v| v as usize >= points);
    match first_position(tets, |v| out_of_range(v).is_some()) {
        Some(tet) => Err(SceneError::PointOutOfRange {
            tet,
            point: out_of_range(&tets[tet]).unwrap_or_default(),
            points,
        }),
        None => Ok(()),
    }
}

fn active_field(mesh: &TetMesh, name: &str) -> Result<Vec<f32>, SceneError> {
    active_values(&mesh.fields, mesh.points.len(), name)
}

/// The values of field `name` among `fields` of a mesh of `points` points,
/// checked: present, one per point, finite.
fn active_values(
    fields: &[ScalarField],
    points: usize,
    name: &str,
) -> Result<Vec<f32>, SceneError> {
    let field = fields
        .iter()
        .find(|f| f.name == name)
        .ok_or_else(|| SceneError::UnknownField {
            name: name.to_string(),
            available: fields
                .iter()
                .map(|f| format!("{:?}", f.name))
                .collect::<Vec<_>>()
                .join(", "),
        })?;
    if field.values.len() != points {
        return Err(SceneError::FieldLength {
            name: name.to_string(),
            values: field.values.len(),
            points,
        });
    }
    if let Some(point) = first_position(&field.values, |v| !v.is_finite()) {
        return Err(SceneError::NonFiniteScalar {
            name: name.to_string(),
            point,
            value: field.values[point],
        });
    }
    Ok(field.values.clone())
}

/// The walk starts from a boundary face's tetrahedron and local face, and
/// trusts that the BVH tested the same three points in the same cyclic
/// order.
fn check_boundary_faces(mesh: &TetMesh, topology: &Topology) -> Result<(), SceneError> {
    for (face, bf) in topology.boundary_faces.iter().enumerate() {
        let bad = SceneError::BadBoundaryFace {
            face,
            tet: bf.tet,
            local_face: bf.local_face,
        };
        let (Some(verts), Some(local)) = (
            mesh.tets.get(bf.tet as usize),
            FACE_VERTICES.get(usize::from(bf.local_face)),
        ) else {
            return Err(bad);
        };
        let own = local.map(|v| verts[v]);
        let rotation = |r: usize| [own[r % 3], own[(r + 1) % 3], own[(r + 2) % 3]];
        if !(0..3).any(|r| rotation(r) == bf.vertices) {
            return Err(bad);
        }
        let neighbor = topology.neighbors[bf.tet as usize][usize::from(bf.local_face)];
        if neighbor != NO_NEIGHBOR {
            return Err(bad);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, jittered_box};

    /// The largest mesh the walk indexes passes, one more tetrahedron or
    /// point is refused with its count (no mesh that large is built here).
    #[test]
    fn sizes_past_the_walk_indices_are_refused() {
        let (tets, points) = ((1 << 30) - 1, 1 << 31);
        assert!(check_sizes(tets, points).is_ok());
        assert!(matches!(
            check_sizes(tets + 1, points),
            Err(SceneError::TooManyTets(n)) if n == 1 << 30
        ));
        assert!(matches!(
            check_sizes(tets, points + 1),
            Err(SceneError::TooManyPoints(n)) if n == points + 1
        ));
        let message = check_sizes(0, points + 1).unwrap_err().to_string();
        assert!(message.contains("2147483649 points"), "{message}");
    }

    /// Switching the active field gives the scene a fresh build would.
    #[test]
    fn another_field_is_the_scene_built_for_it() {
        let mut mesh =
            jittered_box(Vec3::ZERO, Vec3::ONE, [3, 2, 2], 0.2, 7, CellSplit::Six).expect("a mesh");
        let linear = |offset, gradient| ScalarSpec::Linear { offset, gradient };
        add_field(&mut mesh, "x", linear(0.0, Vec3::X));
        add_field(&mut mesh, "yz", linear(0.5, Vec3::new(0.0, 2.0, -1.0)));
        let topology = Topology::build(&mesh).expect("topology");
        let x =
            Scene::new(mesh.clone(), topology.clone(), "x", BuildPreset::default()).expect("scene");
        let yz = Scene::new(mesh, topology, "yz", BuildPreset::default()).expect("scene");
        let switched = x.with_field("yz").expect("the field exists");
        assert_eq!(switched.field, "yz");
        assert_eq!(switched.scalar, yz.scalar);
        assert_eq!(switched.point_records(), yz.point_records());
        assert_eq!(switched.walk_records(), yz.walk_records());
        assert!(matches!(
            x.with_field("nope"),
            Err(SceneError::UnknownField { .. })
        ));
    }
}
