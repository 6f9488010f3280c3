//! The native half of the `tetray` Python package (`tetray._native`):
//! conversion of NumPy arrays and Python values into the engine's options
//! and a [`tetray_mesh::cells::CellGrid`], and of images back into NumPy
//! arrays. Everything else (the mesh assembly, the scene, camera, transfer
//! function, renderers, `compare`) is the engine's, as for the CLI, so a
//! grid from Python and the same grid in a `.vtu` give the same image.
//!
//! Errors: an [`EngineError`] about a file becomes `OSError`, any other
//! `ValueError`, with the engine's message. Loads and renders run with the
//! GIL released ([`Python::detach`]) and under `guard`, which turns a
//! panic into a `RuntimeError` rather than unwinding into the interpreter.

mod convert;
mod extras;
mod grid;
mod interrupt;
mod movie;
mod scene;

use std::panic::{AssertUnwindSafe, catch_unwind};

use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use tetray_engine::EngineError;

/// A [`EngineError`] as the Python exception the package documents.
pub(crate) fn to_py(e: EngineError) -> PyErr {
    if e.is_io() {
        PyOSError::new_err(e.chain())
    } else {
        PyValueError::new_err(e.chain())
    }
}

/// A `ValueError` with `message`.
pub(crate) fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}

/// Runs `f`, turning a panic (a bug: every input is checked before it
/// reaches code that could panic) into a `RuntimeError` naming it.
pub(crate) fn guard<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(PyRuntimeError::new_err(format!(
                "tetray internal error (please report): {what}"
            )))
        }
    }
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<grid::Grid>()?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<movie::MovieWriter>()?;
    m.add_function(wrap_pyfunction!(movie::png_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(extras::segment, m)?)?;
    m.add_function(wrap_pyfunction!(extras::psi, m)?)?;
    m.add_function(wrap_pyfunction!(extras::methods, m)?)?;
    m.add("DEFAULT_VIEW", tetray_engine::DEFAULT_VIEW)?;
    Ok(())
}
