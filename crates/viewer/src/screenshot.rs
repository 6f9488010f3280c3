//! Screenshots: PNG as displayed (the display pass's CPU twin over the
//! finished float images, so a single view is byte for byte what
//! `tetray render` writes), EXR as the float image of each view.

use std::path::{Path, PathBuf};

use anyhow::bail;
use tetray_core::Image;

use crate::engine::{FrameKey, Look};
use crate::present::{Display, PresentParams, Sources, present_image};

pub fn save(
    path: &Path,
    images: &[Image],
    key: &FrameKey,
    look: &Look,
) -> anyhow::Result<Vec<PathBuf>> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (Some(a), b) = (images.first(), images.get(1)) else {
        bail!("nothing rendered yet");
    };
    match ext.as_deref() {
        Some("png") => {
            if b.is_none() {
                a.write_png(path, look.background)?;
            } else {
                composite(images, key, look)?.write_png(path, look.background)?;
            }
            Ok(vec![path.to_path_buf()])
        }
        Some("exr") => {
            a.write_exr(path)?;
            let mut written = vec![path.to_path_buf()];
            if let Some(b) = b {
                let stem = path
                    .file_stem()
                    .map_or("view".into(), |s| s.to_string_lossy());
                let b_path = path.with_file_name(format!("{stem}-b.exr"));
                b.write_exr(&b_path)?;
                written.push(b_path);
            }
            Ok(written)
        }
        _ => bail!(
            "{}: the screenshot must end in .png or .exr",
            path.display()
        ),
    }
}

/// The two views as displayed (divider or difference), as an opaque image.
fn composite(images: &[Image], key: &FrameKey, look: &Look) -> anyhow::Result<Image> {
    let (a, b) = (&images[0], &images[images.len() - 1]);
    let (w, h) = (a.width, a.height);
    let divider = (look.divider.clamp(0.0, 1.0) * w as f32).round() as u32;
    let display = if key.views > 1 {
        look.display
    } else {
        Display::Single
    };
    let params = PresentParams::new(
        (w, h),
        (w, h),
        h,
        display,
        divider,
        look.background,
        look.diff_scale,
    );
    let sources = Sources {
        full_a: &a.rgba,
        full_b: &b.rgba,
        preview_a: &a.rgba,
        preview_b: &b.rgba,
    };
    let rgba = present_image(&params, &sources)
        .into_iter()
        .map(|p| [p[0], p[1], p[2]].map(|v| f32::from(v) / 255.0))
        .map(|[r, g, b]| [r, g, b, 1.0])
        .collect();
    Ok(Image::from_pixels(w, h, rgba)?)
}
