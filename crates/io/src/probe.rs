//! What a file holds, before reading it: its format by the file's name, and
//! by its first bytes where the name does not say (a legacy VTK header, a
//! VTK XML root element, a netCDF or HDF5 signature); an HDF5 file is told
//! apart by its groups (VTKHDF's `/VTKHDF`, a CGNS tree, else netCDF-4, read as Exodus
//! II); and whether it is image data, which shear-warp renders as the
//! regular grid it is.

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
    VtkHdf,
    /// An HDF5 container by name (`.hdf`, `.h5`...) or signature, whose
    /// groups say what it holds; never returned by [`format_for`].
    Hdf5,
    /// A time series of files: `*.series` (JSON) or `.pvd`.
    Series,
    /// An OpenFOAM case: its folder, `controlDict` or a `.foam` marker.
    OpenFoam,
    /// An EnSight Gold case file (`.case`).
    EnSight,
    /// CGNS (`.cgns`; HDF5 or ADF storage).
    Cgns,
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
            Format::VtkHdf => "VTKHDF",
            Format::Hdf5 => "HDF5",
            Format::Series => "file series",
            Format::OpenFoam => "OpenFOAM",
            Format::EnSight => "EnSight Gold",
            Format::Cgns => "CGNS",
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
    let (format, by_content, head) = format_for(path)?;
    let kind = match format {
        Format::Xml if xml_type(&head).as_deref() == Some("ImageData") => DataKind::ImageData,
        Format::Legacy if legacy_dataset(&head).as_deref() == Some("STRUCTURED_POINTS") => {
            DataKind::ImageData
        }
        Format::VtkHdf if crate::vtkhdf::is_image_data(path) => DataKind::ImageData,
        _ => DataKind::Cells,
    };
    Ok(Probe {
        format,
        kind,
        by_content,
    })
}

/// The reader for the file at `path`: by its name, else by its first
/// bytes, an HDF5 container by its groups; whether the content decided;
/// and the first bytes.
///
/// # Errors
/// As [`probe`].
pub(crate) fn format_for(path: &Path) -> Result<(Format, bool, Vec<u8>), IoError> {
    let file = path.display().to_string();
    if path.is_dir() {
        if crate::openfoam::is_case(path) {
            return Ok((Format::OpenFoam, true, Vec::new()));
        }
        return Err(IoError::UnknownFormat {
            file,
            seen: "a folder, not an OpenFOAM case (no constant/polyMesh, processor* or \
                   system/controlDict)"
                .into(),
        });
    }
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
    let format = match format {
        Format::Hdf5 if crate::vtkhdf::is_vtkhdf(path) => Format::VtkHdf,
        Format::Hdf5 if crate::cgns::is_cgns(path) => Format::Cgns,
        // netCDF-4 is HDF5: Exodus II files are written so.
        Format::Hdf5 => Format::Exodus,
        other => other,
    };
    Ok((format, by_content, head))
}

/// The format a file name says (any case).
pub(crate) fn format_of(path: &Path) -> Option<Format> {
    let name = path.file_name()?.to_string_lossy().to_lowercase();
    let ext = name.rsplit_once('.').map_or("", |(_, e)| e);
    if crate::series::is_series_name(&name) {
        Some(Format::Series)
    } else if ["cgns", "adf"].contains(&ext) {
        Some(Format::Cgns)
    } else if ext == "case" {
        Some(Format::EnSight)
    } else if ["foam", "openfoam"].contains(&ext) || name == "controldict" {
        Some(Format::OpenFoam)
    } else if ext == "vtk" {
        Some(Format::Legacy)
    } else if ["vtu", "vts", "vtr", "vti"].contains(&ext) {
        Some(Format::Xml)
    } else if ["pvtu", "pvts", "pvtr", "pvti"].contains(&ext) {
        Some(Format::Parallel)
    } else if ext == "vtm" {
        Some(Format::MultiBlock)
    } else if ["e", "exo", "ex2", "exii", "g", "gen"].contains(&ext) || is_spread_exodus(&name) {
        Some(Format::Exodus)
    } else if ext == "vtkhdf" {
        Some(Format::VtkHdf)
    } else if ["hdf", "hdf5", "h5", "he5"].contains(&ext) {
        Some(Format::Hdf5)
    } else if name.ends_with("xyz.bin") || name.ends_with(".xyz") || name.ends_with(".x") {
        Some(Format::Plot3d)
    } else {
        None
    }
}

/// The file of one process of an Exodus model spread over several: its
/// name ends in `.e-s<step>`, `.e-s.<step>`, `.exo-s<step>`..., optionally
/// followed by `.<processes>.<rank>` (`model.e-s.0002.4.0`).
fn is_spread_exodus(name: &str) -> bool {
    ["e", "exo", "ex2", "g"].iter().any(|ext| {
        name.match_indices(&format!(".{ext}-s")).any(|(at, m)| {
            let rest = &name[at + m.len()..];
            let rest = rest.strip_prefix('.').unwrap_or(rest);
            !rest.is_empty()
                && rest
                    .split('.')
                    .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
        })
    })
}

/// The format the first bytes of a file say: a legacy VTK header, a VTK
/// XML root element, a netCDF classic signature (read as Exodus II) or an
/// HDF5 signature (resolved by its groups).
fn format_of_content(head: &[u8]) -> Option<Format> {
    if head.starts_with(b"# vtk DataFile") {
        return Some(Format::Legacy);
    }
    let netcdf = [&b"CDF\x01"[..], b"CDF\x02", b"CDF\x05"];
    if netcdf.iter().any(|sig| head.starts_with(sig)) {
        return Some(Format::Exodus);
    }
    if head.starts_with(b"\x89HDF\r\n\x1a\n") {
        return Some(Format::Hdf5);
    }
    if crate::cgns::is_adf(head) {
        return Some(Format::Cgns);
    }
    if crate::series::is_series_content(head) {
        return Some(Format::Series);
    }
    let text = String::from_utf8_lossy(head);
    if text.contains("FoamFile") {
        return Some(Format::OpenFoam);
    }
    let lower = text.to_lowercase();
    if lower.contains("format") && lower.contains("ensight gold") {
        return Some(Format::EnSight);
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
        for name in ["can.e-s002", "can.e-s.0002", "m.exo-s3.4.0"] {
            assert_eq!(format_of(p(name)), Some(Format::Exodus), "{name}");
        }
        assert_eq!(format_of(p("a.vtkhdf")), Some(Format::VtkHdf));
        assert_eq!(format_of(p("a.HDF")), Some(Format::Hdf5));

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
            Some(Format::Hdf5)
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
