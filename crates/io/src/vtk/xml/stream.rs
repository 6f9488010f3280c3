//! Streaming `.vtu` writer for large meshes: appended raw (uncompressed)
//! data. Its offsets follow from the counts alone, so the XML header is
//! written first and every array then goes straight to the output, the
//! tetrahedra chunk by chunk from a [`TetChunks`] source: beside the caller's
//! points and fields, nothing larger than one chunk is held.

use std::io::{self, BufWriter, Write};

use glam::Vec3;

use super::tree::{escape, open_vtkfile};
use tetray_mesh::ScalarField;

/// Tetrahedra per chunk when writing from a slice.
const CHUNK: usize = 1 << 16;

/// The tetrahedra of a mesh, produced in order, chunk by chunk.
pub trait TetChunks {
    /// How many tetrahedra [`TetChunks::for_each_chunk`] produces.
    fn tet_count(&self) -> usize;
    /// Calls `sink` with consecutive runs of tetrahedra, `tet_count` in
    /// all, in order; stops at the first error.
    fn for_each_chunk(&self, sink: &mut dyn FnMut(&[[u32; 4]]) -> io::Result<()>)
    -> io::Result<()>;
}

impl TetChunks for [[u32; 4]] {
    fn tet_count(&self) -> usize {
        self.len()
    }

    fn for_each_chunk(
        &self,
        sink: &mut dyn FnMut(&[[u32; 4]]) -> io::Result<()>,
    ) -> io::Result<()> {
        self.chunks(CHUNK).try_for_each(sink)
    }
}

/// Integer type of the connectivity and offsets arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VtuIndex {
    /// Half the bytes; offsets up to `i32::MAX` (536,870,911 tetrahedra).
    Int32,
    /// VTK's default `vtkIdType`.
    Int64,
}

impl VtuIndex {
    fn name(self) -> &'static str {
        match self {
            VtuIndex::Int32 => "Int32",
            VtuIndex::Int64 => "Int64",
        }
    }

    fn size(self) -> usize {
        match self {
            VtuIndex::Int32 => 4,
            VtuIndex::Int64 => 8,
        }
    }
}

/// Options of [`write_vtu_streamed`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VtuStreamOptions {
    pub index: VtuIndex,
    /// `header_type="UInt64"`, else UInt32.
    pub header_u64: bool,
    /// `byte_order="BigEndian"`, else LittleEndian.
    pub big_endian: bool,
}

/// One array of the appended section: its XML attributes and byte count.
struct ArraySpec {
    type_name: &'static str,
    name: String,
    components: usize,
    bytes: usize,
}

/// Writes a `.vtu` of tetrahedra with appended raw data, streaming the
/// tetrahedra from `tets`; the point fields are the PointData (the first
/// one the active scalars). Returns the bytes written.
///
/// # Errors
/// [`io::ErrorKind::InvalidInput`] for a field of the wrong length, a point
/// index out of range, an array too large for the header or index type, or
/// a source that produces another number of tetrahedra than it promised;
/// the writer's errors.
pub fn write_vtu_streamed<T: TetChunks + ?Sized>(
    points: &[Vec3],
    fields: &[ScalarField],
    tets: &T,
    w: &mut impl Write,
    options: &VtuStreamOptions,
) -> io::Result<u64> {
    let invalid = |message: String| io::Error::new(io::ErrorKind::InvalidInput, message);
    let (n, ncells) = (points.len(), tets.tet_count());
    for field in fields {
        if field.values.len() != n {
            return Err(invalid(format!(
                "field \"{}\" has {} values for {n} points",
                field.name,
                field.values.len()
            )));
        }
    }
    if options.index == VtuIndex::Int32 && (4 * ncells > i32::MAX as usize || n > i32::MAX as usize)
    {
        return Err(invalid(format!(
            "{ncells} tetrahedra of {n} points do not fit Int32 indices: use Int64"
        )));
    }
    let mut specs: Vec<ArraySpec> = fields
        .iter()
        .map(|f| ArraySpec {
            type_name: "Float32",
            name: f.name.clone(),
            components: 1,
            bytes: 4 * n,
        })
        .collect();
    let index = options.index;
    let cells = |name: &str, type_name, bytes| ArraySpec {
        type_name,
        name: name.to_string(),
        components: 1,
        bytes,
    };
    specs.push(ArraySpec {
        type_name: "Float32",
        name: "Points".into(),
        components: 3,
        bytes: 12 * n,
    });
    specs.push(cells(
        "connectivity",
        index.name(),
        4 * index.size() * ncells,
    ));
    specs.push(cells("offsets", index.name(), index.size() * ncells));
    specs.push(cells("types", "UInt8", ncells));
    let header_size = if options.header_u64 { 8 } else { 4 };
    if !options.header_u64 && specs.iter().any(|s| u32::try_from(s.bytes).is_err()) {
        return Err(invalid(
            "an array exceeds 4 GiB, too large for a UInt32 header: use UInt64".into(),
        ));
    }

    let mut w = BufWriter::with_capacity(1 << 20, Counting { inner: w, bytes: 0 });
    write_xml(&mut w, n, ncells, fields, &specs, header_size, options)?;
    let order = Order(options.big_endian);
    let mut spec = specs.iter();
    let mut header = |w: &mut BufWriter<_>| -> io::Result<()> {
        let bytes = spec.next().map_or(0, |s| s.bytes);
        match (options.header_u64, options.big_endian) {
            (true, true) => w.write_all(&(bytes as u64).to_be_bytes()),
            (true, false) => w.write_all(&(bytes as u64).to_le_bytes()),
            (false, true) => w.write_all(&(bytes as u32).to_be_bytes()),
            (false, false) => w.write_all(&(bytes as u32).to_le_bytes()),
        }
    };
    for field in fields {
        header(&mut w)?;
        for v in &field.values {
            w.write_all(&order.f32(*v))?;
        }
    }
    header(&mut w)?;
    for p in points {
        for c in p.to_array() {
            w.write_all(&order.f32(c))?;
        }
    }

    header(&mut w)?;
    let mut written = 0usize;
    let mut buf: Vec<u8> = Vec::new();
    tets.for_each_chunk(&mut |chunk| {
        written += chunk.len();
        if written > ncells {
            return Err(invalid(format!(
                "the tetrahedra source gave more than the {ncells} it promised"
            )));
        }
        buf.clear();
        for (t, tet) in chunk.iter().enumerate() {
            if let Some(&p) = tet.iter().find(|&&p| p as usize >= n) {
                let t = written - chunk.len() + t;
                return Err(invalid(format!(
                    "tetrahedron {t} uses point {p}, but there are {n} points"
                )));
            }
            for &p in tet {
                order.index(&mut buf, index, p as u64);
            }
        }
        w.write_all(&buf)
    })?;
    if written != ncells {
        return Err(invalid(format!(
            "the tetrahedra source gave {written} of the {ncells} it promised"
        )));
    }

    header(&mut w)?;
    for start in (0..ncells).step_by(CHUNK) {
        buf.clear();
        for c in start..(start + CHUNK).min(ncells) {
            order.index(&mut buf, index, 4 * (c as u64 + 1));
        }
        w.write_all(&buf)?;
    }
    header(&mut w)?;
    let types = vec![10u8; CHUNK.min(ncells)];
    for start in (0..ncells).step_by(CHUNK) {
        w.write_all(&types[..CHUNK.min(ncells - start)])?;
    }
    writeln!(w)?;
    writeln!(w, "  </AppendedData>")?;
    writeln!(w, "</VTKFile>")?;
    w.flush()?;
    Ok(w.get_ref().bytes)
}

/// The XML up to and including the `_` that starts the appended data.
fn write_xml(
    w: &mut impl Write,
    n: usize,
    ncells: usize,
    fields: &[ScalarField],
    specs: &[ArraySpec],
    header_size: usize,
    options: &VtuStreamOptions,
) -> io::Result<()> {
    open_vtkfile(w, options.big_endian, options.header_u64)?;
    writeln!(w, ">")?;
    writeln!(w, "  <UnstructuredGrid>")?;
    writeln!(
        w,
        "    <Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{ncells}\">"
    )?;
    let mut offset = 0;
    let mut array = |w: &mut dyn Write, spec: &ArraySpec| -> io::Result<()> {
        write!(
            w,
            "        <DataArray type=\"{}\" Name=\"{}\"",
            spec.type_name,
            escape(&spec.name)
        )?;
        if spec.components != 1 {
            write!(w, " NumberOfComponents=\"{}\"", spec.components)?;
        }
        writeln!(w, " format=\"appended\" offset=\"{offset}\"/>")?;
        offset += header_size + spec.bytes;
        Ok(())
    };
    match fields.first() {
        Some(first) => writeln!(w, "      <PointData Scalars=\"{}\">", escape(&first.name))?,
        None => writeln!(w, "      <PointData>")?,
    }
    let (field_specs, rest) = specs.split_at(fields.len());
    for spec in field_specs {
        array(w, spec)?;
    }
    writeln!(w, "      </PointData>")?;
    writeln!(w, "      <Points>")?;
    array(w, &rest[0])?;
    writeln!(w, "      </Points>")?;
    writeln!(w, "      <Cells>")?;
    for spec in &rest[1..] {
        array(w, spec)?;
    }
    writeln!(w, "      </Cells>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, "  <AppendedData encoding=\"raw\">")?;
    write!(w, "   _")
}

/// The output byte order.
#[derive(Clone, Copy)]
struct Order(bool);

impl Order {
    fn f32(self, v: f32) -> [u8; 4] {
        if self.0 {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    }

    /// Appends `v` as the index type (the caller checked it fits).
    fn index(self, buf: &mut Vec<u8>, index: VtuIndex, v: u64) {
        match (index, self.0) {
            (VtuIndex::Int32, true) => buf.extend_from_slice(&(v as i32).to_be_bytes()),
            (VtuIndex::Int32, false) => buf.extend_from_slice(&(v as i32).to_le_bytes()),
            (VtuIndex::Int64, true) => buf.extend_from_slice(&(v as i64).to_be_bytes()),
            (VtuIndex::Int64, false) => buf.extend_from_slice(&(v as i64).to_le_bytes()),
        }
    }
}

/// Counts the bytes passed to the inner writer.
struct Counting<W> {
    inner: W,
    bytes: u64,
}

impl<W: Write> Write for Counting<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let written = self.inner.write(buf)?;
        self.bytes += written as u64;
        Ok(written)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}
