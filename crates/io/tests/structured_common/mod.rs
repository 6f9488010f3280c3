//! A small VTK XML writer for the structured, parallel and multi-block
//! tests: any dataset type, any cells, any arrays, in the four encodings of
//! the VTK XML format (uncompressed, UInt32 headers, little-endian).
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Enc {
    Ascii,
    Base64,
    AppendedRaw,
    AppendedBase64,
}

pub const ENCODINGS: [Enc; 4] = [
    Enc::Ascii,
    Enc::Base64,
    Enc::AppendedRaw,
    Enc::AppendedBase64,
];

/// A DataArray: `ty` is its VTK type name.
#[derive(Debug, Clone)]
pub struct Array {
    pub name: String,
    pub ty: &'static str,
    pub components: usize,
    pub values: Vec<f64>,
}

pub fn array(name: &str, ty: &'static str, components: usize, values: Vec<f64>) -> Array {
    Array {
        name: name.into(),
        ty,
        components,
        values,
    }
}

/// `<tag attrs>` holding arrays (`Points`, `PointData`, `Coordinates`...).
#[derive(Debug, Clone)]
pub struct Section {
    pub tag: &'static str,
    pub attrs: String,
    pub arrays: Vec<Array>,
}

pub fn section(tag: &'static str, attrs: &str, arrays: Vec<Array>) -> Section {
    Section {
        tag,
        attrs: attrs.into(),
        arrays,
    }
}

#[derive(Debug, Clone)]
pub struct Piece {
    pub attrs: String,
    pub sections: Vec<Section>,
}

pub fn extent_attr(e: [i64; 6]) -> String {
    format!(
        "Extent=\"{} {} {} {} {} {}\"",
        e[0], e[1], e[2], e[3], e[4], e[5]
    )
}

/// The bytes of one value of VTK type `ty`, little-endian.
fn value_bytes(ty: &str, v: f64, out: &mut Vec<u8>) {
    match ty {
        "Float64" => out.extend_from_slice(&v.to_le_bytes()),
        "Float32" => out.extend_from_slice(&(v as f32).to_le_bytes()),
        "Int64" => out.extend_from_slice(&(v as i64).to_le_bytes()),
        "Int32" => out.extend_from_slice(&(v as i32).to_le_bytes()),
        "UInt8" => out.push(v as u8),
        other => panic!("test writer: type {other}"),
    }
}

/// `[UInt32 byte count][data]`, the uncompressed binary layout.
fn binary_block(a: &Array) -> Vec<u8> {
    let mut data = Vec::new();
    for &v in &a.values {
        value_bytes(a.ty, v, &mut data);
    }
    let mut block = (data.len() as u32).to_le_bytes().to_vec();
    block.extend(data);
    block
}

pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [0, 1, 2].map(|i| chunk.get(i).copied().unwrap_or(0) as u32);
        let n = (b[0] << 16) | (b[1] << 8) | b[2];
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[((n >> (18 - 6 * i)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A serial XML file: `<VTKFile type="{dataset}">`, `<{dataset} {attrs}>`
/// and the pieces.
pub fn xml_file(dataset: &str, dataset_attrs: &str, pieces: &[Piece], enc: Enc) -> Vec<u8> {
    let mut text = String::new();
    let mut appended: Vec<u8> = Vec::new();
    let _ = writeln!(
        text,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{dataset}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n  <{dataset} {dataset_attrs}>"
    );
    for piece in pieces {
        let _ = writeln!(text, "    <Piece {}>", piece.attrs);
        for s in &piece.sections {
            let _ = writeln!(text, "      <{} {}>", s.tag, s.attrs);
            for a in &s.arrays {
                let head = format!(
                    "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"",
                    a.ty, a.name, a.components
                );
                match enc {
                    Enc::Ascii => {
                        let values: Vec<String> = a
                            .values
                            .iter()
                            .map(|&v| match a.ty {
                                "Float64" | "Float32" => format!("{v:?}"),
                                _ => format!("{}", v as i64),
                            })
                            .collect();
                        let _ = writeln!(
                            text,
                            "{head} format=\"ascii\">\n{}\n        </DataArray>",
                            values.join(" ")
                        );
                    }
                    Enc::Base64 => {
                        let _ = writeln!(
                            text,
                            "{head} format=\"binary\">{}</DataArray>",
                            base64(&binary_block(a))
                        );
                    }
                    Enc::AppendedRaw | Enc::AppendedBase64 => {
                        let _ = writeln!(
                            text,
                            "{head} format=\"appended\" offset=\"{}\"/>",
                            appended.len()
                        );
                        let block = binary_block(a);
                        if enc == Enc::AppendedRaw {
                            appended.extend(block);
                        } else {
                            appended.extend(base64(&block).into_bytes());
                        }
                    }
                }
            }
            let _ = writeln!(text, "      </{}>", s.tag);
        }
        let _ = writeln!(text, "    </Piece>");
    }
    let _ = writeln!(text, "  </{dataset}>");
    let mut bytes = text.into_bytes();
    if matches!(enc, Enc::AppendedRaw | Enc::AppendedBase64) {
        let encoding = if enc == Enc::AppendedRaw {
            "raw"
        } else {
            "base64"
        };
        bytes.extend(format!("  <AppendedData encoding=\"{encoding}\">\n   _").into_bytes());
        bytes.extend(appended);
        bytes.extend(b"\n  </AppendedData>\n");
    }
    bytes.extend(b"</VTKFile>\n");
    bytes
}

/// An UnstructuredGrid piece: points, cells (point lists) and their types.
pub fn unstructured_piece(
    points: &[f64],
    cells: &[Vec<i64>],
    types: &[i64],
    point_data: Vec<Array>,
    cell_data: Vec<Array>,
    point_data_attrs: &str,
) -> Piece {
    let mut offsets = Vec::new();
    let mut connectivity = Vec::new();
    for c in cells {
        connectivity.extend(c.iter().map(|&i| i as f64));
        offsets.push(connectivity.len() as f64);
    }
    Piece {
        attrs: format!(
            "NumberOfPoints=\"{}\" NumberOfCells=\"{}\"",
            points.len() / 3,
            cells.len()
        ),
        sections: vec![
            section("PointData", point_data_attrs, point_data),
            section("CellData", "", cell_data),
            section(
                "Points",
                "",
                vec![array("Points", "Float64", 3, points.to_vec())],
            ),
            section(
                "Cells",
                "",
                vec![
                    array("connectivity", "Int64", 1, connectivity),
                    array("offsets", "Int64", 1, offsets),
                    array(
                        "types",
                        "UInt8",
                        1,
                        types.iter().map(|&t| t as f64).collect(),
                    ),
                ],
            ),
        ],
    }
}

/// VTK hexahedra (type 12) of an `nx x ny x nz` point block whose point
/// `(i, j, k)` has index `i + nx (j + ny k)`.
pub fn block_hexes(dims: [usize; 3]) -> Vec<Vec<i64>> {
    let [nx, ny, nz] = dims;
    let id = |i: usize, j: usize, k: usize| (i + nx * (j + ny * k)) as i64;
    let mut cells = Vec::new();
    for k in 0..nz - 1 {
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                cells.push(vec![
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ]);
            }
        }
    }
    cells
}

/// A warped grid: point `(i, j, k)` of the extent at a smooth, non-affine
/// position (so a reader that mixed up axes or order would be caught).
pub fn warped_points(extent: [i64; 6]) -> Vec<f64> {
    let mut p = Vec::new();
    for k in extent[4]..=extent[5] {
        for j in extent[2]..=extent[3] {
            for i in extent[0]..=extent[1] {
                let (x, y, z) = (i as f64, j as f64, k as f64);
                p.extend_from_slice(&[
                    x + 0.125 * y,
                    1.5 * y + 0.0625 * z * z,
                    0.75 * z + 0.03125 * x,
                ]);
            }
        }
    }
    p
}

/// A folder under the system temp folder, removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("tetray-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        TempDir(dir)
    }

    pub fn write(&self, name: &str, bytes: &[u8]) -> PathBuf {
        let path = self.0.join(name);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).expect("temp subdir");
        }
        std::fs::write(&path, bytes).expect("temp file");
        path
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The folder of the repository's sample files.
pub fn real_data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/real")
        .join(name)
}
