//! What a file holds, before reading it: its format by the file's name, and
//! by its first bytes where the name does not say (a legacy VTK header, a
//! VTK XML root element, a netCDF or HDF5 signature); and whether it is
//! image data, which shear-warp renders as the regular grid it is.

use std::io::Read;
use std::path::Path;

use crate::IoError;

/// The readers [`crate::load`] chooses among.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Format {
    Legacy,
    /// Serial XML: `.vtu`, `.vts`, `.vtr`, `.vti`.
    Xml,
    /// `.pvtu`, `.pvts`, `.pvtr`, `.pvti`.
    Parallel,
    MultiBlock,
    Plot3d,
    Exodus,
}

/// What the cells of a file are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataKind {
    /// Cells of any type, split into tetrahedra.
    Cells,
    /// A single-piece uniform grid (`.vti`, legacy STRUCTURED_POINTS): its
    /// cells, and the regular grid itself for shear-warp.
    ImageData,
}

/// A file's format and kind of data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Probe {
    pub(crate) format: Format,
    pub kind: DataKind,
    /// The format was recognised by the file's content, not its name.
    pub by_content: bool,
}

impl Probe {
    /// The format's name, as the load report gives it.
    pub fn format_name(&self) -> &'static str {
        match self.format {
            Format::Legacy => "VTK legacy",
            Format::Xml => "VTK XML",
            Format::Parallel => "VTK parallel XML",
            Format::MultiBlock => "VTK multi-block",
            Format::Plot3d => "PLOT3D",
            Format::Exodus => "Exodus II",
        }
    }
}

/// How many bytes of a file the content checks read.
const HEAD: usize = 4096;

/// The format of the file at `path` by its name, else by its content, and
/// whether it is image data.
///
/// # Errors
/// [`IoError::Io`] when the file cannot be read, [`IoError::UnknownFormat`]
/// (saying what the file starts with) when neither its name nor its
/// content is a format tetray reads.
pub fn probe(path: &Path) -> Result<Probe, IoError> {
    let file = path.display().to_string();
    let head = read_head(path).map_err(|source| IoError::Io {
        file: file.clone(),
        source,
    })?;
    let (format, by_content) = match format_of(path) {
        Some(format) => (format, false),
        None => match format_of_content(&head) {
            Some(format) => (format, true),
            None => {
                return Err(IoError::UnknownFormat {
                    file,
                    seen: describe_head(&head),
                });
            }
        },
    };
    let kind = match format {
        Format::Xml if xml_type(&head).as_deref() == Some("ImageData") => DataKind::ImageData,
        Format::Legacy if legacy_dataset(&head).as_deref() == Some("STRUCTURED_POINTS") => {
            DataKind::ImageData
        }
        _ => DataKind::Cells,
    };
    Ok(Probe {
        format,
        kind,
        by_content,
    })
}

/// The format a file name says (any case).
pub(crate) fn format_of(path: &Path) -> Option<Format> {
    let name = path.file_name()?.to_string_lossy().to_lowercase();
    let ext = name.rsplit_once('.').map_or("", |(_, e)| e);
    if ext == "vtk" {
        Some(Format::Legacy)
    } else if ["vtu", "vts", "vtr", "vti"].contains(&ext) {
        Some(Format::Xml)
    } else if ["pvtu", "pvts", "pvtr", "pvti"].contains(&ext) {
        Some(Format::Parallel)
    } else if ext == "vtm" {
        Some(Format::MultiBlock)
    } else if ["e", "exo", "ex2", "exii", "g", "gen"].contains(&ext) {
        Some(Format::Exodus)
    } else if name.ends_with("xyz.bin") || name.ends_with(".xyz") || name.ends_with(".x") {
        Some(Format::Plot3d)
    } else {
        None
    }
}

/// The format the first bytes of a file say: a legacy VTK header, a VTK
/// XML root element, or a netCDF (classic or HDF5-based) signature, which
/// tetray reads as Exodus II.
fn format_of_content(head: &[u8]) -> Option<Format> {
    if head.starts_with(b"# vtk DataFile") {
        return Some(Format::Legacy);
    }
    let netcdf = [
        &b"CDF\x01"[..],
        b"CDF\x02",
        b"CDF\x05",
        b"\x89HDF\r\n\x1a\n",
    ];
    if netcdf.iter().any(|sig| head.starts_with(sig)) {
        return Some(Format::Exodus);
    }
    match xml_type(head)?.as_str() {
        "UnstructuredGrid" | "StructuredGrid" | "RectilinearGrid" | "ImageData" => {
            Some(Format::Xml)
        }
        "PUnstructuredGrid" | "PStructuredGrid" | "PRectilinearGrid" | "PImageData" => {
            Some(Format::Parallel)
        }
        "vtkMultiBlockDataSet" => Some(Format::MultiBlock),
        _ => None,
    }
}

/// The `type` of a `<VTKFile>` root element within the head.
fn xml_type(head: &[u8]) -> Option<String> {
    let text = String::from_utf8_lossy(head);
    let root = &text[text.find("<VTKFile")?..];
    let root = &root[..root.find('>').unwrap_or(root.len())];
    let at = root.find("type")? + "type".len();
    let rest = root[at..].trim_start().strip_prefix('=')?.trim_start();
    let quote = rest.chars().next().filter(|c| *c == '"' || *c == '\'')?;
    let value = &rest[1..];
    Some(value[..value.find(quote)?].to_string())
}

/// The legacy header's dataset type (the word after `DATASET`).
fn legacy_dataset(head: &[u8]) -> Option<String> {
    let text = String::from_utf8_lossy(head);
    text.lines().take(16).find_map(|line| {
        let mut words = line.split_whitespace();
        let keyword = words.next()?;
        keyword
            .eq_ignore_ascii_case("DATASET")
            .then(|| words.next().map(str::to_ascii_uppercase))
            .flatten()
    })
}

/// What a file starts with, for an error: its first bytes, escaped.
fn describe_head(head: &[u8]) -> String {
    if head.is_empty() {
        return "the file is empty".to_string();
    }
    let shown: String = head
        .iter()
        .take(16)
        .flat_map(|&b| std::ascii::escape_default(b))
        .map(char::from)
        .collect();
    format!("it starts with \"{shown}\"")
}

fn read_head(path: &Path) -> std::io::Result<Vec<u8>> {
    let mut head = Vec::with_capacity(HEAD);
    std::fs::File::open(path)?
        .take(HEAD as u64)
        .read_to_end(&mut head)?;
    Ok(head)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_contents() {
        let p = Path::new;
        assert_eq!(format_of(p("a/b.VTK")), Some(Format::Legacy));
        assert_eq!(format_of(p("b.vtu")), Some(Format::Xml));
        assert_eq!(format_of(p("b.VTI")), Some(Format::Xml));
        assert_eq!(format_of(p("d/b.pvtu")), Some(Format::Parallel));
        assert_eq!(format_of(p("b.vtm")), Some(Format::MultiBlock));
        assert_eq!(format_of(p("postxyz.bin")), Some(Format::Plot3d));
        assert_eq!(format_of(p("grid.x")), Some(Format::Plot3d));
        assert_eq!(format_of(p("grid.obj")), None);
        for name in [
            "a.e",
            "a.EXO",
            "disk_out_ref.ex2",
            "mesh.g",
            "mesh.Gen",
            "x.exii",
        ] {
            assert_eq!(format_of(p(name)), Some(Format::Exodus), "{name}");
        }
        assert_eq!(format_of(p("a.e-s")), None);

        let legacy = b"# vtk DataFile Version 3.0\nimage\nASCII\nDATASET structured_points\n";
        assert_eq!(format_of_content(legacy), Some(Format::Legacy));
        assert_eq!(legacy_dataset(legacy).as_deref(), Some("STRUCTURED_POINTS"));
        let xml = b"<?xml version=\"1.0\"?>\n<VTKFile type = 'ImageData' version=\"1.0\">";
        assert_eq!(format_of_content(xml), Some(Format::Xml));
        assert_eq!(xml_type(xml).as_deref(), Some("ImageData"));
        let pvtu = b"<VTKFile type=\"PUnstructuredGrid\">";
        assert_eq!(format_of_content(pvtu), Some(Format::Parallel));
        assert_eq!(format_of_content(b"CDF\x01\0\0"), Some(Format::Exodus));
        assert_eq!(
            format_of_content(b"\x89HDF\r\n\x1a\n\0"),
            Some(Format::Exodus)
        );
        assert_eq!(format_of_content(b"<VTKFile type=\"PolyData\">"), None);
        assert_eq!(format_of_content(b"PK\x03\x04"), None);
        assert_eq!(
            describe_head(b"PK\x03\x04"),
            "it starts with \"PK\\x03\\x04\""
        );
        assert_eq!(describe_head(b""), "the file is empty");
    }
}
