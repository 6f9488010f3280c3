//! Loading a mesh from a file, ready to render: read (points relative to
//! an origin near the mesh, see [`crate::centring_origin`]), leave out the
//! cells that cannot be walked (`exclude.rs`), orient, validate, build the
//! topology. What was changed is in the [`LoadReport`].

use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::exclude::{exclude_bad_cells, ExcludedCells};
use crate::plot3d::{read_plot3d_bytes, read_plot3d_files, Plot3dRead};
use crate::validate::{check_input, check_walkable};
use crate::{vtk, MeshError, TetMesh, Topology, ValidationReport};

/// Options of [`load`].
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// The PLOT3D solution file; by default the grid file's sibling with
    /// `xyz` replaced by `q` (`postxyz.bin` -> `postq.bin`, `a.xyz` or
    /// `a.x` -> `a.q`), used when it exists.
    pub plot3d_q: Option<PathBuf>,
}

/// What happened on the way from the file to the mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LoadReport {
    /// The reader used: "VTK legacy", "VTK XML", "PLOT3D" or "memory".
    pub format: &'static str,
    /// Reader and validation warnings, as sentences.
    pub warnings: Vec<String>,
    /// Negatively oriented tetrahedra that were reoriented (for PLOT3D,
    /// those the split made inverted: all of them for a left-handed grid).
    pub inverted_fixed: usize,
    /// Flat tetrahedra made by splitting collapsed cells, dropped by the
    /// reader (PLOT3D; the VTK readers report theirs in `warnings`).
    pub degenerate_dropped: usize,
    /// Non-tetrahedral cells (hexahedra, wedges...) split into tetrahedra.
    pub cells_split: usize,
    /// Tetrahedra made by those splits.
    pub tets_from_split: usize,
    /// Validation findings (components, duplicate points, seams,
    /// non-conforming faces...).
    pub validation: ValidationReport,
    /// The points are stored relative to this origin: a point's coordinates
    /// in the file are `origin + point` (zero unless the mesh lies far from
    /// zero; see [`crate::centring_origin`]). Cameras given in the file's
    /// coordinates subtract it.
    pub origin: DVec3,
    /// Cells left out of the walk (tangled, overlapping) and flat
    /// tetrahedra dropped.
    pub excluded: ExcludedCells,
}

impl LoadReport {
    /// One line saying what loading changed in the mesh (non-conforming
    /// faces made boundary, cells left out with their volume share, the
    /// origin shift), or `None` when it changed nothing of the geometry.
    pub fn changes(&self) -> Option<String> {
        let mut parts = Vec::new();
        let v = &self.validation;
        if !v.nonconforming_faces.is_empty() {
            parts.push(format!(
                "{} non-conforming faces made boundary ({} hanging nodes, {} pairs of faces split \
                 differently)",
                v.nonconforming_faces.len(),
                v.hanging_nodes,
                v.folded_face_pairs
            ));
        }
        let x = &self.excluded;
        if !x.cells.is_empty() {
            parts.push(format!(
                "{} cells left out ({} tangled, {} overlapping, {} non-manifold; {:.4}% of the \
                 volume)",
                x.cells.len(),
                x.tangled,
                x.overlapping,
                x.non_manifold,
                100.0 * x.volume_share
            ));
        }
        if x.flat_tets > 0 {
            parts.push(format!("{} flat tetrahedra dropped", x.flat_tets));
        }
        if self.origin != DVec3::ZERO {
            let o = self.origin;
            parts.push(format!(
                "points stored relative to the origin ({}, {}, {})",
                o.x, o.y, o.z
            ));
        }
        (!parts.is_empty()).then(|| format!("mesh changed on load: {}", parts.join("; ")))
    }
}

/// A mesh ready to render: positively oriented, validated, with its
/// face-neighbour topology.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedMesh {
    pub mesh: TetMesh,
    pub topology: Topology,
    pub report: LoadReport,
}

impl LoadedMesh {
    /// Where the stored points are relative to the file's coordinates
    /// (see [`LoadReport::origin`]).
    pub fn origin(&self) -> DVec3 {
        self.report.origin
    }
}

/// The file formats [`load`] recognises by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Legacy,
    Vtu,
    Plot3d,
}

fn format_of(path: &Path) -> Option<Format> {
    let name = path.file_name()?.to_string_lossy().to_lowercase();
    if name.ends_with(".vtk") {
        Some(Format::Legacy)
    } else if name.ends_with(".vtu") {
        Some(Format::Vtu)
    } else if name.ends_with("xyz.bin") || name.ends_with(".xyz") || name.ends_with(".x") {
        Some(Format::Plot3d)
    } else {
        None
    }
}

/// The default solution file of a PLOT3D grid: the last `xyz` of the file
/// name (any case) replaced by `q`, or a final `.x` by `.q`.
pub fn plot3d_q_sibling(xyz: &Path) -> Option<PathBuf> {
    let name = xyz.file_name()?.to_string_lossy().into_owned();
    let lower = name.to_lowercase();
    let q_name = if let Some(at) = lower.rfind("xyz") {
        format!("{}q{}", &name[..at], &name[at + 3..])
    } else if lower.ends_with(".x") {
        format!("{}q", &name[..name.len() - 1])
    } else {
        return None;
    };
    Some(xyz.with_file_name(q_name))
}

/// Reads the mesh at `path` (chosen by name: `.vtk`, `.vtu`, or a PLOT3D
/// grid `*xyz.bin`, `*.xyz`, `*.x`), then orients, validates and builds the
/// topology (see [`prepare`]).
///
/// # Errors
/// [`MeshError::UnknownFormat`] for an unrecognised name, the reader's
/// errors, and validation errors wrapped in [`MeshError::InFile`].
pub fn load(path: &Path, opts: &LoadOptions) -> Result<LoadedMesh, MeshError> {
    let file = path.display().to_string();
    let format = format_of(path).ok_or_else(|| MeshError::UnknownFormat { file: file.clone() })?;
    let read = match format {
        Format::Legacy => from_vtk(vtk::read_legacy_file(path)?, "VTK legacy"),
        Format::Vtu => from_vtk(vtk::read_vtu_file(path)?, "VTK XML"),
        Format::Plot3d => {
            let mut warnings = Vec::new();
            let q = match &opts.plot3d_q {
                Some(q) => Some(q.clone()),
                None => match plot3d_q_sibling(path) {
                    Some(q) if q.is_file() => Some(q),
                    other => {
                        let looked = other
                            .map_or_else(String::new, |q| format!(" ({} not found)", q.display()));
                        warnings.push(format!(
                            "no PLOT3D solution file{looked}: the mesh has no scalar fields"
                        ));
                        None
                    }
                },
            };
            let mut read = from_plot3d(read_plot3d_files(path, q.as_deref())?);
            warnings.append(&mut read.warnings);
            read.warnings = warnings;
            read
        }
    };
    finish(read).map_err(|e| e.in_file(&file))
}

/// Loads a PLOT3D grid and optional solution held in memory (`name` is
/// used in messages), like [`load`] does a file.
///
/// # Errors
/// As [`crate::read_plot3d_bytes`], and validation errors wrapped in
/// [`MeshError::InFile`].
pub fn load_plot3d_bytes(
    xyz: &[u8],
    q: Option<&[u8]>,
    name: &str,
) -> Result<LoadedMesh, MeshError> {
    finish(from_plot3d(read_plot3d_bytes(xyz, q, name)?)).map_err(|e| e.in_file(name))
}

/// Orients, validates and builds the topology of a mesh made in memory.
///
/// # Errors
/// The first validation error (see [`crate::validate`]).
pub fn prepare(mesh: TetMesh) -> Result<LoadedMesh, MeshError> {
    finish(Read {
        mesh,
        format: "memory",
        ..Read::default()
    })
}

/// A reader's output in common form.
#[derive(Default)]
struct Read {
    mesh: TetMesh,
    format: &'static str,
    warnings: Vec<String>,
    degenerate_dropped: usize,
    inverted_fixed: usize,
    cells_split: usize,
    tets_from_split: usize,
    origin: DVec3,
    /// Per tetrahedron, the cell it came from (empty: each its own).
    tet_cells: Vec<u32>,
}

fn from_vtk(read: vtk::VtkRead, format: &'static str) -> Read {
    let c = read.cells;
    Read {
        mesh: read.mesh,
        format,
        warnings: read.warnings,
        cells_split: c.hexahedra + c.wedges + c.pyramids + c.voxels,
        tets_from_split: c.tets_from_split,
        origin: read.origin,
        tet_cells: read.tet_cells,
        ..Read::default()
    }
}

/// PLOT3D grids are read in f32 (most are single precision); they are
/// centred like the others, the subtraction done in f64.
fn from_plot3d(read: Plot3dRead) -> Read {
    let hexahedra = read.hexahedra - read.blanked_hexahedra;
    let mut mesh = read.mesh;
    let origin = crate::geometry::bounds_f64(mesh.points.iter().map(|p| p.as_dvec3()))
        .map_or(DVec3::ZERO, |(lo, hi)| crate::centring_origin(lo, hi));
    if origin != DVec3::ZERO {
        for p in &mut mesh.points {
            *p = (p.as_dvec3() - origin).as_vec3();
        }
    }
    Read {
        tets_from_split: mesh.tets.len(),
        mesh,
        origin,
        tet_cells: Vec::new(),
        format: "PLOT3D",
        warnings: read.warnings,
        degenerate_dropped: read.degenerate_dropped,
        inverted_fixed: read.reoriented,
        cells_split: hexahedra,
    }
}

fn finish(mut read: Read) -> Result<LoadedMesh, MeshError> {
    check_input(&read.mesh)?;
    let (topology, excluded, reoriented) = exclude_bad_cells(&mut read.mesh, &read.tet_cells)?;
    read.inverted_fixed += reoriented;
    let validation = check_walkable(&read.mesh, &topology)?;
    let mut warnings = read.warnings;
    warnings.extend(excluded.warnings());
    warnings.extend(validation.warnings.iter().cloned());
    Ok(LoadedMesh {
        mesh: read.mesh,
        topology,
        report: LoadReport {
            format: read.format,
            warnings,
            inverted_fixed: read.inverted_fixed,
            degenerate_dropped: read.degenerate_dropped,
            cells_split: read.cells_split,
            tets_from_split: read.tets_from_split,
            validation,
            origin: read.origin,
            excluded,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_and_q_siblings() {
        let p = Path::new;
        assert_eq!(format_of(p("a/b.VTK")), Some(Format::Legacy));
        assert_eq!(format_of(p("b.vtu")), Some(Format::Vtu));
        assert_eq!(format_of(p("postxyz.bin")), Some(Format::Plot3d));
        assert_eq!(format_of(p("grid.x")), Some(Format::Plot3d));
        assert_eq!(format_of(p("grid.obj")), None);
        assert_eq!(
            plot3d_q_sibling(p("d/postxyz.bin")),
            Some(PathBuf::from("d/postq.bin"))
        );
        assert_eq!(
            plot3d_q_sibling(p("d/Wing.XYZ")),
            Some(PathBuf::from("d/Wing.q"))
        );
        assert_eq!(plot3d_q_sibling(p("grid.x")), Some(PathBuf::from("grid.q")));
    }
}
