//! Legacy `.vtk` reader, ASCII and BINARY (big-endian): UNSTRUCTURED_GRID,
//! and the structured datasets whose own sections `structured.rs` reads.
//!
//! Sections: POINTS; CELLS in the count-prefixed form (`CELLS n size`) and
//! the VTK 5.1 form (`CELLS noffsets nconn` + OFFSETS + CONNECTIVITY);
//! CELL_TYPES; POINT_DATA / CELL_DATA with SCALARS (any component count;
//! several components load as their magnitude `<name>_magnitude`), VECTORS
//! (as `<name>_magnitude`) and FIELD arrays (same rule); METADATA blocks.
//! NORMALS, TEXTURE_COORDINATES, TENSORS, COLOR_SCALARS, lookup tables and
//! id arrays are read past (with a warning where they carry data).

use super::lex::{Cursor, decode_name};
use super::structured::{Kind, Structured};
use crate::vtk::ImageGeometry;
use crate::vtk::numeric::Scalar;
use crate::vtk::{ReadOptions, VtkError, VtkRead};
use tetray_mesh::cells::CellError;
use tetray_mesh::cells::{CellArray, CellGrid};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Attributes {
    /// Before POINT_DATA / CELL_DATA: dataset-level FIELD data.
    Dataset,
    Point,
    Cell,
}

/// A count given by a header, with the line it came from.
#[derive(Debug, Clone, Copy)]
struct Declared {
    count: usize,
    line: usize,
}

/// Keywords that start a section (they end a METADATA block).
const SECTION_KEYWORDS: [&str; 17] = [
    "POINTS",
    "CELLS",
    "CELL_TYPES",
    "POINT_DATA",
    "CELL_DATA",
    "FIELD",
    "METADATA",
    "SCALARS",
    "VECTORS",
    "NORMALS",
    "TEXTURE_COORDINATES",
    "TENSORS",
    "TENSORS6",
    "COLOR_SCALARS",
    "LOOKUP_TABLE",
    "GLOBAL_IDS",
    "PEDIGREE_IDS",
];

struct Parser<'a> {
    cur: Cursor<'a>,
    grid: CellGrid,
    points: Option<Declared>,
    cells: Option<Declared>,
    cell_types: Option<Declared>,
    point_data: Option<Declared>,
    cell_data: Option<Declared>,
    mode: Attributes,
    /// None for UNSTRUCTURED_GRID.
    structured: Option<Structured>,
}

/// Parses a legacy VTK file held in memory; `name` is used in messages.
pub(crate) fn read_with(bytes: &[u8], name: &str, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
    crate::vtk::assemble(read_raw(bytes, name)?.0, name, opts)
}

/// The raw grid of a legacy VTK file, before ghost cells and assembly,
/// and for STRUCTURED_POINTS its index space.
pub(crate) fn read_raw(
    bytes: &[u8],
    name: &str,
) -> Result<(CellGrid, Option<ImageGeometry>), VtkError> {
    let mut p = Parser {
        cur: Cursor::new(bytes, name),
        grid: CellGrid::default(),
        points: None,
        cells: None,
        cell_types: None,
        point_data: None,
        cell_data: None,
        mode: Attributes::Dataset,
        structured: None,
    };
    p.header()?;
    while let Some(keyword) = p.cur.token() {
        let line = p.cur.line();
        let keyword = String::from_utf8_lossy(keyword).to_ascii_uppercase();
        if let Some(s) = p.structured.as_mut()
            && s.section(&keyword, &mut p.cur)?
        {
            continue;
        }
        p.section(&keyword, line)?;
    }
    // The declared counts are checked before the grid's points and cells
    // are made from the dimensions.
    let structured = p.structured.take();
    if let Some(s) = &structured {
        let (npoints, ncells) = s.counts(name)?;
        let line = 1;
        p.points = Some(Declared {
            count: npoints,
            line,
        });
        p.cells = Some(Declared {
            count: ncells,
            line,
        });
        p.cell_types = p.cells;
    }
    p.finish()?;
    if let Some(s) = &structured {
        s.finish(&mut p.grid, name)?;
    }
    let image = structured.as_ref().and_then(Structured::image);
    Ok((p.grid, image))
}

impl Parser<'_> {
    fn header(&mut self) -> Result<(), VtkError> {
        let first = self.cur.rest_of_line();
        let magic = b"# vtk DataFile Version";
        let ok = first.len() >= magic.len() && first[..magic.len()].eq_ignore_ascii_case(magic);
        if !ok {
            return Err(VtkError::Syntax {
                file: self.cur.file.into(),
                line: 1,
                message:
                    "not a legacy VTK file: the first line must be \"# vtk DataFile Version x.y\""
                        .into(),
            });
        }
        self.cur.rest_of_line(); // the title
        let format = self.cur.word("ASCII or BINARY")?;
        self.cur.binary = match format.to_ascii_uppercase().as_str() {
            "ASCII" => false,
            "BINARY" => true,
            _ => {
                return Err(self
                    .cur
                    .syntax(format!("expected ASCII or BINARY, found \"{format}\"")));
            }
        };
        let keyword = self.cur.word("DATASET")?;
        if !keyword.eq_ignore_ascii_case("DATASET") {
            if ["POINT_DATA", "CELL_DATA"]
                .iter()
                .any(|k| keyword.eq_ignore_ascii_case(k))
            {
                return Err(VtkError::UnsupportedDataset {
                    file: self.cur.file.into(),
                    found: "none (attribute data only)".into(),
                });
            }
            return Err(self
                .cur
                .syntax(format!("expected DATASET, found \"{keyword}\"")));
        }
        let dataset = self.cur.word("a dataset type")?;
        self.grid.dataset = "UnstructuredGrid";
        if let Some(kind) = Kind::of(dataset) {
            self.grid.dataset = kind.dataset();
            self.structured = Some(Structured::new(kind));
        } else if !dataset.eq_ignore_ascii_case("UNSTRUCTURED_GRID") {
            return Err(VtkError::UnsupportedDataset {
                file: self.cur.file.into(),
                found: dataset.into(),
            });
        }
        Ok(())
    }

    fn section(&mut self, keyword: &str, line: usize) -> Result<(), VtkError> {
        match keyword {
            "POINTS" => self.points(line),
            "CELLS" => self.cells(line),
            "CELL_TYPES" => self.cell_types(line),
            "POINT_DATA" | "CELL_DATA" => {
                let count = self.cur.count(&format!("the {keyword} count"))?;
                let declared = Some(Declared { count, line });
                let slot = if keyword == "POINT_DATA" {
                    self.mode = Attributes::Point;
                    &mut self.point_data
                } else {
                    self.mode = Attributes::Cell;
                    &mut self.cell_data
                };
                if slot.is_some() {
                    return Err(self.cur.syntax(format!("a second {keyword} section")));
                }
                *slot = declared;
                Ok(())
            }
            "FIELD" => self.field(),
            "METADATA" => {
                self.skip_metadata();
                Ok(())
            }
            "SCALARS"
            | "VECTORS"
            | "NORMALS"
            | "TEXTURE_COORDINATES"
            | "TENSORS"
            | "TENSORS6"
            | "COLOR_SCALARS"
            | "LOOKUP_TABLE"
            | "GLOBAL_IDS"
            | "PEDIGREE_IDS" => self.attribute(keyword, line),
            _ => Err(VtkError::Syntax {
                file: self.cur.file.into(),
                line,
                message: format!("unknown keyword \"{keyword}\""),
            }),
        }
    }

    fn data_type(&mut self, section: &str) -> Result<Scalar, VtkError> {
        let name = self.cur.word(&format!("the data type of {section}"))?;
        Scalar::from_legacy_name(name).ok_or_else(|| {
            VtkError::Cell(CellError::Unsupported {
                file: self.cur.file.into(),
                section: section.into(),
                what: "data type",
                value: name.into(),
            })
        })
    }

    fn points(&mut self, line: usize) -> Result<(), VtkError> {
        if self.points.is_some() || !self.grid.points.is_empty() {
            return Err(self.cur.syntax("a second POINTS section"));
        }
        let count = self.cur.count("the number of points")?;
        let section = format!("line {line}, POINTS");
        let ty = self.data_type(&section)?;
        let n = count
            .checked_mul(3)
            .ok_or_else(|| self.cur.syntax("too many points"))?;
        self.grid.points = self.cur.floats(ty, n, &section)?;
        self.grid.points_section = section;
        self.points = Some(Declared { count, line });
        Ok(())
    }

    fn cells(&mut self, line: usize) -> Result<(), VtkError> {
        if self.cells.is_some() {
            return Err(self.cur.syntax("a second CELLS section"));
        }
        let first = self.cur.count("the first CELLS count")?;
        let second = self.cur.count("the second CELLS count")?;
        if self.cur.next_is("OFFSETS") {
            return self.cells_5_1(first, second, line);
        }
        // Count-prefixed: `first` cells, `second` integers in all.
        let section = format!("line {line}, CELLS");
        let list = self.cur.ints(Scalar::I32, second, &section)?;
        let mut offsets = Vec::with_capacity(first.min(list.len()) + 1);
        let mut connectivity = Vec::with_capacity(list.len());
        offsets.push(0);
        let mut at = 0;
        for c in 0..first {
            let Some(&k) = list.get(at) else {
                return Err(VtkError::Cell(CellError::CountMismatch {
                    file: self.cur.file.into(),
                    section,
                    what: format!("cells in {second} integers (it ends before cell {c})"),
                    expected: first,
                    found: c,
                }));
            };
            let k = usize::try_from(k).ok().filter(|&k| k < list.len() - at);
            let Some(k) = k else {
                return Err(VtkError::Cell(CellError::Invalid {
                    file: self.cur.file.into(),
                    section,
                    message: format!(
                        "cell {c} claims {} points but only {} integers remain",
                        list[at],
                        list.len() - at - 1
                    ),
                }));
            };
            connectivity.extend_from_slice(&list[at + 1..at + 1 + k]);
            offsets.push(connectivity.len());
            at += k + 1;
        }
        if at != list.len() {
            return Err(VtkError::Cell(CellError::CountMismatch {
                file: self.cur.file.into(),
                section,
                what: format!("integers (the size in the CELLS header) for {first} cells"),
                expected: at,
                found: list.len(),
            }));
        }
        self.grid.offsets = offsets;
        self.grid.connectivity = connectivity;
        self.cells = Some(Declared { count: first, line });
        Ok(())
    }

    /// `CELLS noffsets nconnectivity`, then OFFSETS and CONNECTIVITY arrays.
    fn cells_5_1(&mut self, noffsets: usize, nconn: usize, line: usize) -> Result<(), VtkError> {
        self.cur.word("OFFSETS")?;
        let section = format!("line {}, CELLS OFFSETS", self.cur.line());
        let ty = self.data_type(&section)?;
        let offsets = self.cur.ints(ty, noffsets, &section)?;
        let keyword = self.cur.word("CONNECTIVITY")?;
        if !keyword.eq_ignore_ascii_case("CONNECTIVITY") {
            return Err(self
                .cur
                .syntax(format!("expected CONNECTIVITY, found \"{keyword}\"")));
        }
        let conn_section = format!("line {}, CELLS CONNECTIVITY", self.cur.line());
        let ty = self.data_type(&conn_section)?;
        self.grid.connectivity = self.cur.ints(ty, nconn, &conn_section)?;
        let mut starts = Vec::with_capacity(offsets.len());
        for (i, &o) in offsets.iter().enumerate() {
            let o = usize::try_from(o).ok().filter(|&o| o <= nconn);
            let previous = starts.last().copied().unwrap_or(0);
            match o {
                Some(o) if o >= previous && (i > 0 || o == 0) => starts.push(o),
                _ => {
                    return Err(VtkError::Cell(CellError::Invalid {
                        file: self.cur.file.into(),
                        section,
                        message: format!(
                            "offset {i} is {}: offsets must start at 0 and not decrease up to {nconn}",
                            offsets[i]
                        ),
                    }));
                }
            }
        }
        if let Some(&last) = starts.last()
            && last != nconn
        {
            return Err(VtkError::Cell(CellError::CountMismatch {
                file: self.cur.file.into(),
                section,
                what: "last offset (the CONNECTIVITY size)".into(),
                expected: nconn,
                found: last,
            }));
        }
        self.grid.offsets = starts;
        self.cells = Some(Declared {
            count: noffsets.saturating_sub(1),
            line,
        });
        Ok(())
    }

    fn cell_types(&mut self, line: usize) -> Result<(), VtkError> {
        if self.cell_types.is_some() {
            return Err(self.cur.syntax("a second CELL_TYPES section"));
        }
        let count = self.cur.count("the number of cell types")?;
        let section = format!("line {line}, CELL_TYPES");
        self.grid.types = self.cur.ints(Scalar::I32, count, &section)?;
        self.cell_types = Some(Declared { count, line });
        Ok(())
    }

    /// The tuple count of the current attribute section.
    fn tuples(&self, keyword: &str) -> Result<usize, VtkError> {
        match self.mode {
            Attributes::Point => Ok(self.point_data.map_or(0, |d| d.count)),
            Attributes::Cell => Ok(self.cell_data.map_or(0, |d| d.count)),
            Attributes::Dataset => Err(self
                .cur
                .syntax(format!("{keyword} before POINT_DATA or CELL_DATA"))),
        }
    }

    fn attribute(&mut self, keyword: &str, line: usize) -> Result<(), VtkError> {
        let n = self.tuples(keyword)?;
        let name = decode_name(self.cur.word(&format!("the name of the {keyword} array"))?);
        let place = match self.mode {
            Attributes::Point => "POINT_DATA",
            _ => "CELL_DATA",
        };
        let section = format!("line {line}, {place} {keyword} \"{name}\"");
        if keyword == "COLOR_SCALARS" || keyword == "LOOKUP_TABLE" {
            return self.skip_colors(keyword, n, &section);
        }
        // The data type and components of what follows, and whether it is
        // loaded as a field.
        let (ty, components, load) = match keyword {
            "SCALARS" => {
                let (ty, k) = self.scalars_header(&section)?;
                (ty, k, true)
            }
            "VECTORS" => (self.data_type(&section)?, 3, true),
            "NORMALS" => (self.data_type(&section)?, 3, false),
            "TENSORS" => (self.data_type(&section)?, 9, false),
            "TENSORS6" => (self.data_type(&section)?, 6, false),
            "TEXTURE_COORDINATES" => {
                let dim = self.cur.count("the texture coordinate dimension")?;
                (self.data_type(&section)?, dim, false)
            }
            // GLOBAL_IDS, PEDIGREE_IDS: ids, not physical values.
            _ => (self.data_type(&section)?, 1, false),
        };
        let total = n
            .checked_mul(components)
            .ok_or_else(|| self.cur.syntax("count overflow"))?;
        let values = self.cur.floats(ty, total, &section)?;
        if load {
            self.push_array(name, components, values, section);
        } else if keyword != "GLOBAL_IDS" && keyword != "PEDIGREE_IDS" {
            let warning =
                format!("{section}: skipped (only scalars, vectors and field arrays are loaded)");
            self.grid.warnings.push(warning);
        }
        Ok(())
    }

    /// `SCALARS name type [ncomp]`, then an optional `LOOKUP_TABLE name`.
    fn scalars_header(&mut self, section: &str) -> Result<(Scalar, usize), VtkError> {
        let ty = self.data_type(section)?;
        let components = match self.cur.line_word() {
            None => 1,
            Some(w) => match w.parse() {
                Ok(k) if (1..=16).contains(&k) => k,
                _ => {
                    return Err(self
                        .cur
                        .syntax(format!("{section}: bad component count \"{w}\"")));
                }
            },
        };
        if self.cur.next_is("LOOKUP_TABLE") {
            self.cur.word("LOOKUP_TABLE")?;
            self.cur.word("a lookup table name")?;
        }
        Ok((ty, components))
    }

    /// `COLOR_SCALARS name ncomp` (per tuple) or `LOOKUP_TABLE name size`
    /// (RGBA entries): floats in ASCII files, unsigned chars in BINARY ones.
    fn skip_colors(&mut self, keyword: &str, tuples: usize, section: &str) -> Result<(), VtkError> {
        let k = self.cur.count(&format!("the size of {section}"))?;
        let (per, count) = if keyword == "LOOKUP_TABLE" {
            (4, k)
        } else {
            (k, tuples)
        };
        let total = per
            .checked_mul(count)
            .ok_or_else(|| self.cur.syntax("count overflow"))?;
        let ty = if self.cur.binary {
            Scalar::U8
        } else {
            Scalar::F32
        };
        self.cur.floats(ty, total, section)?;
        Ok(())
    }

    fn push_array(&mut self, name: String, components: usize, values: Vec<f64>, section: String) {
        let array = CellArray {
            name,
            components,
            values,
            section,
            defined: None,
        };
        match self.mode {
            Attributes::Point => self.grid.point_arrays.push(array),
            Attributes::Cell => self.grid.cell_arrays.push(array),
            Attributes::Dataset => {}
        }
    }

    /// `FIELD name narrays`, then per array `name ncomp ntuples type` and
    /// its values. Dataset-level field data is read past.
    fn field(&mut self) -> Result<(), VtkError> {
        self.cur.word("the FIELD name")?;
        let narrays = self.cur.count("the number of FIELD arrays")?;
        for _ in 0..narrays {
            let array_line = self.cur.line();
            let name = decode_name(self.cur.word("a FIELD array name")?);
            if name == "NULL_ARRAY" {
                continue;
            }
            let place = match self.mode {
                Attributes::Dataset => "dataset",
                Attributes::Point => "POINT_DATA",
                Attributes::Cell => "CELL_DATA",
            };
            let section = format!("line {array_line}, {place} FIELD array \"{name}\"");
            let k = self
                .cur
                .count(&format!("the component count of {section}"))?;
            let ntuples = self.cur.count(&format!("the tuple count of {section}"))?;
            let ty = self.data_type(&section)?;
            let total = k
                .checked_mul(ntuples)
                .ok_or_else(|| self.cur.syntax("count overflow"))?;
            let values = self.cur.floats(ty, total, &section)?;
            if self.mode != Attributes::Dataset {
                let n = self.tuples("FIELD")?;
                if ntuples != n {
                    return Err(VtkError::Cell(CellError::CountMismatch {
                        file: self.cur.file.into(),
                        section,
                        what: format!("tuples (the {place} count)"),
                        expected: n,
                        found: ntuples,
                    }));
                }
                self.push_array(name, k, values, section);
            }
            if self.cur.next_is("METADATA") {
                self.cur.word("METADATA")?;
                self.skip_metadata();
            }
        }
        Ok(())
    }

    /// METADATA blocks (VTK >= 8) end at the first empty line. A section
    /// keyword also ends one, so a missing empty line cannot swallow the
    /// rest of the file.
    fn skip_metadata(&mut self) {
        self.cur.rest_of_line();
        while !self.cur.at_eof() {
            let line = self.cur.peek_line();
            let first = line.split(u8::is_ascii_whitespace).find(|t| !t.is_empty());
            let keyword = first.is_some_and(|t| {
                SECTION_KEYWORDS
                    .iter()
                    .any(|k| t.eq_ignore_ascii_case(k.as_bytes()))
            });
            if first.is_none() || keyword {
                break;
            }
            self.cur.rest_of_line();
        }
    }

    /// Checks that the declared counts agree with each other.
    fn finish(&mut self) -> Result<(), VtkError> {
        let file = self.cur.file;
        let Some(points) = self.points else {
            return Err(VtkError::Cell(CellError::Invalid {
                file: file.into(),
                section: "UNSTRUCTURED_GRID".into(),
                message: "no POINTS section".into(),
            }));
        };
        let ncells = self.cells.map_or(0, |c| c.count);
        let mismatch = |d: Declared, keyword: &str, what: &str, expected: usize| {
            VtkError::Cell(CellError::CountMismatch {
                file: file.into(),
                section: format!("line {}, {keyword}", d.line),
                what: what.into(),
                expected,
                found: d.count,
            })
        };
        match (self.cells, self.cell_types) {
            (Some(c), None) if c.count > 0 => {
                return Err(VtkError::Cell(CellError::Invalid {
                    file: file.into(),
                    section: format!("line {}, CELLS", c.line),
                    message: "CELLS without CELL_TYPES".into(),
                }));
            }
            (_, Some(t)) if t.count != ncells => {
                return Err(mismatch(
                    t,
                    "CELL_TYPES",
                    "cell types (the CELLS count)",
                    ncells,
                ));
            }
            _ => {}
        }
        if let Some(d) = self.point_data.filter(|d| d.count != points.count) {
            return Err(mismatch(
                d,
                "POINT_DATA",
                "tuples (the POINTS count)",
                points.count,
            ));
        }
        if let Some(d) = self.cell_data.filter(|d| d.count != ncells) {
            return Err(mismatch(d, "CELL_DATA", "tuples (the CELLS count)", ncells));
        }
        Ok(())
    }
}
