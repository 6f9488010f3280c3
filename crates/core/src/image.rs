//! Float RGBA images with premultiplied colour, written as linear EXR or as
//! 8-bit PNG composited over a background.

use std::path::{Path, PathBuf};

use glam::Vec3;

/// Why an image could not be made or written.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    #[error("cannot write image {path}: {source}")]
    Write {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("image size {width}x{height} needs {expected} pixels, got {actual}")]
    SizeMismatch {
        width: u32,
        height: u32,
        expected: usize,
        actual: usize,
    },
    #[error("image size {width}x{height} is too large")]
    TooLarge { width: u32, height: u32 },
    #[error("cannot write image {path}: {source}")]
    WriteFile {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

/// A rendered image: `rgba[y * width + x]`, row 0 at the top.
///
/// Colour is premultiplied by alpha (it is the light reaching the eye from
/// the volume, eq. 2.1's integral); alpha is `1 - transmittance`. When the
/// transmittance has a colour (RGB attenuation) alpha is `1 - mean(T_r, T_g,
/// T_b)`: a single alpha cannot express coloured attenuation, and the mean
/// keeps compositing over a grey background exact.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<[f32; 4]>,
}

impl Image {
    /// A transparent black image.
    pub fn new(width: u32, height: u32) -> Result<Image, ImageError> {
        let count = pixel_count(width, height)?;
        Ok(Image {
            width,
            height,
            rgba: vec![[0.0; 4]; count],
        })
    }

    /// Wraps existing pixels, checking their number.
    pub fn from_pixels(width: u32, height: u32, rgba: Vec<[f32; 4]>) -> Result<Image, ImageError> {
        let expected = pixel_count(width, height)?;
        if rgba.len() != expected {
            return Err(ImageError::SizeMismatch {
                width,
                height,
                expected,
                actual: rgba.len(),
            });
        }
        Ok(Image {
            width,
            height,
            rgba,
        })
    }

    /// The pixel at column `x`, row `y` (row 0 at the top), if inside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[f32; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.rgba
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }

    /// Linear float RGBA OpenEXR, premultiplied (EXR's own convention).
    pub fn write_exr(&self, path: &Path) -> Result<(), ImageError> {
        let flat: Vec<f32> = self.rgba.iter().flatten().copied().collect();
        let buffer = image::Rgba32FImage::from_raw(self.width, self.height, flat).ok_or(
            ImageError::SizeMismatch {
                width: self.width,
                height: self.height,
                expected: self.width as usize * self.height as usize,
                actual: self.rgba.len(),
            },
        )?;
        buffer
            .save_with_format(path, image::ImageFormat::OpenExr)
            .map_err(|source| ImageError::Write {
                path: path.to_path_buf(),
                source,
            })
    }

    /// The image composited over `background` (`c + (1 - a) * bg`) as 8-bit
    /// RGB, clamped to [0, 1], with no sRGB transform: the stored values are
    /// the linear ones, as VTK's renders store them.
    pub fn to_rgb8(&self, background: Vec3) -> Result<image::RgbImage, ImageError> {
        let bytes: Vec<u8> = self
            .rgba
            .iter()
            .flat_map(|&p| composite_over(p, background).map(to_u8))
            .collect();
        image::RgbImage::from_raw(self.width, self.height, bytes).ok_or(ImageError::SizeMismatch {
            width: self.width,
            height: self.height,
            expected: self.width as usize * self.height as usize,
            actual: self.rgba.len(),
        })
    }

    /// The PNG [`Image::write_png`] writes, as bytes (for a notebook to
    /// show).
    pub fn png_bytes(&self, background: Vec3) -> Result<Vec<u8>, ImageError> {
        let mut bytes = std::io::Cursor::new(Vec::new());
        self.to_rgb8(background)?
            .write_to(&mut bytes, image::ImageFormat::Png)
            .map_err(|source| ImageError::Write {
                path: PathBuf::from("(in memory)"),
                source,
            })?;
        Ok(bytes.into_inner())
    }

    /// The image as a NumPy `.npy` file (format version 1.0): a
    /// `(height, width, 4)` array of little-endian f32, C order, row 0 at
    /// the top, premultiplied like the EXR. NumPy reads it with
    /// `numpy.load`, exactly (no conversion on either side).
    pub fn npy_bytes(&self) -> Vec<u8> {
        let header = format!(
            "{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}, 4), }}",
            self.height, self.width
        );
        // Magic (6) + version (2) + header length (2) + header + '\n',
        // padded with spaces to a multiple of 64 bytes (the format's rule).
        let unpadded = 10 + header.len() + 1;
        let padding = unpadded.next_multiple_of(64) - unpadded;
        let header_len = header.len() + padding + 1;
        let mut bytes = Vec::with_capacity(10 + header_len + self.rgba.len() * 16);
        bytes.extend_from_slice(b"\x93NUMPY\x01\x00");
        bytes.extend_from_slice(&(header_len as u16).to_le_bytes());
        bytes.extend_from_slice(header.as_bytes());
        bytes.extend(std::iter::repeat_n(b' ', padding));
        bytes.push(b'\n');
        for value in self.rgba.iter().flatten() {
            bytes.extend_from_slice(&value.to_le_bytes());
        }
        bytes
    }

    /// [`Image::npy_bytes`] written to `path`.
    pub fn write_npy(&self, path: &Path) -> Result<(), ImageError> {
        std::fs::write(path, self.npy_bytes()).map_err(|source| ImageError::WriteFile {
            path: path.to_path_buf(),
            source,
        })
    }

    /// [`Image::to_rgb8`] written as a PNG.
    pub fn write_png(&self, path: &Path, background: Vec3) -> Result<(), ImageError> {
        self.to_rgb8(background)?
            .save_with_format(path, image::ImageFormat::Png)
            .map_err(|source| ImageError::Write {
                path: path.to_path_buf(),
                source,
            })
    }
}

/// Premultiplied `rgba` over an opaque `background`, unclamped.
pub fn composite_over(rgba: [f32; 4], background: Vec3) -> [f32; 3] {
    let keep = 1.0 - rgba[3];
    [
        rgba[0] + keep * background.x,
        rgba[1] + keep * background.y,
        rgba[2] + keep * background.z,
    ]
}

fn to_u8(v: f32) -> u8 {
    // NaN clamps to 0 (`as` saturates and maps NaN to 0).
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

fn pixel_count(width: u32, height: u32) -> Result<usize, ImageError> {
    (width as usize)
        .checked_mul(height as usize)
        .filter(|&n| n <= usize::MAX / 16)
        .ok_or(ImageError::TooLarge { width, height })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The layout NumPy's format document fixes: magic, version 1.0, a
    /// header padded so the data starts at a multiple of 64, then the
    /// values in order, little-endian.
    #[test]
    fn npy_layout() {
        let image = Image {
            width: 3,
            height: 2,
            rgba: (0..6).map(|i| [i as f32, 0.5, -1.0, 0.25]).collect(),
        };
        let bytes = image.npy_bytes();
        assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
        let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        let data = 10 + header_len;
        assert_eq!(data % 64, 0);
        let header = std::str::from_utf8(&bytes[10..data]).unwrap();
        assert!(header.contains("'shape': (2, 3, 4)"), "{header}");
        assert!(header.ends_with('\n'));
        assert_eq!(bytes.len(), data + 6 * 16);
        let value = |k: usize| {
            f32::from_le_bytes(bytes[data + 4 * k..data + 4 * k + 4].try_into().unwrap())
        };
        assert_eq!(value(4), 1.0);
        assert_eq!(value(6), -1.0);
    }
}
