//! Legacy `.vtk` writer: UNSTRUCTURED_GRID of tetrahedra, f32 points and
//! point scalars, ASCII or BINARY (big-endian, as the format requires).

use std::io::{self, Write};

use tetray_mesh::TetMesh;

/// VTK_TETRA.
const TETRA: i32 = 10;

/// Writes `mesh` as a legacy VTK file (version 3.0 layout, read by every
/// VTK since 4). ASCII floats are written in Rust's shortest round-trip
/// form, so reading them back gives the same f32 bits.
pub fn write_legacy(mesh: &TetMesh, w: &mut impl Write, binary: bool) -> io::Result<()> {
    if i32::try_from(mesh.points.len()).is_err() || i32::try_from(mesh.tets.len() * 5).is_err() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "mesh too large for the legacy format's 32-bit CELLS section",
        ));
    }
    let mut w = io::BufWriter::new(w);
    writeln!(w, "# vtk DataFile Version 3.0")?;
    writeln!(w, "tetray tetrahedral mesh")?;
    writeln!(w, "{}", if binary { "BINARY" } else { "ASCII" })?;
    writeln!(w, "DATASET UNSTRUCTURED_GRID")?;

    writeln!(w, "POINTS {} float", mesh.points.len())?;
    let coords = mesh.points.iter().flat_map(|p| p.to_array());
    write_f32s(&mut w, coords, 3, binary)?;

    let n = mesh.tets.len();
    writeln!(w, "CELLS {n} {}", 5 * n)?;
    if binary {
        for t in &mesh.tets {
            w.write_all(&4i32.to_be_bytes())?;
            for &i in t {
                w.write_all(&(i as i32).to_be_bytes())?;
            }
        }
        writeln!(w)?;
    } else {
        for t in &mesh.tets {
            writeln!(w, "4 {} {} {} {}", t[0], t[1], t[2], t[3])?;
        }
    }
    writeln!(w, "CELL_TYPES {n}")?;
    if binary {
        for _ in 0..n {
            w.write_all(&TETRA.to_be_bytes())?;
        }
        writeln!(w)?;
    } else {
        for _ in 0..n {
            writeln!(w, "{TETRA}")?;
        }
    }

    if !mesh.fields.is_empty() {
        writeln!(w, "POINT_DATA {}", mesh.points.len())?;
        for (i, field) in mesh.fields.iter().enumerate() {
            if field.values.len() != mesh.points.len() {
                return Err(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!(
                        "field \"{}\" has {} values for {} points",
                        field.name,
                        field.values.len(),
                        mesh.points.len()
                    ),
                ));
            }
            writeln!(w, "SCALARS {} float 1", encode_name(&field.name, i))?;
            writeln!(w, "LOOKUP_TABLE default")?;
            write_f32s(&mut w, field.values.iter().copied(), 9, binary)?;
        }
    }
    w.flush()
}

fn write_f32s(
    w: &mut impl Write,
    values: impl Iterator<Item = f32>,
    per_line: usize,
    binary: bool,
) -> io::Result<()> {
    if binary {
        for v in values {
            w.write_all(&v.to_be_bytes())?;
        }
        return writeln!(w);
    }
    let mut on_line = 0;
    for v in values {
        if on_line > 0 {
            write!(w, " ")?;
        }
        write!(w, "{v}")?;
        on_line += 1;
        if on_line == per_line {
            writeln!(w)?;
            on_line = 0;
        }
    }
    if on_line > 0 {
        writeln!(w)?;
    }
    Ok(())
}

/// Names cannot hold whitespace; VTK escapes such bytes as `%XX`.
fn encode_name(name: &str, index: usize) -> String {
    if name.is_empty() {
        return format!("field_{index}");
    }
    let mut out = String::with_capacity(name.len());
    for b in name.bytes() {
        if b.is_ascii_graphic() && b != b'%' {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}
