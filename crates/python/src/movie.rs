//! Animations and PNG bytes from Python: the CLI's frame writer (a folder
//! of PNG frames, an animated GIF, an MP4 through ffmpeg) fed NumPy images,
//! and one image as the PNG the CLI writes (what a notebook shows).

use glam::Vec3;
use numpy::{PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use tetray_core::{Image, Movie};

use crate::value_error;

/// A (height, width, 4) float32 array as an image.
fn image_of(array: &PyReadonlyArray3<'_, f32>) -> PyResult<Image> {
    let shape = array.shape();
    if shape[2] != 4 {
        return Err(value_error(format!(
            "expected a (height, width, 4) image, got shape {shape:?}"
        )));
    }
    let (h, w) = (
        u32::try_from(shape[0]).map_err(|_| value_error("image too tall"))?,
        u32::try_from(shape[1]).map_err(|_| value_error("image too wide"))?,
    );
    let values = array.as_array();
    let rgba = (0..shape[0])
        .flat_map(|y| (0..shape[1]).map(move |x| (y, x)))
        .map(|(y, x)| std::array::from_fn(|c| values[[y, x, c]]))
        .collect();
    Image::from_pixels(w, h, rgba).map_err(|e| value_error(e.to_string()))
}

fn background(rgb: (f32, f32, f32)) -> PyResult<Vec3> {
    let v = Vec3::new(rgb.0, rgb.1, rgb.2);
    if !v.is_finite() {
        return Err(value_error(format!("background {v} must be finite")));
    }
    Ok(v)
}

/// The PNG of `image` over `background`, as the CLI writes it.
#[pyfunction]
#[pyo3(signature = (image, background=(0.0, 0.0, 0.0)))]
pub fn png_bytes<'py>(
    py: Python<'py>,
    image: PyReadonlyArray3<'py, f32>,
    background: (f32, f32, f32),
) -> PyResult<Bound<'py, PyBytes>> {
    let bytes = image_of(&image)?
        .png_bytes(self::background(background)?)
        .map_err(|e| value_error(e.to_string()))?;
    Ok(PyBytes::new(py, &bytes))
}

/// An animation being written, frame by frame.
#[pyclass(unsendable)]
pub struct MovieWriter {
    movie: Option<Movie>,
    written: usize,
}

#[pymethods]
impl MovieWriter {
    #[new]
    #[pyo3(signature = (path, size, fps=10, background=(0.0, 0.0, 0.0)))]
    fn new(
        path: std::path::PathBuf,
        size: (u32, u32),
        fps: u32,
        background: (f32, f32, f32),
    ) -> PyResult<Self> {
        let movie = Movie::create(&path, size, fps, self::background(background)?)
            .map_err(|e| value_error(e.to_string()))?;
        Ok(MovieWriter {
            movie: Some(movie),
            written: 0,
        })
    }

    fn add(&mut self, image: PyReadonlyArray3<'_, f32>) -> PyResult<()> {
        let image = image_of(&image)?;
        self.movie
            .as_mut()
            .ok_or_else(|| value_error("the animation is closed"))?
            .add(&image)
            .map_err(|e| value_error(e.to_string()))?;
        self.written += 1;
        Ok(())
    }

    /// Frames written.
    #[getter]
    fn frames(&self) -> usize {
        self.written
    }

    fn close(&mut self) -> PyResult<()> {
        match self.movie.take() {
            Some(movie) => movie.finish().map_err(|e| value_error(e.to_string())),
            None => Ok(()),
        }
    }
}
