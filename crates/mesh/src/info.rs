//! A human-readable summary of a loaded mesh (`tetray info`).

use std::fmt;

use glam::{DVec3, Vec3};

use crate::cells::PieceCounts;
use crate::{BoundaryFace, ElementBlock, ExcludedCells, LoadedMesh};

/// Range of one scalar field.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldRange {
    pub name: String,
    pub min: f32,
    pub max: f32,
}

/// Counts, bounds, scalar ranges and findings of a loaded mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSummary {
    pub format: &'static str,
    pub points: usize,
    pub tets: usize,
    pub boundary_faces: usize,
    /// Interior faces (each shared by two tetrahedra).
    pub interior_faces: usize,
    pub components: usize,
    pub bounds: (Vec3, Vec3),
    pub fields: Vec<FieldRange>,
    pub inverted_fixed: usize,
    pub degenerate_dropped: usize,
    pub cells_split: usize,
    pub tets_from_split: usize,
    /// Pieces joined, points welded, ghost and blanked cells dropped.
    pub pieces: PieceCounts,
    /// The stored points are relative to this origin (file coordinates =
    /// origin + point).
    pub origin: DVec3,
    /// Cells left out of the walk.
    pub excluded: ExcludedCells,
    /// Hanging nodes, pairs of faces split differently, and the unmatched
    /// faces made boundary.
    pub hanging_nodes: usize,
    pub folded_face_pairs: usize,
    pub nonconforming_faces: Vec<BoundaryFace>,
    pub warnings: Vec<String>,
    /// The stored times (Exodus II), one per time step.
    pub times: Vec<f64>,
    /// The time step read.
    pub time_step: Option<usize>,
    /// The file's element blocks (Exodus II).
    pub blocks: Vec<ElementBlock>,
}

impl MeshSummary {
    pub fn new(loaded: &LoadedMesh) -> MeshSummary {
        let LoadedMesh {
            mesh,
            topology,
            report,
            ..
        } = loaded;
        let fields = mesh
            .fields
            .iter()
            .map(|f| {
                let (min, max) = f
                    .values
                    .iter()
                    .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
                        (lo.min(v), hi.max(v))
                    });
                FieldRange {
                    name: f.name.clone(),
                    min,
                    max,
                }
            })
            .collect();
        let boundary_faces = topology.boundary_faces.len();
        MeshSummary {
            format: report.format,
            points: mesh.points.len(),
            tets: mesh.tets.len(),
            boundary_faces,
            interior_faces: (4 * mesh.tets.len() - boundary_faces) / 2,
            components: report.validation.components,
            bounds: mesh.bounds(),
            fields,
            inverted_fixed: report.inverted_fixed,
            degenerate_dropped: report.degenerate_dropped,
            cells_split: report.cells_split,
            tets_from_split: report.tets_from_split,
            pieces: report.pieces,
            origin: report.origin,
            excluded: report.excluded.clone(),
            hanging_nodes: report.validation.hanging_nodes,
            folded_face_pairs: report.validation.folded_face_pairs,
            nonconforming_faces: report.validation.nonconforming_faces.clone(),
            warnings: report.warnings.clone(),
            times: report.times.clone(),
            time_step: report.time_step,
            blocks: report.blocks.clone(),
        }
    }
}

impl fmt::Display for MeshSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (lo, hi) = self.bounds;
        writeln!(f, "format:          {}", self.format)?;
        writeln!(f, "points:          {}", self.points)?;
        writeln!(f, "tetrahedra:      {}", self.tets)?;
        writeln!(f, "interior faces:  {}", self.interior_faces)?;
        writeln!(f, "boundary faces:  {}", self.boundary_faces)?;
        writeln!(f, "components:      {}", self.components)?;
        writeln!(
            f,
            "bounds:          x [{}, {}]  y [{}, {}]  z [{}, {}]",
            lo.x, hi.x, lo.y, hi.y, lo.z, hi.z
        )?;
        if self.cells_split > 0 {
            writeln!(
                f,
                "split:           {} cells into {} tetrahedra",
                self.cells_split, self.tets_from_split
            )?;
        }
        if let Some(step) = self.time_step {
            writeln!(
                f,
                "time steps:      {} (read step {step}, time {})",
                self.times.len(),
                self.times[step]
            )?;
        } else if !self.blocks.is_empty() {
            writeln!(f, "time steps:      none")?;
        }
        if !self.blocks.is_empty() {
            writeln!(f, "element blocks:")?;
            for b in &self.blocks {
                let name = if b.name.is_empty() {
                    String::new()
                } else {
                    format!(" \"{}\"", b.name)
                };
                let what = if b.kept { "kept" } else { "skipped" };
                writeln!(
                    f,
                    "  id {}{name}: {} x {} ({} nodes), {what}",
                    b.id, b.cells, b.elem_type, b.nodes_per_element
                )?;
            }
        }
        let p = &self.pieces;
        if p.pieces > 0 {
            writeln!(
                f,
                "pieces:          {} joined, {} points welded, {} ghost cells dropped",
                p.pieces, p.welded_points, p.ghost_cells_dropped
            )?;
        }
        if p.blocks > 0 {
            writeln!(
                f,
                "blocks:          {} read, {} skipped",
                p.blocks, p.blocks_skipped
            )?;
        }
        if p.hidden_cells_dropped > 0 || (p.pieces == 0 && p.ghost_cells_dropped > 0) {
            writeln!(
                f,
                "blanked:         {} hidden and {} ghost cells dropped",
                p.hidden_cells_dropped, p.ghost_cells_dropped
            )?;
        }
        let o = self.origin;
        if o != DVec3::ZERO {
            writeln!(
                f,
                "origin:          ({}, {}, {}) (bounds are relative to it)",
                o.x, o.y, o.z
            )?;
        }
        writeln!(f, "reoriented:      {}", self.inverted_fixed)?;
        writeln!(f, "flat dropped:    {}", self.degenerate_dropped)?;
        let x = &self.excluded;
        if !x.cells.is_empty() {
            let shown: Vec<String> = x.cells.iter().take(20).map(u32::to_string).collect();
            writeln!(
                f,
                "left out:        {} cells ({} tangled, {} overlapping, {} non-manifold), {} \
                 tetrahedra, {:.4}% of the volume",
                x.cells.len(),
                x.tangled,
                x.overlapping,
                x.non_manifold,
                x.tets,
                100.0 * x.volume_share
            )?;
            let more = if x.cells.len() > 20 { " ..." } else { "" };
            writeln!(f, "  cells:         {}{more}", shown.join(" "))?;
        }
        if x.flat_tets > 0 {
            writeln!(f, "flat left out:   {} tetrahedra", x.flat_tets)?;
        }
        if !self.nonconforming_faces.is_empty() {
            writeln!(
                f,
                "non-conforming:  {} faces made boundary ({} hanging nodes, {} pairs of faces \
                 split differently)",
                self.nonconforming_faces.len(),
                self.hanging_nodes,
                self.folded_face_pairs
            )?;
            for face in self.nonconforming_faces.iter().take(10) {
                writeln!(
                    f,
                    "  tetrahedron {} face {}: points {:?}",
                    face.tet, face.local_face, face.vertices
                )?;
            }
            if self.nonconforming_faces.len() > 10 {
                writeln!(f, "  ...")?;
            }
        }
        if self.fields.is_empty() {
            writeln!(f, "fields:          none")?;
        } else {
            writeln!(f, "fields:")?;
            let width = self.fields.iter().map(|r| r.name.len()).max().unwrap_or(0);
            for r in &self.fields {
                writeln!(f, "  {:width$}  [{}, {}]", r.name, r.min, r.max)?;
            }
        }
        if self.warnings.is_empty() {
            writeln!(f, "validation:      ok, no warnings")?;
        } else {
            writeln!(f, "validation:      ok, {} warnings:", self.warnings.len())?;
            for w in &self.warnings {
                writeln!(f, "  - {w}")?;
            }
        }
        Ok(())
    }
}
