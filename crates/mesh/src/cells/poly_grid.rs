//! Polyhedron faces beside the raw grid: the legacy face streams moved out
//! of the connectivity, and the faces kept in step with the grid when
//! ghost cells are dropped, unused points removed and pieces welded (the
//! faces are keyed by cell index and hold point indices, like the
//! connectivity).

use super::CellError;
use super::grid::CellGrid;
use super::polyhedron::{PolyhedronFaces, check_closed, parse_face_stream};

/// The faces of polyhedron `cell` as point ids, checked in range and
/// closed.
pub fn checked_faces(
    all: &PolyhedronFaces,
    cell: usize,
    npoints: usize,
    file: &str,
) -> Result<Vec<Vec<u32>>, CellError> {
    let bad = |message: String| CellError::BadPolyhedron {
        file: file.into(),
        cell,
        message,
    };
    let faces = all
        .get(&cell)
        .ok_or_else(|| bad("the file lists no faces for it".into()))?;
    let mut out = Vec::with_capacity(faces.len());
    for face in faces {
        let mut ids = Vec::with_capacity(face.len());
        for &index in face {
            match u32::try_from(index) {
                Ok(i) if (i as usize) < npoints => ids.push(i),
                _ => {
                    return Err(CellError::BadIndex {
                        file: file.into(),
                        cell,
                        index,
                        npoints,
                    });
                }
            }
        }
        out.push(ids);
    }
    check_closed(&out).map_err(bad)?;
    Ok(out)
}

/// Legacy files carry a polyhedron's face stream in its CELLS entry: moves
/// it to `polyhedron_faces` and leaves the cell's distinct points in the
/// connectivity. Malformed offsets are left for `assemble`.
pub fn separate_inline_faces(grid: &mut CellGrid, file: &str) -> Result<(), CellError> {
    let inline = |c: usize| grid.types[c] == 42 && !grid.polyhedron_faces.contains_key(&c);
    let ncells = grid.types.len();
    if !(0..ncells).any(inline) || grid.offsets.len() != ncells + 1 {
        return Ok(());
    }
    let mut offsets = Vec::with_capacity(ncells + 1);
    let mut connectivity = Vec::with_capacity(grid.connectivity.len());
    offsets.push(0);
    let mut streams = Vec::new();
    for c in 0..ncells {
        let (start, end) = (grid.offsets[c], grid.offsets[c + 1]);
        let Some(entry) = grid.connectivity.get(start..end) else {
            return Ok(());
        };
        if inline(c) {
            let faces = parse_face_stream(entry).map_err(|message| CellError::BadPolyhedron {
                file: file.into(),
                cell: c,
                message,
            })?;
            for &p in faces.iter().flatten() {
                if !connectivity[offsets[c]..].contains(&p) {
                    connectivity.push(p);
                }
            }
            streams.push((c, faces));
        } else {
            connectivity.extend_from_slice(entry);
        }
        offsets.push(connectivity.len());
    }
    grid.offsets = offsets;
    grid.connectivity = connectivity;
    grid.polyhedron_faces.extend(streams);
    Ok(())
}

/// Keeps the faces of the cells `keep` keeps, renumbered like the cells.
pub fn keep_cell_faces(faces: &mut PolyhedronFaces, keep: &[bool]) {
    if faces.is_empty() {
        return;
    }
    let mut new_index = Vec::with_capacity(keep.len());
    let mut next = 0;
    for &k in keep {
        new_index.push(k.then_some(next));
        next += usize::from(k);
    }
    *faces = std::mem::take(faces)
        .into_iter()
        .filter_map(|(c, f)| new_index.get(c).copied().flatten().map(|n| (n, f)))
        .collect();
}

/// Moves the faces `cells_before` cells on and maps their point indices
/// with `map` (as the connectivity of a welded piece is).
pub fn shift_faces(
    faces: PolyhedronFaces,
    cells_before: usize,
    map: impl Fn(i64) -> i64,
) -> PolyhedronFaces {
    faces
        .into_iter()
        .map(|(c, mut f)| {
            for p in f.iter_mut().flatten() {
                *p = map(*p);
            }
            (cells_before + c, f)
        })
        .collect()
}
