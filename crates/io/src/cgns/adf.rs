//! CGNS's older storage, ADF (the Advanced Data Format of the CGNS
//! mid-level library). A file is a 186-byte header, a free-chunk table and
//! a tree of 246-byte node headers. Each node holds its name, label, data
//! type and dimensions, a table of its children, and its data in one chunk
//! or a table of chunks.
//!
//! Disk pointers are a block of 4096 bytes and an offset in it. Files
//! whose what-string says version `A` write the pointers, the counts and
//! the dimensions as ASCII hexadecimal. Version `B` writes pointers and
//! dimensions as integers in the file's byte order. The header's numeric
//! format says that byte order (`B` big-endian, `L` little-endian IEEE).
//! Node data is stored in that order too, and arrays in Fortran order.
//!
//! The tree is read once, bounded by the file's length: a node or a table
//! that lies past the end, a cycle, or a wrong tag is an error. Data is
//! read on demand, after its size is checked against the chunks that hold
//! it.

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

use super::CgnsError;

const BLOCK: u64 = 4096;
const FILE_HEADER: usize = 186;
const NODE_HEADER: usize = 246;
const POINTER: usize = 12;
const NAME: usize = 32;
/// CGNS trees are a few levels deep; a deeper one is a corrupt file.
const MAX_DEPTH: usize = 64;
/// Links followed in one lookup.
const MAX_LINKS: usize = 8;

/// One node of the tree.
struct Node {
    label: String,
    data_type: String,
    dims: Vec<u64>,
    chunks: u64,
    data: u64,
    children: Vec<String>,
}

/// An ADF file's tree, by absolute path (`/Base/Zone`).
pub(super) struct Adf {
    file: RefCell<File>,
    len: u64,
    name: String,
    /// Version `A`: ASCII hexadecimal pointers and dimensions.
    ascii: bool,
    little: bool,
    nodes: HashMap<String, Node>,
}

impl Adf {
    pub fn open(path: &Path) -> Result<Adf, CgnsError> {
        let name = path.display().to_string();
        let io = |source| CgnsError::Io {
            file: name.clone(),
            source,
        };
        let file = File::open(path).map_err(io)?;
        let len = file.metadata().map_err(io)?.len();
        let mut adf = Adf {
            file: RefCell::new(file),
            len,
            name,
            ascii: true,
            little: true,
            nodes: HashMap::new(),
        };
        let header = adf.bytes(0, FILE_HEADER, "the ADF file header")?;
        for (at, tag) in [
            (32, b"AdF0"),
            (64, b"AdF1"),
            (96, b"AdF2"),
            (102, b"AdF3"),
            (130, b"AdF4"),
            (182, b"AdF5"),
        ] {
            if &header[at..at + 4] != tag {
                return Err(adf.invalid("the ADF file header", format!("no {} tag", ascii(tag))));
            }
        }
        adf.ascii = match header[25] {
            b'A' => true,
            b'B' => false,
            v => {
                return Err(adf.invalid(
                    "the ADF file header",
                    format!("database version {:?} is not read", char::from(v)),
                ));
            }
        };
        adf.little = match header[100] {
            b'L' => true,
            b'B' => false,
            v => {
                return Err(adf.invalid(
                    "the ADF file header",
                    format!(
                        "numeric format {:?} is not read (IEEE big- and little-endian are)",
                        char::from(v)
                    ),
                ));
            }
        };
        let root = adf.pointer(&header[134..134 + POINTER], "the ADF file header")?;
        // The position of the last byte written: a shorter file was cut
        // (what follows it, up to the end of its block, is unused).
        let last = adf.pointer(&header[146..146 + POINTER], "the ADF file header")?;
        if last >= len {
            return Err(CgnsError::Truncated {
                file: adf.name,
                what: "the ADF file (its header's end of file)".into(),
                expected: last + 1,
                found: len,
            });
        }
        adf.read_tree(root)?;
        Ok(adf)
    }

    pub fn invalid(&self, what: &str, message: String) -> CgnsError {
        CgnsError::Invalid {
            file: self.name.clone(),
            what: what.into(),
            message,
        }
    }

    /// `count` bytes at `at`, after checking that the file holds them.
    fn bytes(&self, at: u64, count: usize, what: &str) -> Result<Vec<u8>, CgnsError> {
        let end = at.saturating_add(count as u64);
        if end > self.len {
            return Err(CgnsError::Truncated {
                file: self.name.clone(),
                what: what.into(),
                expected: end,
                found: self.len,
            });
        }
        let mut out = vec![0u8; count];
        let mut file = self.file.borrow_mut();
        file.seek(SeekFrom::Start(at))
            .and_then(|_| file.read_exact(&mut out))
            .map_err(|source| CgnsError::Io {
                file: self.name.clone(),
                source,
            })?;
        Ok(out)
    }

    /// A 12-byte disk pointer as a file position.
    fn pointer(&self, raw: &[u8], what: &str) -> Result<u64, CgnsError> {
        let (block, offset) = if self.ascii {
            (hex(&raw[..8]), hex(&raw[8..12]))
        } else {
            (Some(self.int(&raw[..8])), Some(self.int(&raw[8..12])))
        };
        match (block, offset) {
            (Some(b), Some(o)) if o <= BLOCK => b
                .checked_mul(BLOCK)
                .and_then(|p| p.checked_add(o))
                .ok_or_else(|| self.invalid(what, "a disk pointer past any file".into())),
            _ => Err(self.invalid(
                what,
                format!("disk pointer {:?} is not a block and an offset", ascii(raw)),
            )),
        }
    }

    /// An unsigned integer of 4 or 8 bytes in the file's byte order.
    fn int(&self, raw: &[u8]) -> u64 {
        let mut v = 0u64;
        for i in 0..raw.len() {
            let b = if self.little {
                raw[raw.len() - 1 - i]
            } else {
                raw[i]
            };
            v = (v << 8) | u64::from(b);
        }
        v
    }

    /// The end of the chunk at `at` (where its end tag starts), after
    /// checking its start tag; the chunk's content lies between.
    fn chunk(&self, at: u64, tag: &[u8; 4], what: &str) -> Result<(u64, u64), CgnsError> {
        let head = self.bytes(at, 4 + POINTER, what)?;
        if &head[..4] != tag {
            return Err(self.invalid(what, format!("no {} tag", ascii(tag))));
        }
        let end = self.pointer(&head[4..], what)?;
        let start = at + 4 + POINTER as u64;
        if end < start || end.checked_add(4).is_none_or(|e| e > self.len) {
            return Err(self.invalid(what, format!("a chunk from {at} to {end}")));
        }
        Ok((start, end))
    }

    fn read_tree(&mut self, root: u64) -> Result<(), CgnsError> {
        let mut seen = HashSet::new();
        let mut stack = vec![(String::from("/"), root, 0usize)];
        while let Some((path, at, depth)) = stack.pop() {
            if depth > MAX_DEPTH || !seen.insert(at) {
                return Err(self.invalid(&path, "the node tree loops or is too deep".into()));
            }
            let (node, table) = self.node(at, &path)?;
            for (name, child) in &table {
                let child_path = format!("{}/{name}", path.trim_end_matches('/'));
                stack.push((child_path, *child, depth + 1));
            }
            self.nodes.insert(
                path,
                Node {
                    children: table.into_iter().map(|(n, _)| n).collect(),
                    ..node
                },
            );
        }
        Ok(())
    }

    /// The node header at `at` and its children (name, position).
    fn node(&self, at: u64, path: &str) -> Result<(Node, Vec<(String, u64)>), CgnsError> {
        let h = self.bytes(at, NODE_HEADER, path)?;
        if &h[..4] != b"NoDe" || &h[NODE_HEADER - 4..] != b"TaiL" {
            return Err(self.invalid(path, format!("no node header at byte {at}")));
        }
        let field = |range: std::ops::Range<usize>, what: &str| {
            hex(&h[range]).ok_or_else(|| self.invalid(path, format!("{what} is not hexadecimal")))
        };
        let children = field(68..76, "the number of children")?;
        let ndims = field(128..130, "the number of dimensions")?;
        if ndims > 12 {
            return Err(self.invalid(path, format!("{ndims} dimensions")));
        }
        let mut dims = Vec::with_capacity(ndims as usize);
        for i in 0..ndims as usize {
            dims.push(if self.ascii {
                field(130 + 8 * i..138 + 8 * i, "a dimension")?
            } else {
                self.int(&h[130 + 8 * i..138 + 8 * i])
            });
        }
        let node = Node {
            label: text(&h[36..68]),
            data_type: text(&h[96..128]),
            dims,
            chunks: field(226..230, "the number of data chunks")?,
            data: self.pointer(&h[230..242], path)?,
            children: Vec::new(),
        };
        let mut table = Vec::new();
        if children > 0 {
            let entry = NAME + POINTER;
            let what = format!("{path}: the table of children");
            let (start, end) = self.chunk(self.pointer(&h[84..96], path)?, b"SNTb", &what)?;
            if (end - start) / (entry as u64) < children {
                return Err(self.invalid(
                    &what,
                    format!("{children} children in {} bytes", end - start),
                ));
            }
            let raw = self.bytes(start, children as usize * entry, &what)?;
            for e in raw.chunks_exact(entry) {
                table.push((text(&e[..NAME]), self.pointer(&e[NAME..], &what)?));
            }
        }
        Ok((node, table))
    }

    /// The node at `path`, following links inside this file.
    fn get(&self, path: &str) -> Result<&Node, CgnsError> {
        let mut path = path.to_string();
        for _ in 0..=MAX_LINKS {
            let Some((node, target)) = self.link_on(&path)? else {
                return self.nodes.get(&path).ok_or_else(|| CgnsError::Missing {
                    file: self.name.clone(),
                    what: format!("node {path}"),
                });
            };
            path = format!("{target}{}", &path[node.len()..]);
        }
        Err(self.invalid(&path, "links lead to links more than 8 times".into()))
    }

    /// The first link on `path` (its path and its target's), if any.
    fn link_on(&self, path: &str) -> Result<Option<(String, String)>, CgnsError> {
        let mut prefix = String::new();
        for part in path.split('/').filter(|p| !p.is_empty()) {
            prefix.push('/');
            prefix.push_str(part);
            let Some(node) = self.nodes.get(&prefix) else {
                return Ok(None);
            };
            if node.data_type == "LK" {
                let bytes = self.raw(node, &prefix)?;
                let link = String::from_utf8_lossy(&bytes)
                    .trim_end_matches('\0')
                    .trim()
                    .to_string();
                let (file, target) = link.split_once('|').unwrap_or(("", link.as_str()));
                if !file.trim().is_empty() {
                    return Err(self.invalid(
                        &prefix,
                        format!("a link to {target} in file {file}, which is not followed"),
                    ));
                }
                return Ok(Some((
                    prefix,
                    format!("/{}", target.trim_start_matches('/')),
                )));
            }
        }
        Ok(None)
    }

    pub fn label(&self, path: &str) -> Option<String> {
        self.get(path).ok().map(|n| n.label.clone())
    }

    /// The children of the node at `path`, by name.
    pub fn children(&self, path: &str) -> Result<Vec<String>, CgnsError> {
        Ok(self.get(path)?.children.clone())
    }

    /// The data bytes of a node, from its chunk or its table of chunks.
    fn raw(&self, node: &Node, path: &str) -> Result<Vec<u8>, CgnsError> {
        let size = match node.data_type.as_str() {
            "MT" => return Ok(Vec::new()),
            "C1" | "B1" | "LK" => 1u64,
            "I4" | "U4" | "R4" => 4,
            "I8" | "U8" | "R8" | "X4" => 8,
            "X8" => 16,
            other => return Err(self.invalid(path, format!("data type {other:?} is not read"))),
        };
        let total = node
            .dims
            .iter()
            .try_fold(size, |n, &d| n.checked_mul(d))
            .filter(|&t| t <= self.len)
            .ok_or_else(|| {
                self.invalid(
                    path,
                    format!(
                        "dimensions {:?} need more bytes than the file has",
                        node.dims
                    ),
                )
            })?;
        if node.chunks == 0 || node.dims.is_empty() {
            return Ok(Vec::new());
        }
        let what = format!("{path}: data");
        let mut spans = Vec::new();
        if node.chunks == 1 {
            spans.push(self.chunk(node.data, b"DaTa", &what)?);
        } else {
            let (start, end) = self.chunk(node.data, b"DCtb", &what)?;
            let entry = 2 * POINTER as u64;
            if (end - start) / entry < node.chunks {
                return Err(self.invalid(
                    &what,
                    format!("{} chunks in a table of {} bytes", node.chunks, end - start),
                ));
            }
            let table = self.bytes(start, (node.chunks * entry) as usize, &what)?;
            for e in table.chunks_exact(entry as usize) {
                let (s, _) = self.chunk(self.pointer(&e[..POINTER], &what)?, b"DaTa", &what)?;
                let end = self.pointer(&e[POINTER..], &what)?;
                if end < s || end > self.len {
                    return Err(self.invalid(&what, format!("a chunk from {s} to {end}")));
                }
                spans.push((s, end));
            }
        }
        let held: u64 = spans.iter().map(|(s, e)| e - s).sum();
        if held < total {
            return Err(CgnsError::Truncated {
                file: self.name.clone(),
                what,
                expected: total,
                found: held,
            });
        }
        // The bytes, and the values decoded from them.
        crate::preflight::check(&self.name, || format!("the data of {path}"), total * 2)?;
        let mut out = Vec::with_capacity(total as usize);
        for (s, e) in spans {
            let take = (e - s).min(total - out.len() as u64);
            out.extend(self.bytes(s, take as usize, &what)?);
            if out.len() as u64 == total {
                break;
            }
        }
        Ok(out)
    }

    /// The data type and bytes of the node at `path`.
    fn typed(&self, path: &str) -> Result<(&str, Vec<u8>), CgnsError> {
        let node = self.get(path)?;
        Ok((node.data_type.as_str(), self.raw(node, path)?))
    }

    /// Integers of type `kind` (characters and bytes by their codes) in the
    /// file's byte order; `None` for a type that is not an integer.
    fn integers(&self, kind: &str, raw: &[u8]) -> Option<Vec<i64>> {
        Some(match kind {
            "I4" => raw
                .chunks_exact(4)
                .map(|b| i64::from(self.int(b) as u32 as i32))
                .collect(),
            "U4" => raw.chunks_exact(4).map(|b| self.int(b) as i64).collect(),
            "I8" | "U8" => raw.chunks_exact(8).map(|b| self.int(b) as i64).collect(),
            "C1" | "B1" => raw.iter().map(|&b| i64::from(b)).collect(),
            "MT" => Vec::new(),
            _ => return None,
        })
    }

    /// The data of the node at `path` as f64, in Fortran order.
    pub fn data_f64(&self, path: &str) -> Result<Vec<f64>, CgnsError> {
        let (kind, raw) = self.typed(path)?;
        Ok(match kind {
            "R4" => raw
                .chunks_exact(4)
                .map(|b| f64::from(f32::from_bits(self.int(b) as u32)))
                .collect(),
            "R8" => raw
                .chunks_exact(8)
                .map(|b| f64::from_bits(self.int(b)))
                .collect(),
            // Unsigned: past i64's range too.
            "U8" => raw.chunks_exact(8).map(|b| self.int(b) as f64).collect(),
            _ => match self.integers(kind, &raw) {
                Some(values) => values.into_iter().map(|v| v as f64).collect(),
                None => {
                    return Err(self.invalid(path, format!("data type {kind} is not numeric")));
                }
            },
        })
    }

    /// The data of the node at `path` as i64 (integers, and characters by
    /// their codes).
    pub fn data_i64(&self, path: &str) -> Result<Vec<i64>, CgnsError> {
        let (kind, raw) = self.typed(path)?;
        self.integers(kind, &raw)
            .ok_or_else(|| self.invalid(path, format!("data type {kind} is not an integer")))
    }
}

/// ASCII hexadecimal digits as a number.
fn hex(raw: &[u8]) -> Option<u64> {
    raw.iter().try_fold(0u64, |n, &c| {
        Some(n * 16 + u64::from(char::from(c).to_digit(16)?))
    })
}

/// A blank- or null-padded name.
fn text(raw: &[u8]) -> String {
    String::from_utf8_lossy(raw)
        .trim_end_matches(['\0', ' '])
        .to_string()
}

fn ascii(raw: &[u8]) -> String {
    String::from_utf8_lossy(raw).into_owned()
}

#[cfg(test)]
#[path = "adf_tests.rs"]
mod tests;
