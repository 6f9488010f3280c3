//! An OpenFOAM `polyMesh` (points, faces, owner, neighbour) as cells: each
//! cell is the faces it owns or neighbours (a face's points run
//! anticlockwise seen from its owner's outside, so a neighbour sees it
//! reversed). Cells whose faces make a tetrahedron, pyramid, wedge or
//! hexahedron become that VTK cell, with VTK's point order; any other is a
//! polyhedron (VTK type 42) with its faces, split around its centroid.

use std::path::Path;

use tetray_mesh::cells::CellGrid;

use super::OpenFoamError;
use super::foam::FoamFile;

const TETRA: i64 = 10;
const HEXAHEDRON: i64 = 12;
const WEDGE: i64 = 13;
const PYRAMID: i64 = 14;
const POLYHEDRON: i64 = 42;

/// Reads `folder` (a `polyMesh`) into a grid without arrays.
pub(super) fn read_poly_mesh(folder: &Path) -> Result<CellGrid, OpenFoamError> {
    let points = read_list(folder, "points", |f, at| f.numbers(at, 3, false, "points"))?;
    let (starts, labels) = with_file(folder, "faces", |f, at| f.faces(at))?;
    let owner = read_list(folder, "owner", |f, at| f.numbers(at, 1, true, "owner"))?;
    let neighbour = read_list(folder, "neighbour", |f, at| {
        f.numbers(at, 1, true, "neighbour")
    })?;
    let name = folder.display().to_string();
    let invalid = |message: String| OpenFoamError::Invalid {
        file: name.clone(),
        at: 0,
        message,
    };
    let npoints = points.len() / 3;
    let nfaces = starts.len().saturating_sub(1);
    if owner.len() != nfaces || neighbour.len() > nfaces {
        return Err(invalid(format!(
            "{nfaces} faces, {} owners and {} neighbours (one owner per face, one neighbour per \
             internal face)",
            owner.len(),
            neighbour.len()
        )));
    }
    if let Some(&bad) = labels.iter().find(|&&l| l < 0 || l as usize >= npoints) {
        return Err(invalid(format!("a face names point {bad} of {npoints}")));
    }
    let ncells = owner
        .iter()
        .chain(&neighbour)
        .try_fold(0usize, |n, &c| {
            (c >= 0.0 && c < u32::MAX as f64).then(|| n.max(c as usize + 1))
        })
        .ok_or_else(|| invalid("a negative or huge cell label in owner or neighbour".into()))?;
    // Every cell has at least four faces, each face at most two cells.
    if ncells > nfaces / 2 {
        return Err(invalid(format!(
            "owner and neighbour name {ncells} cells, more than {nfaces} faces can bound"
        )));
    }
    // Each cell's faces, outward: owned faces as stored, neighboured ones
    // reversed.
    let mut count = vec![0usize; ncells + 1];
    for &c in owner.iter().chain(&neighbour) {
        count[c as usize + 1] += 1;
    }
    for c in 0..ncells {
        count[c + 1] += count[c];
    }
    let mut slots = count.clone();
    let mut cell_faces = vec![(0usize, false); count[ncells]];
    for (f, &c) in owner.iter().enumerate() {
        cell_faces[slots[c as usize]] = (f, false);
        slots[c as usize] += 1;
    }
    for (f, &c) in neighbour.iter().enumerate() {
        cell_faces[slots[c as usize]] = (f, true);
        slots[c as usize] += 1;
    }
    let face = |f: usize, reversed: bool| -> Vec<i64> {
        let mut v = labels[starts[f]..starts[f + 1]].to_vec();
        if reversed {
            v.reverse();
        }
        v
    };
    let mut grid = CellGrid {
        points,
        points_section: "points".into(),
        dataset: "UnstructuredGrid",
        ..CellGrid::default()
    };
    grid.offsets.push(0);
    for c in 0..ncells {
        let faces: Vec<Vec<i64>> = cell_faces[count[c]..count[c + 1]]
            .iter()
            .map(|&(f, r)| face(f, r))
            .collect();
        if faces.len() < 4 {
            return Err(invalid(format!("cell {c} has {} faces", faces.len())));
        }
        match shape(&faces) {
            Some((kind, nodes)) => {
                grid.types.push(kind);
                grid.connectivity.extend(nodes);
            }
            None => {
                let mut nodes: Vec<i64> = faces.iter().flatten().copied().collect();
                nodes.sort_unstable();
                nodes.dedup();
                grid.types.push(POLYHEDRON);
                grid.connectivity.extend(nodes);
                grid.polyhedron_faces.insert(c, faces);
            }
        }
        grid.offsets.push(grid.connectivity.len());
    }
    Ok(grid)
}

fn with_file<T>(
    folder: &Path,
    name: &str,
    read: impl FnOnce(&FoamFile, &mut usize) -> Result<T, OpenFoamError>,
) -> Result<T, OpenFoamError> {
    let (path, bytes) = super::read_maybe_gz(&folder.join(name))?;
    let file = FoamFile::parse(&bytes, &path.display().to_string())?;
    let mut at = file.body;
    read(&file, &mut at)
}

fn read_list(
    folder: &Path,
    name: &str,
    read: impl FnOnce(&FoamFile, &mut usize) -> Result<Vec<f64>, OpenFoamError>,
) -> Result<Vec<f64>, OpenFoamError> {
    with_file(folder, name, read)
}

/// The VTK cell a cell's outward faces make, with VTK's point order, or
/// `None` for a polyhedron.
fn shape(faces: &[Vec<i64>]) -> Option<(i64, Vec<i64>)> {
    let tris: Vec<&Vec<i64>> = faces.iter().filter(|f| f.len() == 3).collect();
    let quads: Vec<&Vec<i64>> = faces.iter().filter(|f| f.len() == 4).collect();
    if tris.len() + quads.len() != faces.len() {
        return None;
    }
    let mut nodes: Vec<i64> = faces.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    let (kind, base, inward, count) = match (tris.len(), quads.len()) {
        (4, 0) => (TETRA, tris[0], true, 4),
        (4, 1) => (PYRAMID, quads[0], true, 5),
        (2, 3) => (WEDGE, tris[0], false, 6),
        (0, 6) => (HEXAHEDRON, quads[0], true, 8),
        _ => return None,
    };
    if nodes.len() != count {
        return None;
    }
    // VTK's base faces: a tetrahedron's, a pyramid's and a hexahedron's
    // turn towards the rest of the cell (inward), a wedge's away from it.
    let mut order: Vec<i64> = base.clone();
    if inward {
        order.reverse();
    }
    let rest: Vec<i64> = nodes
        .iter()
        .copied()
        .filter(|n| !order.contains(n))
        .collect();
    match kind {
        TETRA | PYRAMID => {
            if rest.len() != 1 {
                return None;
            }
            order.push(rest[0]);
        }
        _ => {
            // The far end of each base point's edge that leaves the base.
            let mut top = Vec::with_capacity(order.len());
            for &p in &order {
                let far = edge_partners(faces, p)
                    .into_iter()
                    .filter(|q| !order.contains(q))
                    .collect::<Vec<_>>();
                if far.len() != 1 {
                    return None;
                }
                top.push(far[0]);
            }
            let mut unique = top.clone();
            unique.sort_unstable();
            unique.dedup();
            if unique.len() != top.len() {
                return None;
            }
            order.extend(top);
        }
    }
    Some((kind, order))
}

/// The points joined to `p` by an edge of the faces.
fn edge_partners(faces: &[Vec<i64>], p: i64) -> Vec<i64> {
    let mut out = Vec::new();
    for f in faces {
        let k = f.len();
        for i in 0..k {
            if f[i] == p {
                for q in [f[(i + 1) % k], f[(i + k - 1) % k]] {
                    if !out.contains(&q) {
                        out.push(q);
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube's faces, outward, as OpenFOAM's blockMesh writes a
    /// hexahedron (points 0-3 at z = 0 anticlockwise, 4-7 above).
    fn cube() -> Vec<Vec<i64>> {
        vec![
            vec![0, 3, 2, 1],
            vec![4, 5, 6, 7],
            vec![0, 1, 5, 4],
            vec![2, 3, 7, 6],
            vec![1, 2, 6, 5],
            vec![0, 4, 7, 3],
        ]
    }

    #[test]
    fn a_cube_is_a_hexahedron_in_vtk_order() {
        let (kind, nodes) = shape(&cube()).unwrap();
        assert_eq!(kind, HEXAHEDRON);
        // The base turned inward: 0 1 2 3 (normal +z, towards the top).
        assert_eq!(nodes, vec![1, 2, 3, 0, 5, 6, 7, 4]);
    }

    #[test]
    fn other_shapes_and_polyhedra() {
        // A tetrahedron on (0,0,0) (1,0,0) (0,1,0) (0,0,1), outward faces.
        let tet = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
        assert_eq!(shape(&tet).unwrap(), (TETRA, vec![1, 2, 0, 3]));
        // A prism: triangles 0 1 2 (bottom) and 3 4 5 above.
        let wedge = vec![
            vec![0, 2, 1],
            vec![3, 4, 5],
            vec![0, 1, 4, 3],
            vec![1, 2, 5, 4],
            vec![2, 0, 3, 5],
        ];
        assert_eq!(shape(&wedge).unwrap(), (WEDGE, vec![0, 2, 1, 3, 5, 4]));
        // A cube with one face split in two: a polyhedron.
        let mut split = cube();
        split[1] = vec![4, 5, 6];
        split.push(vec![4, 6, 7]);
        assert_eq!(shape(&split), None);
    }
}
