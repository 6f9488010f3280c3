//! One CGNS zone as cells: a structured zone's vertex lattice, or an
//! unstructured zone's element sections; its flow solutions as point or
//! cell arrays.

use std::collections::HashMap;

use tetray_mesh::cells::{CellArray, CellGrid, add_cells};

use super::{CgnsError, Tree};

/// CGNS element types read: (CGNS code, VTK type, nodes). The linear
/// cells, faces and bars, and the quadratic tetrahedra and pyramids (whose
/// node order is VTK's).
const ELEMENTS: [(i64, i64, usize); 14] = [
    (2, 1, 1),    // NODE
    (3, 3, 2),    // BAR_2
    (4, 21, 3),   // BAR_3
    (5, 5, 3),    // TRI_3
    (6, 22, 6),   // TRI_6
    (7, 9, 4),    // QUAD_4
    (8, 23, 8),   // QUAD_8
    (10, 10, 4),  // TETRA_4
    (11, 24, 10), // TETRA_10
    (12, 14, 5),  // PYRA_5
    (14, 13, 6),  // PENTA_6
    (17, 12, 8),  // HEXA_8
    (21, 27, 13), // PYRA_13
    (9, 28, 9),   // QUAD_9
];

/// Quadratic types whose node order differs from VTK's: (CGNS code, VTK
/// type, nodes, the CGNS node at each VTK node). CGNS lists the vertical
/// edges' midpoints before the top edges', VTK after; its hexahedron face
/// centres go bottom, y = 0, x = 1, y = 1, x = 0, top, VTK's x = 0, x = 1,
/// y = 0, y = 1, bottom, top. PYRA_14's base centre has no place in VTK's
/// 13-node pyramid and is left out (the splitter puts a centre there).
const REORDERED: [(i64, i64, usize, &[usize]); 5] = [
    (13, 27, 14, &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]),
    (
        15,
        26,
        15,
        &[0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 13, 14, 9, 10, 11],
    ),
    (
        16,
        32,
        18,
        &[0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 13, 14, 9, 10, 11, 15, 16, 17],
    ),
    (
        18,
        25,
        20,
        &[
            0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15,
        ],
    ),
    (
        19,
        29,
        27,
        &[
            0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15, 24, 22, 21, 23,
            20, 25, 26,
        ],
    ),
];

const MIXED: i64 = 20;
const NGON: i64 = 22;
const NFACE: i64 = 23;
/// VTK's polyhedron.
const POLYHEDRON: i64 = 42;

pub(super) fn read_zone(
    tree: &Tree,
    zone: &str,
    step: Option<usize>,
) -> Result<CellGrid, CgnsError> {
    let size = tree.data_f64(zone)?;
    let kind = tree
        .data_text(&format!("{zone}/ZoneType"))
        .unwrap_or_else(|| "Structured".into());
    // The step's coordinates and solution, when the zone's iterative data
    // names them.
    let coordinates_at = step_node(tree, zone, "GridCoordinatesPointers", step)?;
    let solution_at = step_node(tree, zone, "FlowSolutionPointers", step)?;
    let coordinates = tree.children(zone, "GridCoordinates_t")?;
    let coords = match &coordinates_at {
        Some(name) => coordinates.iter().find(|c| c == &name),
        None => coordinates
            .iter()
            .find(|c| c.ends_with("/GridCoordinates"))
            .or(coordinates.first()),
    };
    let Some(coords) = coords else {
        let named = coordinates_at.map_or(String::new(), |c| format!(" {c}"));
        return Err(tree.invalid(zone, format!("no GridCoordinates{named}")));
    };
    let axis = |name: &str| tree.data_f64(&format!("{coords}/{name}"));
    let (x, y, z) = (
        axis("CoordinateX")?,
        axis("CoordinateY")?,
        axis("CoordinateZ")?,
    );
    if x.len() != y.len() || x.len() != z.len() {
        return Err(tree.invalid(
            coords,
            format!("{} x, {} y and {} z coordinates", x.len(), y.len(), z.len()),
        ));
    }
    let mut grid = CellGrid {
        points: (0..x.len()).flat_map(|i| [x[i], y[i], z[i]]).collect(),
        points_section: coords.clone(),
        ..CellGrid::default()
    };
    let structured = kind.eq_ignore_ascii_case("Structured");
    // Structured: vertex and cell sizes per direction; unstructured: the
    // vertex and cell counts.
    let (vertex_dims, cell_dims) = if structured {
        if size.len() < 6 {
            return Err(tree.invalid(zone, format!("zone sizes {size:?}")));
        }
        let v = [size[0] as usize, size[1] as usize, size[2] as usize];
        let c = [size[3] as usize, size[4] as usize, size[5] as usize];
        let cells_fit = c
            .iter()
            .zip(&v)
            .all(|(&c, &v)| c + 1 == v || (c == v && v == 1));
        if product(&v) != Some(x.len()) || !cells_fit {
            return Err(tree.invalid(
                zone,
                format!("{v:?} vertices and {c:?} cells, {} coordinates", x.len()),
            ));
        }
        grid.dataset = "StructuredGrid";
        add_cells(v, &mut grid);
        (v, c)
    } else {
        grid.dataset = "UnstructuredGrid";
        elements(tree, zone, x.len(), &mut grid)?;
        (
            [x.len(), 1, 1],
            [size.get(1).copied().unwrap_or(0.0) as usize, 1, 1],
        )
    };
    for solution in tree.children(zone, "FlowSolution_t")? {
        if solution_at.as_ref().is_some_and(|s| s != &solution) {
            continue;
        }
        solution_arrays(
            tree,
            &solution,
            structured,
            vertex_dims,
            cell_dims,
            &mut grid,
        )?;
    }
    join_vectors(&mut grid.point_arrays);
    join_vectors(&mut grid.cell_arrays);
    Ok(grid)
}

/// The path of the node a zone's iterative data names for `step` (a row
/// of 32-character names in `pointers`), if it names one.
fn step_node(
    tree: &Tree,
    zone: &str,
    pointers: &str,
    step: Option<usize>,
) -> Result<Option<String>, CgnsError> {
    let Some(step) = step else {
        return Ok(None);
    };
    let Some(data) = tree
        .children(zone, "ZoneIterativeData_t")?
        .into_iter()
        .next()
    else {
        return Ok(None);
    };
    let path = format!("{data}/{pointers}");
    if tree.label(&path) != "DataArray_t" {
        return Ok(None);
    }
    let chars = tree.data_i64(&path)?;
    let name: Vec<u8> = chars
        .get(32 * step..32 * (step + 1))
        .ok_or_else(|| tree.invalid(&path, format!("no name for step {step}")))?
        .iter()
        .map(|&c| c as u8)
        .collect();
    // A name ends at its first null; writers leave what follows unset.
    let end = name.iter().position(|&c| c == 0).unwrap_or(name.len());
    let name = String::from_utf8_lossy(&name[..end]).trim().to_string();
    Ok(Some(format!("{zone}/{name}")))
}

/// The element sections of an unstructured zone, in element-number order.
fn elements(tree: &Tree, zone: &str, npoints: usize, grid: &mut CellGrid) -> Result<(), CgnsError> {
    let mut sections = Vec::new();
    for section in tree.children(zone, "Elements_t")? {
        let header = tree.data_i64(&section)?;
        let range = tree.data_i64(&format!("{section}/ElementRange"))?;
        let (Some(&code), [start, end, ..]) = (header.first(), range.as_slice()) else {
            return Err(tree.invalid(&section, "no element type or range".into()));
        };
        sections.push((*start, *end, code, section));
    }
    sections.sort();
    grid.offsets.push(0);
    let faces = ngon_faces(tree, &sections, npoints)?;
    for (start, end, code, section) in sections {
        let count = usize::try_from(end - start + 1)
            .map_err(|_| tree.invalid(&section, format!("range {start}..{end}")))?;
        if code == NGON {
            continue;
        }
        if code == NFACE {
            polyhedra(tree, &section, count, &faces, grid)?;
            continue;
        }
        let connectivity = tree.data_i64(&format!("{section}/ElementConnectivity"))?;
        let mut at = 0usize;
        let offsets = if code == MIXED {
            tree.data_i64(&format!("{section}/ElementStartOffset")).ok()
        } else {
            None
        };
        for e in 0..count {
            let (cell_code, nodes_at) = if code == MIXED {
                if let Some(offsets) = &offsets {
                    at = offsets
                        .get(e)
                        .copied()
                        .unwrap_or(-1)
                        .try_into()
                        .unwrap_or(usize::MAX);
                }
                let c = *connectivity.get(at).ok_or_else(|| {
                    tree.invalid(&section, format!("element {e} past the connectivity"))
                })?;
                (c, at + 1)
            } else {
                (code, at)
            };
            let (vtk, n, order): (i64, usize, Option<&[usize]>) = if let Some(&(_, vtk, n)) =
                ELEMENTS.iter().find(|t| t.0 == cell_code)
            {
                (vtk, n, None)
            } else if let Some(&(_, vtk, n, order)) = REORDERED.iter().find(|t| t.0 == cell_code) {
                (vtk, n, Some(order))
            } else {
                return Err(tree.invalid(&section, format!("element type {cell_code} is not read")));
            };
            let nodes = connectivity.get(nodes_at..nodes_at + n).ok_or_else(|| {
                tree.invalid(&section, format!("element {e} past the connectivity"))
            })?;
            for &node in nodes {
                if node < 1 || node as usize > npoints {
                    return Err(tree.invalid(
                        &section,
                        format!("element {e} names vertex {node} of {npoints}"),
                    ));
                }
            }
            match order {
                Some(order) => grid
                    .connectivity
                    .extend(order.iter().map(|&k| nodes[k] - 1)),
                None => grid.connectivity.extend(nodes.iter().map(|&v| v - 1)),
            }
            grid.types.push(vtk);
            grid.offsets.push(grid.connectivity.len());
            at = nodes_at + n;
        }
    }
    Ok(())
}

/// Lists of `count` elements: by `ElementStartOffset` (CGNS 4) or with
/// each list's length before it in the connectivity (CGNS 3).
fn lists(tree: &Tree, section: &str, count: usize) -> Result<Vec<Vec<i64>>, CgnsError> {
    let connectivity = tree.data_i64(&format!("{section}/ElementConnectivity"))?;
    let offsets = tree.data_i64(&format!("{section}/ElementStartOffset")).ok();
    let past = |e: usize| tree.invalid(section, format!("element {e} past the connectivity"));
    let mut out = Vec::with_capacity(count.min(connectivity.len()));
    let mut at = 0usize;
    for e in 0..count {
        let (from, to) = match &offsets {
            Some(o) => {
                let bound = |i: usize| {
                    o.get(i)
                        .and_then(|&v| usize::try_from(v).ok())
                        .ok_or_else(|| past(e))
                };
                (bound(e)?, bound(e + 1)?)
            }
            None => {
                let n = connectivity
                    .get(at)
                    .and_then(|&n| usize::try_from(n).ok())
                    .ok_or_else(|| past(e))?;
                (at + 1, (at + 1).checked_add(n).ok_or_else(|| past(e))?)
            }
        };
        out.push(connectivity.get(from..to).ok_or_else(|| past(e))?.to_vec());
        at = to;
    }
    Ok(out)
}

/// The faces of the zone's NGON_n sections by element number, as 0-based
/// vertices.
fn ngon_faces(
    tree: &Tree,
    sections: &[(i64, i64, i64, String)],
    npoints: usize,
) -> Result<HashMap<i64, Vec<i64>>, CgnsError> {
    let mut faces = HashMap::new();
    for (start, end, _, section) in sections.iter().filter(|s| s.2 == NGON) {
        let count = usize::try_from(end - start + 1)
            .map_err(|_| tree.invalid(section, format!("range {start}..{end}")))?;
        for (e, face) in lists(tree, section, count)?.into_iter().enumerate() {
            if face.len() < 3 || face.iter().any(|&v| v < 1 || v as usize > npoints) {
                return Err(tree.invalid(
                    section,
                    format!("face {e} has vertices {face:?} of {npoints}"),
                ));
            }
            faces.insert(start + e as i64, face.iter().map(|v| v - 1).collect());
        }
    }
    Ok(faces)
}

/// The polyhedra of an NFACE_n section: each a list of face element
/// numbers, negative where the face's normal points into the cell.
fn polyhedra(
    tree: &Tree,
    section: &str,
    count: usize,
    faces: &HashMap<i64, Vec<i64>>,
    grid: &mut CellGrid,
) -> Result<(), CgnsError> {
    for (e, cell) in lists(tree, section, count)?.into_iter().enumerate() {
        if cell.len() < 4 {
            return Err(tree.invalid(section, format!("cell {e} has {} faces", cell.len())));
        }
        let mut outward = Vec::with_capacity(cell.len());
        for &f in &cell {
            let mut face = faces
                .get(&f.unsigned_abs().try_into().unwrap_or(i64::MAX))
                .ok_or_else(|| {
                    tree.invalid(
                        section,
                        format!("cell {e} names face {f}, which no NGON_n section holds"),
                    )
                })?
                .clone();
            if f < 0 {
                face.reverse();
            }
            outward.push(face);
        }
        let mut nodes: Vec<i64> = outward.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        grid.polyhedron_faces.insert(grid.types.len(), outward);
        grid.types.push(POLYHEDRON);
        grid.connectivity.extend(nodes);
        grid.offsets.push(grid.connectivity.len());
    }
    Ok(())
}

/// The arrays of one flow solution, at the vertices or the cells, their
/// rind layers (structured zones) stripped.
fn solution_arrays(
    tree: &Tree,
    solution: &str,
    structured: bool,
    vertex_dims: [usize; 3],
    cell_dims: [usize; 3],
    grid: &mut CellGrid,
) -> Result<(), CgnsError> {
    let location = tree
        .data_text(&format!("{solution}/GridLocation"))
        .unwrap_or_else(|| "Vertex".into());
    let at_cells = match location.as_str() {
        "Vertex" => false,
        "CellCenter" => true,
        other => {
            grid.warnings
                .push(format!("{solution}: GridLocation {other} is not read"));
            return Ok(());
        }
    };
    let rind = if structured {
        tree.data_i64(&format!("{solution}/Rind"))
            .unwrap_or_default()
    } else {
        Vec::new()
    };
    let dims = if at_cells { cell_dims } else { vertex_dims };
    let stored: [usize; 3] = std::array::from_fn(|a| {
        dims[a]
            + rind.get(2 * a).copied().unwrap_or(0).max(0) as usize
            + rind.get(2 * a + 1).copied().unwrap_or(0).max(0) as usize
    });
    for array in tree.children(solution, "DataArray_t")? {
        let values = tree.data_f64(&array)?;
        let total = product(&stored);
        if Some(values.len()) != total {
            return Err(tree.invalid(
                &array,
                format!("{} values where the zone has {stored:?}", values.len()),
            ));
        }
        let lo: [usize; 3] =
            std::array::from_fn(|a| rind.get(2 * a).copied().unwrap_or(0).max(0) as usize);
        let mut inner = Vec::with_capacity(values.len());
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                let row = ((k + lo[2]) * stored[1] + j + lo[1]) * stored[0] + lo[0];
                inner.extend_from_slice(&values[row..row + dims[0]]);
            }
        }
        let name = array.rsplit('/').next().unwrap_or(&array).to_string();
        // An unstructured zone's boundary faces follow its volume cells
        // and have no cell value (they are not volume cells either).
        let mut defined = None;
        if at_cells && grid.types.len() > inner.len() {
            let mut d = vec![true; inner.len()];
            d.resize(grid.types.len(), false);
            inner.resize(grid.types.len(), 0.0);
            defined = Some(d);
        }
        let out = CellArray {
            name,
            components: 1,
            values: inner,
            section: array.clone(),
            defined,
        };
        if at_cells {
            grid.cell_arrays.push(out);
        } else {
            grid.point_arrays.push(out);
        }
    }
    Ok(())
}

/// SIDS names a vector's components `<name>X`, `<name>Y`, `<name>Z`
/// (`MomentumX`...): the three also make the vector `<name>`, whose
/// magnitude the assembly adds, as VTK's CGNS reader joins them.
fn join_vectors(arrays: &mut Vec<CellArray>) {
    let mut vectors = Vec::new();
    for a in arrays.iter() {
        let Some(base) = a.name.strip_suffix('X').filter(|b| !b.is_empty()) else {
            continue;
        };
        let find = |axis: &str| arrays.iter().find(|b| b.name == format!("{base}{axis}"));
        let (Some(y), Some(z)) = (find("Y"), find("Z")) else {
            continue;
        };
        if arrays.iter().any(|b| b.name == base)
            || a.components != 1
            || y.values.len() != a.values.len()
            || z.values.len() != a.values.len()
        {
            continue;
        }
        let values = (0..a.values.len())
            .flat_map(|i| [a.values[i], y.values[i], z.values[i]])
            .collect();
        let defined = a.defined.clone();
        vectors.push(CellArray {
            name: base.to_string(),
            components: 3,
            values,
            section: format!("{} (with Y and Z)", a.section),
            defined,
        });
    }
    arrays.extend(vectors);
}

/// The product of sizes, `None` on overflow.
fn product(v: &[usize]) -> Option<usize> {
    v.iter().try_fold(1usize, |n, &d| n.checked_mul(d))
}
