//! The XML structure of a serial VTK XML file (`.vtu`, `.vts`, `.vtr`,
//! `.vti`): VTKFile attributes, the dataset element's attributes (extents,
//! origin, spacing), Pieces and their DataArrays (attributes and text), and
//! where the appended data starts. Decoding the arrays is `data.rs`'s job.
//!
//! Appended raw data is not XML, so parsing stops at the start tag of
//! `<AppendedData>`; its bytes are located by hand from there.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};
use tetray_mesh::cells::CellError;

use crate::vtk::VtkError;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Format {
    Ascii,
    Binary,
    Appended { offset: usize },
}

#[derive(Debug, Clone)]
pub(crate) struct XmlArray {
    pub name: Option<String>,
    /// The `type` attribute as written (checked when decoded).
    pub type_name: String,
    pub components: usize,
    pub format: Format,
    /// Text directly inside the element (not inside nested elements such as
    /// VTK's `<InformationKey>`).
    pub text: Vec<u8>,
    pub line: usize,
}

#[derive(Debug, Clone, Default)]
pub(crate) struct XmlPiece {
    pub line: usize,
    pub npoints: usize,
    pub ncells: usize,
    pub points: Option<XmlArray>,
    pub cells: Vec<XmlArray>,
    pub point_data: Vec<XmlArray>,
    pub cell_data: Vec<XmlArray>,
    /// `<Coordinates>` arrays of a RectilinearGrid (x, y, z).
    pub coordinates: Vec<XmlArray>,
    /// The Piece's attributes (`Extent` of structured pieces).
    pub attributes: Vec<(String, String)>,
    /// The point array that `<PointData GlobalIds="...">` names.
    pub global_ids: Option<String>,
}

impl XmlPiece {
    pub fn attribute(&self, key: &str) -> Option<&str> {
        find(&self.attributes, key)
    }
}

/// The value of `key` in a list of attributes.
pub(crate) fn find<'v>(attributes: &'v [(String, String)], key: &str) -> Option<&'v str> {
    attributes
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

/// The XML dataset types read: the `type` of `<VTKFile>`.
pub(crate) const DATASETS: [&str; 4] = [
    "UnstructuredGrid",
    "StructuredGrid",
    "RectilinearGrid",
    "ImageData",
];

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum AppendedEncoding {
    Raw,
    Base64,
}

#[derive(Debug, Clone)]
pub(crate) struct Appended<'a> {
    pub encoding: AppendedEncoding,
    /// Everything after the `_` marker (raw: to the end of the file; base64:
    /// to the next `<`).
    pub data: &'a [u8],
}

#[derive(Debug, Clone)]
pub(crate) struct VtuDoc<'a> {
    /// One of [`DATASETS`].
    pub dataset: String,
    /// The dataset element's attributes (`WholeExtent`, `Origin`...).
    pub dataset_attributes: Vec<(String, String)>,
    pub big_endian: bool,
    pub header_u64: bool,
    pub compressor: Option<String>,
    pub pieces: Vec<XmlPiece>,
    pub appended: Option<Appended<'a>>,
}

/// Where DataArrays inside the current element go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Target {
    Points,
    Cells,
    PointData,
    CellData,
    Coordinates,
    Ignored,
}

/// Turns byte offsets into 1-based line numbers, for offsets that only grow.
struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Lines<'_> {
    fn at(&mut self, pos: usize) -> usize {
        let pos = pos.min(self.bytes.len());
        if pos < self.pos {
            self.pos = 0;
            self.line = 1;
        }
        self.line += self.bytes[self.pos..pos]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.pos = pos;
        self.line
    }
}

struct Builder<'a> {
    file: &'a str,
    lines: Lines<'a>,
    doc: VtuDoc<'a>,
    /// Local names of the open elements.
    stack: Vec<String>,
    piece: Option<XmlPiece>,
    target: Target,
    /// The open DataArray and the stack depth of its element.
    array: Option<(XmlArray, usize)>,
    seen_root: bool,
}

pub(crate) fn parse<'a>(bytes: &'a [u8], file: &'a str) -> Result<VtuDoc<'a>, VtkError> {
    let mut reader = Reader::from_reader(bytes);
    let mut b = Builder {
        file,
        lines: Lines {
            bytes,
            pos: 0,
            line: 1,
        },
        doc: VtuDoc {
            dataset: String::new(),
            dataset_attributes: Vec::new(),
            big_endian: false,
            header_u64: false,
            compressor: None,
            pieces: Vec::new(),
            appended: None,
        },
        stack: Vec::new(),
        piece: None,
        target: Target::Ignored,
        array: None,
        seen_root: false,
    };
    loop {
        let start = reader.buffer_position() as usize;
        let event = reader.read_event().map_err(|e| {
            let at = reader.error_position() as usize;
            b.xml_error(at, e.to_string())
        })?;
        match event {
            Event::Start(e) => {
                if local_name(&e) == "AppendedData" {
                    b.appended(&e, start, reader.buffer_position() as usize, bytes)?;
                    break;
                }
                b.open(&e, start)?;
            }
            Event::Empty(e) => {
                b.open(&e, start)?;
                b.close(start)?;
            }
            Event::End(_) => b.close(start)?,
            Event::Text(t) => b.text(&t),
            Event::CData(t) => b.text(&t),
            Event::GeneralRef(_) if b.array.is_some() => {
                return Err(b.xml_error(start, "entity reference inside a DataArray".into()));
            }
            Event::Eof => {
                if let Some(open) = b.stack.last() {
                    let message = format!("the file ends inside <{open}>");
                    return Err(b.xml_error(bytes.len(), message));
                }
                break;
            }
            _ => {}
        }
    }
    if !b.seen_root {
        return Err(b.xml_error(0, "no <VTKFile> element".into()));
    }
    Ok(b.doc)
}

fn local_name(e: &BytesStart<'_>) -> String {
    String::from_utf8_lossy(e.local_name().as_ref()).into_owned()
}

impl<'a> Builder<'a> {
    fn xml_error(&mut self, at: usize, message: String) -> VtkError {
        VtkError::Xml {
            file: self.file.into(),
            line: self.lines.at(at),
            message,
        }
    }

    /// The element's attributes, unescaped.
    fn attributes(
        &mut self,
        e: &BytesStart<'_>,
        at: usize,
    ) -> Result<Vec<(String, String)>, VtkError> {
        let mut out = Vec::new();
        for attr in e.attributes() {
            let attr = attr.map_err(|err| self.xml_error(at, err.to_string()))?;
            let key = String::from_utf8_lossy(attr.key.local_name().as_ref()).into_owned();
            let value = attr
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| self.xml_error(at, err.to_string()))?;
            out.push((key, value.into_owned()));
        }
        Ok(out)
    }

    fn open(&mut self, e: &BytesStart<'_>, at: usize) -> Result<(), VtkError> {
        let name = local_name(e);
        let parent = self.stack.last().map(String::as_str);
        match (parent, name.as_str()) {
            (None, "VTKFile") => self.vtk_file(e, at)?,
            (None, other) => {
                let message = format!("the root element is <{other}>, not <VTKFile>");
                return Err(self.xml_error(at, message));
            }
            (Some("VTKFile"), other)
                if other == self.doc.dataset || self.doc.dataset.is_empty() =>
            {
                if !DATASETS.contains(&other) {
                    return Err(VtkError::UnsupportedDataset {
                        file: self.file.into(),
                        found: other.into(),
                    });
                }
                self.doc.dataset = other.into();
                self.doc.dataset_attributes = self.attributes(e, at)?;
            }
            (Some("VTKFile"), other) if DATASETS.contains(&other) => {
                let message = format!(
                    "<VTKFile type=\"{}\"> holds a <{other}> element",
                    self.doc.dataset
                );
                return Err(self.xml_error(at, message));
            }
            (Some("VTKFile"), other) if other != "AppendedData" => {
                return Err(VtkError::UnsupportedDataset {
                    file: self.file.into(),
                    found: other.into(),
                });
            }
            (Some(parent), "Piece") if parent == self.doc.dataset => {
                let attrs = self.attributes(e, at)?;
                let line = self.lines.at(at);
                let count = |key: &str| -> Result<usize, VtkError> {
                    let value = attrs
                        .iter()
                        .find(|(k, _)| k == key)
                        .map(|(_, v)| v.as_str());
                    value
                        .unwrap_or("0")
                        .trim()
                        .parse()
                        .map_err(|_| VtkError::Xml {
                            file: self.file.into(),
                            line,
                            message: format!(
                                "<Piece> {key}=\"{}\" is not a count",
                                value.unwrap_or("")
                            ),
                        })
                };
                self.piece = Some(XmlPiece {
                    line,
                    npoints: count("NumberOfPoints")?,
                    ncells: count("NumberOfCells")?,
                    attributes: attrs.clone(),
                    ..XmlPiece::default()
                });
            }
            (Some("Piece"), section) => {
                self.target = match section {
                    "Points" => Target::Points,
                    "Cells" => Target::Cells,
                    "PointData" => Target::PointData,
                    "CellData" => Target::CellData,
                    "Coordinates" => Target::Coordinates,
                    _ => Target::Ignored,
                };
                if section == "PointData" {
                    let ids = find(&self.attributes(e, at)?, "GlobalIds").map(str::to_string);
                    if let Some(piece) = self.piece.as_mut() {
                        piece.global_ids = ids;
                    }
                }
            }
            (Some(_), "DataArray") if self.array.is_none() && self.piece.is_some() => {
                let array = self.data_array(e, at)?;
                self.array = Some((array, self.stack.len() + 1));
            }
            _ => {}
        }
        self.stack.push(name);
        Ok(())
    }

    fn vtk_file(&mut self, e: &BytesStart<'_>, at: usize) -> Result<(), VtkError> {
        self.seen_root = true;
        let section = format!("line {}, <VTKFile>", self.lines.at(at));
        let unsupported = |what: &'static str, value: &str| {
            VtkError::Cell(CellError::Unsupported {
                file: self.file.into(),
                section: section.clone(),
                what,
                value: value.into(),
            })
        };
        for (key, value) in self.attributes(e, at)? {
            match key.as_str() {
                "type" if !DATASETS.contains(&value.as_str()) => {
                    return Err(VtkError::UnsupportedDataset {
                        file: self.file.into(),
                        found: value,
                    });
                }
                "type" => self.doc.dataset = value,
                "byte_order" => {
                    self.doc.big_endian = match value.as_str() {
                        "LittleEndian" => false,
                        "BigEndian" => true,
                        _ => return Err(unsupported("byte_order", &value)),
                    }
                }
                "header_type" => {
                    self.doc.header_u64 = match value.as_str() {
                        "UInt32" => false,
                        "UInt64" => true,
                        _ => return Err(unsupported("header_type", &value)),
                    }
                }
                "compressor" if !value.is_empty() => self.doc.compressor = Some(value),
                _ => {}
            }
        }
        Ok(())
    }

    fn data_array(&mut self, e: &BytesStart<'_>, at: usize) -> Result<XmlArray, VtkError> {
        let line = self.lines.at(at);
        let mut array = XmlArray {
            name: None,
            type_name: String::new(),
            components: 1,
            format: Format::Ascii,
            text: Vec::new(),
            line,
        };
        let mut offset = None;
        let mut format = String::from("ascii");
        for (key, value) in self.attributes(e, at)? {
            match key.as_str() {
                "Name" => array.name = Some(value),
                "type" => array.type_name = value,
                "format" => format = value,
                "NumberOfComponents" => {
                    array.components =
                        value
                            .trim()
                            .parse()
                            .ok()
                            .filter(|&k| k > 0)
                            .ok_or_else(|| {
                                self.xml_error(
                                    at,
                                    format!(
                                        "NumberOfComponents=\"{value}\" is not a positive count"
                                    ),
                                )
                            })?
                }
                "offset" => {
                    offset = Some(value.trim().parse().map_err(|_| {
                        self.xml_error(at, format!("offset=\"{value}\" is not a byte offset"))
                    })?)
                }
                _ => {}
            }
        }
        array.format = match (format.as_str(), offset) {
            ("ascii", _) => Format::Ascii,
            ("binary", _) => Format::Binary,
            ("appended", Some(offset)) => Format::Appended { offset },
            ("appended", None) => {
                return Err(self.xml_error(at, "an appended DataArray without an offset".into()));
            }
            (other, _) => {
                return Err(VtkError::Cell(CellError::Unsupported {
                    file: self.file.into(),
                    section: format!("line {line}, DataArray"),
                    what: "DataArray format",
                    value: other.into(),
                }));
            }
        };
        Ok(array)
    }

    fn close(&mut self, at: usize) -> Result<(), VtkError> {
        let depth = self.stack.len();
        let Some(name) = self.stack.pop() else {
            return Err(self.xml_error(at, "an end tag without a start tag".into()));
        };
        if self.array.as_ref().is_some_and(|(_, d)| *d == depth) {
            if let (Some((array, _)), Some(piece)) = (self.array.take(), self.piece.as_mut()) {
                match self.target {
                    Target::Points if piece.points.is_none() => piece.points = Some(array),
                    Target::Cells => piece.cells.push(array),
                    Target::PointData => piece.point_data.push(array),
                    Target::CellData => piece.cell_data.push(array),
                    Target::Coordinates => piece.coordinates.push(array),
                    _ => {}
                }
            }
        } else if name == "Piece" {
            if let Some(piece) = self.piece.take() {
                self.doc.pieces.push(piece);
            }
        } else if self.stack.last().is_some_and(|p| p == "Piece") {
            self.target = Target::Ignored;
        }
        Ok(())
    }

    fn text(&mut self, t: &[u8]) {
        let depth = self.stack.len();
        if let Some((array, d)) = self.array.as_mut()
            && *d == depth
        {
            array.text.extend_from_slice(t);
            array.text.push(b' ');
        }
    }

    /// `<AppendedData encoding="...">`, whitespace, `_`, then the data.
    fn appended(
        &mut self,
        e: &BytesStart<'_>,
        at: usize,
        end: usize,
        bytes: &'a [u8],
    ) -> Result<(), VtkError> {
        let mut encoding = AppendedEncoding::Base64;
        for (key, value) in self.attributes(e, at)? {
            if key == "encoding" {
                encoding = match value.as_str() {
                    "raw" => AppendedEncoding::Raw,
                    "base64" => AppendedEncoding::Base64,
                    other => {
                        return Err(VtkError::Cell(CellError::Unsupported {
                            file: self.file.into(),
                            section: format!("line {}, <AppendedData>", self.lines.at(at)),
                            what: "AppendedData encoding",
                            value: other.into(),
                        }));
                    }
                };
            }
        }
        let rest = &bytes[end..];
        let skip = rest.iter().take_while(|b| b.is_ascii_whitespace()).count();
        if rest.get(skip) != Some(&b'_') {
            let message = "appended data must start with '_'".into();
            return Err(self.xml_error(end + skip, message));
        }
        let mut data = &rest[skip + 1..];
        if encoding == AppendedEncoding::Base64 {
            data = &data[..data.iter().position(|&b| b == b'<').unwrap_or(data.len())];
        }
        self.doc.appended = Some(Appended { encoding, data });
        Ok(())
    }
}

/// The opening `<VTKFile ...` tag of an UnstructuredGrid file written with
/// `big_endian` byte order and `header_u64` headers, after the XML
/// declaration; the caller closes the tag (after a compressor, if any).
pub(super) fn open_vtkfile(
    w: &mut impl std::io::Write,
    big_endian: bool,
    header_u64: bool,
) -> std::io::Result<()> {
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    write!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"{}\" header_type=\"{}\"",
        if big_endian {
            "BigEndian"
        } else {
            "LittleEndian"
        },
        if header_u64 { "UInt64" } else { "UInt32" },
    )
}

/// Escapes text for an XML attribute value.
pub(super) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(c),
        }
    }
    out
}
