//! Serial VTK XML files: the XML tree (`tree.rs`), the one DataArray
//! decoder every XML reader shares (`data.rs`: ascii, base64, appended,
//! zlib), `.vtu` unstructured grids (`read.rs`), `.vts`/`.vtr`/`.vti`
//! structured grids (`structured.rs`), and the `.vtu` writers (`write.rs`,
//! whole meshes; `stream.rs`, chunk by chunk).

pub(crate) mod data;
pub(crate) mod read;
pub(crate) mod stream;
pub(crate) mod structured;
pub(crate) mod tree;
pub(crate) mod write;

use tetray_mesh::cells::CellError;
use tetray_mesh::cells::CellGrid;

use crate::vtk::{ReadOptions, VtkError, VtkRead};

/// Parses a serial VTK XML file held in memory; `name` is used in messages.
pub(crate) fn read_with(bytes: &[u8], name: &str, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
    crate::vtk::assemble(read_raw(bytes, name)?, name, opts)
}

/// The raw grid of a serial VTK XML file of any dataset type read.
pub(crate) fn read_raw(bytes: &[u8], name: &str) -> Result<CellGrid, VtkError> {
    let mut doc = tree::parse(bytes, name)?;
    if doc.pieces.is_empty() {
        return Err(VtkError::Cell(CellError::Invalid {
            file: name.into(),
            section: format!("<{}>", doc.dataset),
            message: "no <Piece> element".into(),
        }));
    }
    if doc.dataset == "UnstructuredGrid" {
        read::read_unstructured(&doc, name)
    } else {
        structured::read_raw(&mut doc, name)
    }
}
