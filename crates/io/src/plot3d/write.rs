//! PLOT3D binary writer: the layout of the NASA datasets (single grid, no
//! Fortran records, big-endian 32-bit ints and floats), IBLANK after z when
//! the source has it. Arrays are computed and written in chunks, so a
//! source computed on the fly (a refinement) is never held whole.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use rayon::prelude::*;

use super::grid::Plot3dSource;
use crate::IoError;

/// Points per chunk: 1 MiB of output per array chunk.
const CHUNK: usize = 1 << 18;

/// Size in bytes of the grid file [`write_plot3d_xyz`] writes.
pub fn plot3d_xyz_bytes(dims: [usize; 3], iblank: bool) -> u64 {
    let n: u64 = dims.iter().map(|&d| d as u64).product();
    12 + n * if iblank { 16 } else { 12 }
}

/// Size in bytes of the solution file [`write_plot3d_q`] writes.
pub fn plot3d_q_bytes(dims: [usize; 3]) -> u64 {
    let n: u64 = dims.iter().map(|&d| d as u64).product();
    12 + 16 + 20 * n
}

/// Writes the grid file of `source`: `ni nj nk`, all x, all y, all z, then
/// IBLANK when the source has one. Returns the bytes written.
///
/// # Errors
/// [`io::ErrorKind::InvalidInput`] when a dimension does not fit the
/// 32-bit header; the writer's errors.
pub fn write_plot3d_xyz(source: &impl Plot3dSource, w: &mut impl Write) -> io::Result<u64> {
    let n = source.point_count();
    write_header(source.dims(), w)?;
    for axis in 0..3 {
        write_array(w, n, |p| source.coordinate(axis, p).to_be_bytes())?;
    }
    if source.has_iblank() {
        write_array(w, n, |p| source.iblank(p).to_be_bytes())?;
    }
    Ok(plot3d_xyz_bytes(source.dims(), source.has_iblank()))
}

/// Writes the solution file of `source`: `ni nj nk`, fsmach alpha re time,
/// then density, x/y/z momentum and stagnation energy. Returns the bytes
/// written.
///
/// # Errors
/// [`io::ErrorKind::InvalidInput`] when the source has no solution or a
/// dimension does not fit the header; the writer's errors.
pub fn write_plot3d_q(source: &impl Plot3dSource, w: &mut impl Write) -> io::Result<u64> {
    let Some(conditions) = source.conditions() else {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the grid has no solution to write",
        ));
    };
    let n = source.point_count();
    write_header(source.dims(), w)?;
    for c in conditions {
        w.write_all(&c.to_be_bytes())?;
    }
    for q in 0..5 {
        write_array(w, n, |p| source.solution(q, p).to_be_bytes())?;
    }
    Ok(plot3d_q_bytes(source.dims()))
}

/// Writes the grid file, and the solution file when `q` is given (and the
/// source has a solution). Returns the bytes of each.
///
/// # Errors
/// [`IoError::Io`] naming the file that could not be created or written.
pub fn write_plot3d_files(
    source: &impl Plot3dSource,
    xyz: &Path,
    q: Option<&Path>,
) -> Result<(u64, Option<u64>), IoError> {
    fn to_file(
        path: &Path,
        write: impl FnOnce(&mut BufWriter<File>) -> io::Result<u64>,
    ) -> Result<u64, IoError> {
        let io_error = |source| IoError::Io {
            file: path.display().to_string(),
            source,
        };
        let mut w = BufWriter::new(File::create(path).map_err(io_error)?);
        let bytes = write(&mut w).map_err(io_error)?;
        w.flush().map_err(io_error)?;
        Ok(bytes)
    }
    let xyz_bytes = to_file(xyz, |w| write_plot3d_xyz(source, w))?;
    let q_bytes = match q {
        Some(q) if source.conditions().is_some() => {
            Some(to_file(q, |w| write_plot3d_q(source, w))?)
        }
        _ => None,
    };
    Ok((xyz_bytes, q_bytes))
}

fn write_header(dims: [usize; 3], w: &mut impl Write) -> io::Result<()> {
    for d in dims {
        let d = i32::try_from(d).map_err(|_| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("dimension {d} does not fit the 32-bit PLOT3D header"),
            )
        })?;
        w.write_all(&d.to_be_bytes())?;
    }
    Ok(())
}

/// Writes `n` four-byte values, computed in parallel a chunk at a time.
fn write_array(
    w: &mut impl Write,
    n: usize,
    value: impl Fn(usize) -> [u8; 4] + Sync,
) -> io::Result<()> {
    let mut buf = vec![0u8; 4 * CHUNK.min(n)];
    for start in (0..n).step_by(CHUNK) {
        let len = CHUNK.min(n - start);
        let chunk = &mut buf[..4 * len];
        chunk
            .par_chunks_mut(4)
            .enumerate()
            .for_each(|(i, out)| out.copy_from_slice(&value(start + i)));
        w.write_all(chunk)?;
    }
    Ok(())
}
