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
