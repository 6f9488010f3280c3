//! Legacy `.vtk` files (ASCII or BINARY): the tokenizer (`lex.rs`),
//! UNSTRUCTURED_GRID (`read.rs`), STRUCTURED_GRID, RECTILINEAR_GRID and
//! STRUCTURED_POINTS (`structured.rs`), and the writer (`write.rs`).

pub(crate) mod lex;
pub(crate) mod read;
pub(crate) mod structured;
pub(crate) mod write;
