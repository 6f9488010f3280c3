//! The comparison of several methods' images against a reference image:
//! error maps, the table of errors and speeds, and the files they are
//! written to.

use std::path::{Path, PathBuf};

use glam::Vec3;
use serde::Serialize;
use tetray_core::Image;

use crate::CompareError;
use crate::flip::{PIXELS_PER_DEGREE, flip};
use crate::heatmap::{colour_bar, heat_map};
use crate::metrics::{ErrorStats, ONE_LEVEL, abs_error};
use crate::sheet::{SheetRow, sheet};

/// How fast a method made its image.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Speed {
    pub ms_per_frame: f64,
    pub tets_per_s: f64,
    pub segments_per_s: f64,
}

/// One rendered image and what made it.
#[derive(Debug, Clone)]
pub struct Method {
    /// Short and unique: "gpu ppi", "project ppi mpvo".
    pub label: String,
    pub renderer: String,
    pub integrator: String,
    /// The projection's visibility sort.
    pub sort: Option<String>,
    /// The projection's adaptive transfer-function sampling.
    pub adaptive_tf: Option<bool>,
    pub image: Image,
    pub speed: Speed,
}

/// One line of the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    pub label: String,
    pub renderer: String,
    pub integrator: String,
    pub sort: Option<String>,
    pub adaptive_tf: Option<bool>,
    /// Absolute error, the largest over the premultiplied RGBA channels.
    pub abs_error: ErrorStats,
    /// The FLIP-like error of the images over black.
    pub flip_mean: f64,
    pub flip_p99: f32,
    pub speed: Speed,
    /// File names of the method's maps, in the output folder.
    pub abs_map: String,
    pub flip_map: String,
}

/// Everything compared, with the maps.
pub struct Report {
    pub title: String,
    pub reference: Method,
    pub methods: Vec<Method>,
    pub rows: Vec<Row>,
    pub abs_maps: Vec<Vec<f32>>,
    pub flip_maps: Vec<Vec<f32>>,
    /// The absolute error shown white in every heat map: the largest over
    /// the methods (at least one 8-bit level), so the maps share a scale.
    pub abs_scale: f32,
}

/// Compares each of `methods` with `reference`.
pub fn compare(
    title: &str,
    reference: Method,
    methods: Vec<Method>,
) -> Result<Report, CompareError> {
    if methods.is_empty() {
        return Err(CompareError::NoMethods);
    }
    let mut rows = Vec::with_capacity(methods.len());
    let (mut abs_maps, mut flip_maps) = (Vec::new(), Vec::new());
    for (i, method) in methods.iter().enumerate() {
        let abs = abs_error(&method.image, &reference.image)?;
        let perceptual = flip(&method.image, &reference.image, PIXELS_PER_DEGREE)?;
        let flip_stats = ErrorStats::of(&perceptual);
        let slug = format!("{}_{}", i + 1, slug(&method.label));
        rows.push(Row {
            label: method.label.clone(),
            renderer: method.renderer.clone(),
            integrator: method.integrator.clone(),
            sort: method.sort.clone(),
            adaptive_tf: method.adaptive_tf,
            abs_error: ErrorStats::of(&abs),
            flip_mean: flip_stats.mean,
            flip_p99: flip_stats.p99,
            speed: method.speed,
            abs_map: format!("abs_{slug}.png"),
            flip_map: format!("flip_{slug}.png"),
        });
        abs_maps.push(abs);
        flip_maps.push(perceptual);
    }
    let abs_scale = rows
        .iter()
        .map(|r| r.abs_error.max)
        .fold(ONE_LEVEL, f32::max);
    Ok(Report {
        title: title.to_string(),
        reference,
        methods,
        rows,
        abs_maps,
        flip_maps,
        abs_scale,
    })
}

/// The table as written to JSON.
#[derive(Serialize)]
struct Table<'a> {
    title: &'a str,
    width: u32,
    height: u32,
    reference: Reference<'a>,
    abs_scale: f32,
    one_level: f32,
    methods: &'a [Row],
}

#[derive(Serialize)]
struct Reference<'a> {
    label: &'a str,
    renderer: &'a str,
    integrator: &'a str,
    speed: Speed,
}

impl Report {
    /// The table as JSON.
    pub fn json(&self) -> Result<String, CompareError> {
        let r = &self.reference;
        let table = Table {
            title: &self.title,
            width: r.image.width,
            height: r.image.height,
            reference: Reference {
                label: &r.label,
                renderer: &r.renderer,
                integrator: &r.integrator,
                speed: r.speed,
            },
            abs_scale: self.abs_scale,
            one_level: ONE_LEVEL,
            methods: &self.rows,
        };
        Ok(serde_json::to_string_pretty(&table)?)
    }

    /// The table as Markdown.
    pub fn markdown(&self) -> String {
        let r = &self.reference;
        let mut md = format!(
            "# {}\n\n{}x{} pixels; errors against {} ({:.1} ms/frame); absolute error is the \
             largest over premultiplied RGBA; px > 1/255 counts pixels a PNG shows as \
             different.\n\n",
            self.title, r.image.width, r.image.height, r.label, r.speed.ms_per_frame
        );
        md += "| method | max | mean | p99 | px > 1/255 | FLIP mean | FLIP p99 | ms/frame \
               | tets/s | segments/s |\n";
        md += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for row in &self.rows {
            let e = &row.abs_error;
            md += &format!(
                "| {} | {:.2e} | {:.2e} | {:.2e} | {} ({:.2}%) | {:.4} | {:.4} | {:.1} | {:.3e} \
                 | {:.3e} |\n",
                row.label,
                e.max,
                e.mean,
                e.p99,
                e.over_one_level,
                100.0 * e.over_one_level as f64 / e.pixels.max(1) as f64,
                row.flip_mean,
                row.flip_p99,
                row.speed.ms_per_frame,
                row.speed.tets_per_s,
                row.speed.segments_per_s
            );
        }
        md
    }

    /// Writes sheet.png, the per-method maps, table.json and table.md into
    /// `dir` (created if missing); returns the paths written.
    pub fn write(&self, dir: &Path, background: Vec3) -> Result<Vec<PathBuf>, CompareError> {
        std::fs::create_dir_all(dir).map_err(|source| CompareError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        let (w, h) = (self.reference.image.width, self.reference.image.height);
        let bar_height = h.max(48);
        let abs_bar = colour_bar(bar_height, self.abs_scale, "ABS ERROR");
        let flip_bar = colour_bar(bar_height, 1.0, "FLIP");
        let mut written = Vec::new();
        let mut save = |name: &str, image: &image::RgbImage| -> Result<(), CompareError> {
            let path = dir.join(name);
            image.save(&path).map_err(|source| CompareError::Image {
                path: path.clone(),
                source,
            })?;
            written.push(path);
            Ok(())
        };
        let (mut abs_cells, mut flip_cells) = (vec![None], vec![None]);
        for (i, row) in self.rows.iter().enumerate() {
            let abs = heat_map(&self.abs_maps[i], w, h, self.abs_scale);
            let perceptual = heat_map(&self.flip_maps[i], w, h, 1.0);
            let title = format!("{}: ABS ERROR AGAINST {}", row.label, self.reference.label);
            save(&row.abs_map, &with_bar(&title, &abs, &abs_bar))?;
            let title = format!("{}: FLIP AGAINST {}", row.label, self.reference.label);
            save(&row.flip_map, &with_bar(&title, &perceptual, &flip_bar))?;
            abs_cells.push(Some(abs));
            flip_cells.push(Some(perceptual));
        }
        let renders = std::iter::once(&self.reference)
            .chain(&self.methods)
            .map(|m| m.image.to_rgb8(background).map(Some))
            .collect::<Result<_, _>>()?;
        let columns: Vec<String> = std::iter::once(format!("{} (REF)", self.reference.label))
            .chain(self.rows.iter().map(|r| r.label.clone()))
            .collect();
        let rows = [
            SheetRow {
                title: self.title.clone(),
                cells: renders,
                colour_bar: None,
            },
            SheetRow {
                title: "ABS ERROR AGAINST THE REFERENCE (MAX OVER RGBA)".into(),
                cells: abs_cells,
                colour_bar: Some(abs_bar),
            },
            SheetRow {
                title: "FLIP-LIKE PERCEPTUAL ERROR".into(),
                cells: flip_cells,
                colour_bar: Some(flip_bar),
            },
        ];
        save("sheet.png", &sheet(&columns, &rows))?;
        for (name, text) in [("table.json", self.json()?), ("table.md", self.markdown())] {
            let path = dir.join(name);
            std::fs::write(&path, text).map_err(|source| CompareError::Io {
                path: path.clone(),
                source,
            })?;
            written.push(path);
        }
        Ok(written)
    }
}

/// A map with its title above and its colour bar to the right.
fn with_bar(title: &str, map: &image::RgbImage, bar: &image::RgbImage) -> image::RgbImage {
    let row = SheetRow {
        title: title.to_string(),
        cells: vec![Some(map.clone())],
        colour_bar: Some(bar.clone()),
    };
    sheet(&[String::new()], &[row])
}

/// A file-name part: lower-case letters and digits, runs of anything else
/// as one '-'.
fn slug(label: &str) -> String {
    let mut out = String::new();
    for c in label.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn method(label: &str, level: f32) -> Method {
        let pixels = (0..16 * 16)
            .map(|i| {
                if i % 16 < 8 {
                    [level, 0.0, 0.0, level]
                } else {
                    [0.0; 4]
                }
            })
            .collect();
        Method {
            label: label.to_string(),
            renderer: "cpu".into(),
            integrator: "reference".into(),
            sort: None,
            adaptive_tf: None,
            image: Image::from_pixels(16, 16, pixels).expect("image"),
            speed: Speed {
                ms_per_frame: 2.0,
                tets_per_s: 1e6,
                segments_per_s: 2e6,
            },
        }
    }

    #[test]
    fn rows_measure_each_method_against_the_reference() {
        let report = compare(
            "test",
            method("ref", 0.5),
            vec![method("same", 0.5), method("off by 0.1", 0.6)],
        )
        .expect("compare");
        let (same, off) = (&report.rows[0], &report.rows[1]);
        assert_eq!(same.abs_error.max, 0.0);
        assert_eq!(same.abs_error.over_one_level, 0);
        assert!((off.abs_error.max - 0.1).abs() < 1e-6);
        // Half the pixels differ by 0.1 (red and alpha).
        assert_eq!(off.abs_error.over_one_level, 128);
        assert!(off.flip_mean > same.flip_mean);
        assert!((report.abs_scale - off.abs_error.max).abs() < 1e-6);
        assert_eq!(off.abs_map, "abs_2_off-by-0-1.png");
        let md = report.markdown();
        assert!(md.contains("| off by 0.1 | 1.00e-1 |"), "{md}");
        let json: serde_json::Value = serde_json::from_str(&report.json().unwrap()).unwrap();
        assert_eq!(json["methods"][1]["abs_error"]["over_one_level"], 128);
        assert!(compare("x", method("ref", 0.5), vec![]).is_err());
    }

    #[test]
    fn writes_the_sheet_maps_and_tables() {
        let dir = std::env::temp_dir().join(format!("tetray-compare-{}", std::process::id()));
        let report = compare("t", method("ref", 0.5), vec![method("a", 0.4)]).expect("compare");
        let written = report.write(&dir, Vec3::ZERO).expect("write");
        let names: Vec<String> = written
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        for name in [
            "abs_1_a.png",
            "flip_1_a.png",
            "sheet.png",
            "table.json",
            "table.md",
        ] {
            assert!(names.iter().any(|n| n == name), "{name} in {names:?}");
        }
        let sheet = image::open(dir.join("sheet.png"))
            .expect("sheet")
            .into_rgb8();
        assert!(sheet.width() > 2 * 16 && sheet.height() > 3 * 16);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
