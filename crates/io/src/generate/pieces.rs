//! The torus shell written as a partitioned `.pvtu`: `P` piece files, each
//! a slab of whole hexahedra around the z axis (`iu` in `[start, end)`),
//! with its own copy of the points on its two bounding planes. No global
//! point ids are written, so the reader joins the pieces by welding
//! bit-equal coordinates (the shared planes are computed from the same
//! wrapped angle in every piece), which is what a `.pvtu` of a partitioned
//! simulation asks of it.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use glam::Vec3;
use rayon::prelude::*;
use tetray_mesh::structured::templates;

use super::GenerateError;
use super::solid::{CHUNK_HEXES, FIELDS, TorusShell, cell_tets};
use crate::vtk::{TetChunks, VtuIndex, VtuStreamOptions, write_vtu_streamed};

/// One piece: the hexahedra with `iu` in `[start, end)`.
struct Piece<'a> {
    shell: &'a TorusShell,
    start: usize,
    end: usize,
}

impl Piece<'_> {
    /// Points per `iv, iw` row of the piece: `iu` in `[start, end]`.
    fn width(&self) -> usize {
        self.end - self.start + 1
    }

    /// The piece's number of the shell's point `(iu, iv, iw)`, `iu` in
    /// `[start, end]` (unwrapped), `iv` wrapped.
    fn local(&self, iu: usize, iv: usize, iw: usize) -> u32 {
        let nv = self.shell.cells[1];
        (iu - self.start + self.width() * ((iv % nv) + nv * iw)) as u32
    }

    /// The piece's points, `iu` fastest, each the shell's own point (the
    /// last plane wraps to `iu = 0` for the last piece).
    fn points(&self, all: &[Vec3]) -> Vec<Vec3> {
        let [_, nv, nw] = self.shell.cells;
        let w = self.width();
        (0..w * nv * (nw + 1))
            .into_par_iter()
            .map(|p| {
                let (du, iv, iw) = (p % w, (p / w) % nv, p / (w * nv));
                all[self.shell.index(self.start + du, iv, iw) as usize]
            })
            .collect()
    }
}

impl TetChunks for Piece<'_> {
    fn tet_count(&self) -> usize {
        let [_, nv, nw] = self.shell.cells;
        5 * (self.end - self.start) * nv * nw
    }

    fn for_each_chunk(
        &self,
        sink: &mut dyn FnMut(&[[u32; 4]]) -> io::Result<()>,
    ) -> io::Result<()> {
        let t = templates();
        let [_, nv, nw] = self.shell.cells;
        let w = self.end - self.start;
        let hexes = w * nv * nw;
        let mut chunk = Vec::with_capacity(5 * CHUNK_HEXES);
        for first in (0..hexes).step_by(CHUNK_HEXES) {
            chunk.clear();
            for h in first..(first + CHUNK_HEXES).min(hexes) {
                // The shell's own split (parity included), so the pieces'
                // tetrahedra are the whole shell's.
                let corner = (self.start + h % w, (h / w) % nv, h / (w * nv));
                chunk.extend(cell_tets(&t, corner, |iu, iv, iw| self.local(iu, iv, iw)));
            }
            sink(&chunk)?;
        }
        Ok(())
    }
}

/// Writes `shell` as `path` (a `.pvtu`) and `pieces` piece files in the
/// folder `<stem>/` beside it. Returns every file written with its size,
/// the `.pvtu` first.
///
/// # Errors
/// [`GenerateError::BadShell`] for more pieces than cells around the axis
/// (or none); [`GenerateError::Io`] naming the file.
pub fn write_pvtu(
    shell: &TorusShell,
    path: &Path,
    pieces: usize,
) -> Result<Vec<(PathBuf, u64)>, GenerateError> {
    let nu = shell.cells[0];
    if pieces == 0 || pieces > nu {
        return Err(GenerateError::BadShell {
            cells: shell.cells,
            reason: format!("{pieces} pieces: between 1 and {nu} (cells around the axis)"),
        });
    }
    let io_error = |file: &Path| {
        let file = file.display().to_string();
        move |source| GenerateError::Io { file, source }
    };
    let stem = path.file_stem().map_or_else(
        || "pieces".to_string(),
        |s| s.to_string_lossy().into_owned(),
    );
    let folder = path.with_file_name(&stem);
    std::fs::create_dir_all(&folder).map_err(io_error(&folder))?;
    let all = shell.points();
    let options = VtuStreamOptions {
        index: VtuIndex::Int32,
        header_u64: true,
        big_endian: false,
    };
    let mut written = Vec::new();
    let mut sources = Vec::new();
    for p in 0..pieces {
        let piece = Piece {
            shell,
            start: p * nu / pieces,
            end: (p + 1) * nu / pieces,
        };
        let points = piece.points(&all);
        let fields = TorusShell::fields(&points);
        let name = format!("{stem}_{p}.vtu");
        let file_path = folder.join(&name);
        let mut file = File::create(&file_path).map_err(io_error(&file_path))?;
        let bytes = write_vtu_streamed(&points, &fields, &piece, &mut file, &options)
            .map_err(io_error(&file_path))?;
        written.push((file_path, bytes));
        sources.push(format!("{stem}/{name}"));
    }
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" \
         byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PUnstructuredGrid \
         GhostLevel=\"0\">\n",
    );
    xml.push_str(&format!("    <PPointData Scalars=\"{}\">\n", FIELDS[0]));
    for name in FIELDS {
        xml.push_str(&format!(
            "      <PDataArray type=\"Float32\" Name=\"{name}\"/>\n"
        ));
    }
    xml.push_str(
        "    </PPointData>\n    <PPoints>\n      <PDataArray type=\"Float32\" \
         NumberOfComponents=\"3\"/>\n    </PPoints>\n",
    );
    for source in &sources {
        xml.push_str(&format!("    <Piece Source=\"{source}\"/>\n"));
    }
    xml.push_str("  </PUnstructuredGrid>\n</VTKFile>\n");
    let mut file = File::create(path).map_err(io_error(path))?;
    file.write_all(xml.as_bytes()).map_err(io_error(path))?;
    written.insert(0, (path.to_path_buf(), xml.len() as u64));
    Ok(written)
}
