//! Files that name other files: parallel XML (`.pvtu`, `.pvts`, `.pvtr`,
//! `.pvti`: `<Piece Source="...">` under the `P...` dataset element) and
//! multi-block `.vtm` (`<vtkMultiBlockDataSet>` with nested `<Block>`s and,
//! for multi-piece blocks, `<Piece>`s, whose leaves are `<DataSet
//! file="...">`). Paths are relative to the folder of the file naming them.
//! Pieces and leaves are read in parallel, then welded (`pieces.rs`).

use std::path::{Path, PathBuf};
use tetray_mesh::cells::CellError;

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};
use rayon::prelude::*;

use super::xml::read_raw as read_xml_raw;
use super::xml::tree::find;
use super::{ReadOptions, VtkError, VtkRead, read_path};
use tetray_mesh::cells::{CellGrid, assemble_with};
use tetray_mesh::cells::{CellKind, classify, type_name};
use tetray_mesh::cells::{drop_ghosts, drop_global_ids, weld};

/// The parallel dataset elements and the serial type of their pieces.
const PARALLEL: [&str; 4] = [
    "PUnstructuredGrid",
    "PStructuredGrid",
    "PRectilinearGrid",
    "PImageData",
];

pub(crate) fn read_parallel(path: &Path, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
    let name = path.display().to_string();
    let grid = parallel_raw(path)?;
    ready(grid, &name, opts)
}

pub(crate) fn read_multiblock(
    path: &Path,
    block: Option<&str>,
    opts: &ReadOptions,
) -> Result<VtkRead, VtkError> {
    let name = path.display().to_string();
    let grid = multiblock_raw(path, block, 0)?;
    ready(grid, &name, opts)
}

/// The last steps shared by both: no ids as fields, a volume to render.
/// The pieces and blocks are welded into one raw grid first, so the
/// options (how higher-order cells are split) apply to all of them at once
/// and the points a split adds on a face two pieces share are made once.
fn ready(mut grid: CellGrid, name: &str, opts: &ReadOptions) -> Result<VtkRead, VtkError> {
    drop_global_ids(&mut grid);
    require_volume(&grid, name, "")?;
    Ok(assemble_with(grid, name, opts)?)
}

/// An XML element with its attributes and children (the files naming
/// other files are small).
#[derive(Debug, Default)]
struct Node {
    name: String,
    attributes: Vec<(String, String)>,
    children: Vec<Node>,
    line: usize,
}

impl Node {
    fn attribute(&self, key: &str) -> Option<&str> {
        find(&self.attributes, key)
    }
}

fn xml_tree(bytes: &[u8], file: &str) -> Result<Node, VtkError> {
    let line_at = |pos: usize| {
        1 + bytes[..pos.min(bytes.len())]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    };
    let xml_error = |pos: usize, message: String| VtkError::Xml {
        file: file.into(),
        line: line_at(pos),
        message,
    };
    let element = |e: &BytesStart<'_>, pos: usize| -> Result<Node, VtkError> {
        let mut attributes = Vec::new();
        for attr in e.attributes() {
            let attr = attr.map_err(|err| xml_error(pos, err.to_string()))?;
            let key = String::from_utf8_lossy(attr.key.local_name().as_ref()).into_owned();
            let value = attr
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| xml_error(pos, err.to_string()))?;
            attributes.push((key, value.into_owned()));
        }
        Ok(Node {
            name: String::from_utf8_lossy(e.local_name().as_ref()).into_owned(),
            attributes,
            children: Vec::new(),
            line: line_at(pos),
        })
    };
    let mut reader = Reader::from_reader(bytes);
    let mut stack: Vec<Node> = Vec::new();
    loop {
        let pos = reader.buffer_position() as usize;
        let event = reader
            .read_event()
            .map_err(|e| xml_error(reader.error_position() as usize, e.to_string()))?;
        let closed = match event {
            Event::Start(e) => {
                stack.push(element(&e, pos)?);
                None
            }
            Event::Empty(e) => Some(element(&e, pos)?),
            Event::End(_) => stack.pop(),
            Event::Eof => {
                return Err(match stack.last() {
                    Some(open) => {
                        xml_error(bytes.len(), format!("the file ends inside <{}>", open.name))
                    }
                    None => xml_error(0, "no <VTKFile> element".into()),
                });
            }
            _ => None,
        };
        if let Some(node) = closed {
            match stack.last_mut() {
                Some(parent) => parent.children.push(node),
                None if node.name == "VTKFile" => return Ok(node),
                None => {
                    let message = format!("the root element is <{}>, not <VTKFile>", node.name);
                    return Err(xml_error(pos, message));
                }
            }
        }
    }
}

fn folder_of(path: &Path) -> PathBuf {
    path.parent().map(Path::to_path_buf).unwrap_or_default()
}

/// A parallel file's pieces, ghost cells dropped, welded (global ids kept).
fn parallel_raw(path: &Path) -> Result<CellGrid, VtkError> {
    let name = path.display().to_string();
    let sources = piece_paths(path)?;
    let grids = sources
        .par_iter()
        .map(|piece| serial_raw(piece))
        .collect::<Result<Vec<_>, _>>()?;
    let mut grid = weld(grids, &name)?;
    grid.pieces.pieces = sources.len();
    Ok(grid)
}

/// The files of a parallel file's pieces, in its order; each must exist.
pub(super) fn piece_paths(path: &Path) -> Result<Vec<PathBuf>, VtkError> {
    let name = path.display().to_string();
    let root = xml_tree(&read_path(path)?, &name)?;
    let dataset = root
        .children
        .iter()
        .find(|n| PARALLEL.contains(&n.name.as_str()))
        .ok_or_else(|| VtkError::UnsupportedDataset {
            file: name.clone(),
            found: root.attribute("type").unwrap_or("none").into(),
        })?;
    let sources: Vec<&str> = dataset
        .children
        .iter()
        .filter(|n| n.name == "Piece")
        .filter_map(|n| n.attribute("Source"))
        .collect();
    if sources.is_empty() {
        return Err(VtkError::Cell(CellError::Invalid {
            file: name,
            section: format!("line {}, <{}>", dataset.line, dataset.name),
            message: "no <Piece Source=\"...\"> element".into(),
        }));
    }
    let folder = folder_of(path);
    sources
        .iter()
        .map(|&source| {
            let piece = folder.join(source);
            if !piece.is_file() {
                return Err(VtkError::MissingFile {
                    file: name.clone(),
                    what: "piece".into(),
                    source_name: source.into(),
                    path: piece.display().to_string(),
                });
            }
            Ok(piece)
        })
        .collect()
}

/// A serial XML file's raw grid with its ghost cells dropped; the places
/// its messages name start with the file, as several files are joined.
pub(super) fn serial_raw(path: &Path) -> Result<CellGrid, VtkError> {
    let name = path.display().to_string();
    let mut grid = read_xml_raw(&read_path(path)?, &name)?;
    drop_ghosts(&mut grid, &name)?;
    for array in grid.point_arrays.iter_mut().chain(&mut grid.cell_arrays) {
        array.section = format!("{name}, {}", array.section);
    }
    for warning in &mut grid.warnings {
        *warning = format!("{name}: {warning}");
    }
    Ok(grid)
}

/// A `<DataSet file>` of a multi-block file and the names leading to it.
struct Leaf {
    path: Vec<String>,
    file: String,
}

fn collect_leaves(node: &Node, path: &mut Vec<String>, out: &mut Vec<Leaf>) {
    for child in &node.children {
        let named = child.attribute("name").filter(|n| !n.is_empty());
        if let Some(n) = named {
            path.push(n.to_string());
        }
        match child.name.as_str() {
            "DataSet" => {
                if let Some(file) = child.attribute("file").filter(|f| !f.is_empty()) {
                    out.push(Leaf {
                        path: path.clone(),
                        file: file.to_string(),
                    });
                }
            }
            _ => collect_leaves(child, path, out),
        }
        if named.is_some() {
            path.pop();
        }
    }
}

fn matches_block(leaf: &Leaf, block: &str) -> bool {
    let joined = leaf.path.join("/");
    joined == block
        || joined.starts_with(&format!("{block}/"))
        || leaf.path.iter().any(|p| p == block)
}

/// What a leaf turned out to hold.
enum LeafGrid {
    Volume(Box<CellGrid>),
    /// Polygonal data, another format, or only lower-dimensional cells:
    /// a note, and the cells by type.
    Skipped(String, Vec<(i64, usize)>),
}

/// `.vtm` files may name `.vtm` files; deeper than this is taken for a loop.
const MAX_NESTING: usize = 16;

fn multiblock_raw(path: &Path, block: Option<&str>, depth: usize) -> Result<CellGrid, VtkError> {
    let name = path.display().to_string();
    if depth > MAX_NESTING {
        return Err(VtkError::Cell(CellError::Invalid {
            file: name,
            section: "<DataSet file>".into(),
            message: format!(
                "multi-block files nested more than {MAX_NESTING} deep (a file naming itself?)"
            ),
        }));
    }
    let root = xml_tree(&read_path(path)?, &name)?;
    let Some(top) = root
        .children
        .iter()
        .find(|n| n.name == "vtkMultiBlockDataSet")
    else {
        return Err(VtkError::UnsupportedDataset {
            file: name,
            found: root.attribute("type").unwrap_or("none").into(),
        });
    };
    let mut leaves = Vec::new();
    collect_leaves(top, &mut Vec::new(), &mut leaves);
    if let Some(block) = block {
        let all: Vec<String> = leaves.iter().map(|l| l.path.join("/")).collect();
        leaves.retain(|l| matches_block(l, block));
        if leaves.is_empty() {
            let mut names = all;
            names.dedup();
            return Err(VtkError::NoSuchBlock {
                file: name,
                block: block.into(),
                blocks: names.join(", "),
            });
        }
    }
    weld_leaves(&folder_of(path), &leaves, &name, depth)
}

/// The parts of one step of a data collection (`.pvd`), each a VTK XML
/// file, read in parallel and welded like the blocks of a `.vtm`; `name`
/// (the collection) is used in messages.
pub(crate) fn read_parts(
    files: &[PathBuf],
    name: &str,
    opts: &ReadOptions,
) -> Result<VtkRead, VtkError> {
    let leaves: Vec<Leaf> = files
        .iter()
        .enumerate()
        .map(|(i, file)| Leaf {
            path: vec![format!("part {i}")],
            file: file.display().to_string(),
        })
        .collect();
    let grid = weld_leaves(Path::new(""), &leaves, name, 0)?;
    ready(grid, name, opts)
}

/// The leaves' files (relative to `folder`) read in parallel; those with
/// volume cells welded, the others skipped with a note.
fn weld_leaves(
    folder: &Path,
    leaves: &[Leaf],
    name: &str,
    depth: usize,
) -> Result<CellGrid, VtkError> {
    let name = name.to_string();
    let read = leaves
        .par_iter()
        .map(|leaf| read_leaf(&folder.join(&leaf.file), leaf, &name, depth))
        .collect::<Result<Vec<_>, _>>()?;
    let mut grids = Vec::new();
    let mut notes = Vec::new();
    let mut surface: Vec<(i64, usize)> = Vec::new();
    for (leaf, grid) in leaves.iter().zip(read) {
        match grid {
            LeafGrid::Volume(g) => grids.push(*g),
            LeafGrid::Skipped(note, cells) => {
                notes.push(format!(
                    "block \"{}\" ({}): {note}",
                    leaf.path.join("/"),
                    leaf.file
                ));
                for (t, n) in cells {
                    match surface.iter_mut().find(|(s, _)| *s == t) {
                        Some((_, m)) => *m += n,
                        None => surface.push((t, n)),
                    }
                }
            }
        }
    }
    if grids.is_empty() {
        surface.sort_unstable();
        let found = describe_cells(&surface);
        return Err(VtkError::NoVolumeCells {
            file: name,
            found: format!(
                "{found} in {} block file{}",
                leaves.len(),
                if leaves.len() == 1 { "" } else { "s" }
            ),
        });
    }
    let (read_count, skipped) = (grids.len(), notes.len());
    let mut grid = weld(grids, &name)?;
    grid.pieces.blocks = read_count;
    grid.pieces.blocks_skipped = skipped;
    grid.warnings
        .extend(notes.into_iter().map(|n| format!("skipped {n}")));
    Ok(grid)
}

fn read_leaf(file: &Path, leaf: &Leaf, vtm: &str, depth: usize) -> Result<LeafGrid, VtkError> {
    let lower = leaf.file.to_ascii_lowercase();
    let ext = lower.rsplit('.').next().unwrap_or("");
    if ext == "vtp" {
        return Ok(LeafGrid::Skipped(
            "polygonal data (.vtp) is not a volume".into(),
            Vec::new(),
        ));
    }
    if !file.is_file() {
        return Err(VtkError::MissingFile {
            file: vtm.into(),
            what: format!("block \"{}\": file", leaf.path.join("/")),
            source_name: leaf.file.clone(),
            path: file.display().to_string(),
        });
    }
    let grid = match ext {
        "vtu" | "vts" | "vtr" | "vti" => serial_raw(file)?,
        "pvtu" | "pvts" | "pvtr" | "pvti" => parallel_raw(file)?,
        "vtm" => multiblock_raw(file, None, depth + 1)?,
        _ => {
            return Ok(LeafGrid::Skipped(
                format!("format .{ext} is not read in multi-block files"),
                Vec::new(),
            ));
        }
    };
    let cells = lower_dim_cells(&grid);
    if cells.is_none() {
        return Ok(LeafGrid::Volume(Box::new(grid)));
    }
    let cells = cells.unwrap_or_default();
    Ok(LeafGrid::Skipped(describe_cells(&cells), cells))
}

/// `None` when the grid has a 3-D cell; else its cells by type.
fn lower_dim_cells(grid: &CellGrid) -> Option<Vec<(i64, usize)>> {
    let mut counts: Vec<(i64, usize)> = Vec::new();
    for &t in &grid.types {
        if classify(t) != CellKind::LowerDim {
            return None;
        }
        match counts.iter_mut().find(|(s, _)| *s == t) {
            Some((_, n)) => *n += 1,
            None => counts.push((t, 1)),
        }
    }
    counts.sort_unstable();
    Some(counts)
}

/// The error for a grid without a volume cell (`place` adds to the file).
pub(crate) fn require_volume(grid: &CellGrid, file: &str, place: &str) -> Result<(), VtkError> {
    match lower_dim_cells(grid) {
        None => Ok(()),
        Some(cells) => Err(VtkError::NoVolumeCells {
            file: format!("{file}{place}"),
            found: describe_cells(&cells),
        }),
    }
}

/// "only surface cells (16 quadrilaterals, 2 triangles)", "no cells".
fn describe_cells(cells: &[(i64, usize)]) -> String {
    if cells.is_empty() {
        return "no cells".into();
    }
    let surface = cells
        .iter()
        .all(|&(t, _)| matches!(t, 5..=9 | 22 | 23 | 28 | 30 | 34 | 36 | 69 | 70 | 76 | 77));
    let list: Vec<String> = cells
        .iter()
        .map(|&(t, n)| {
            let plural = match t {
                1 => "vertices",
                3 => "lines",
                5 => "triangles",
                6 => "triangle strips",
                7 => "polygons",
                8 => "pixels",
                9 => "quadrilaterals",
                _ => "",
            };
            if plural.is_empty() {
                format!("{n} cells of type {t} ({})", type_name(t))
            } else {
                format!("{n} {plural}")
            }
        })
        .collect();
    let kind = if surface {
        "surface"
    } else {
        "lower-dimensional"
    };
    format!("only {kind} cells ({})", list.join(", "))
}
