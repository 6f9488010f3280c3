//! One CGNS zone as cells: a structured zone's vertex lattice, or an
//! unstructured zone's element sections; its flow solutions as point or
//! cell arrays.

use tetray_mesh::cells::{CellArray, CellGrid, add_cells};

use super::{CgnsError, H5, children, data_f64, data_i64, data_text};

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

/// Quadratic types whose node order differs from VTK's: their corners are
/// kept (CGNS code, the linear VTK type, nodes, corners).
const CORNERS: [(i64, i64, usize, usize); 5] = [
    (13, 14, 14, 5), // PYRA_14
    (15, 13, 15, 6), // PENTA_15
    (16, 13, 18, 6), // PENTA_18
    (18, 12, 20, 8), // HEXA_20
    (19, 12, 27, 8), // HEXA_27
];

const MIXED: i64 = 20;

pub(super) fn read_zone(
    h5: &H5,
    zone: &str,
    warnings: &mut Vec<String>,
) -> Result<CellGrid, CgnsError> {
    let (size, _) = data_f64(h5, zone)?;
    let kind = data_text(h5, &format!("{zone}/ZoneType")).unwrap_or_else(|| "Structured".into());
    let coordinates = children(h5, zone, "GridCoordinates_t")?;
    let Some(coords) = coordinates
        .iter()
        .find(|c| c.ends_with("/GridCoordinates"))
        .or(coordinates.first())
    else {
        return Err(h5.invalid(zone, "no GridCoordinates".into()));
    };
    let axis = |name: &str| data_f64(h5, &format!("{coords}/{name}")).map(|(v, _)| v);
    let (x, y, z) = (
        axis("CoordinateX")?,
        axis("CoordinateY")?,
        axis("CoordinateZ")?,
    );
    if x.len() != y.len() || x.len() != z.len() {
        return Err(h5.invalid(
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
            return Err(h5.invalid(zone, format!("zone sizes {size:?}")));
        }
        let v = [size[0] as usize, size[1] as usize, size[2] as usize];
        let c = [size[3] as usize, size[4] as usize, size[5] as usize];
        let cells_fit = c
            .iter()
            .zip(&v)
            .all(|(&c, &v)| c + 1 == v || (c == v && v == 1));
        if product(&v) != Some(x.len()) || !cells_fit {
            return Err(h5.invalid(
                zone,
                format!("{v:?} vertices and {c:?} cells, {} coordinates", x.len()),
            ));
        }
        grid.dataset = "StructuredGrid";
        add_cells(v, &mut grid);
        (v, c)
    } else {
        grid.dataset = "UnstructuredGrid";
        elements(h5, zone, x.len(), &mut grid, warnings)?;
        (
            [x.len(), 1, 1],
            [size.get(1).copied().unwrap_or(0.0) as usize, 1, 1],
        )
    };
    for solution in children(h5, zone, "FlowSolution_t")? {
        solution_arrays(h5, &solution, structured, vertex_dims, cell_dims, &mut grid)?;
    }
    join_vectors(&mut grid.point_arrays);
    join_vectors(&mut grid.cell_arrays);
    Ok(grid)
}

/// The element sections of an unstructured zone, in element-number order.
fn elements(
    h5: &H5,
    zone: &str,
    npoints: usize,
    grid: &mut CellGrid,
    warnings: &mut Vec<String>,
) -> Result<(), CgnsError> {
    let mut sections = Vec::new();
    for section in children(h5, zone, "Elements_t")? {
        let header = data_i64(h5, &section)?;
        let range = data_i64(h5, &format!("{section}/ElementRange"))?;
        let (Some(&code), [start, end, ..]) = (header.first(), range.as_slice()) else {
            return Err(h5.invalid(&section, "no element type or range".into()));
        };
        sections.push((*start, *end, code, section));
    }
    sections.sort();
    grid.offsets.push(0);
    for (start, end, code, section) in sections {
        let count = usize::try_from(end - start + 1)
            .map_err(|_| h5.invalid(&section, format!("range {start}..{end}")))?;
        let connectivity = data_i64(h5, &format!("{section}/ElementConnectivity"))?;
        let mut at = 0usize;
        let offsets = if code == MIXED {
            data_i64(h5, &format!("{section}/ElementStartOffset")).ok()
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
                    h5.invalid(&section, format!("element {e} past the connectivity"))
                })?;
                (c, at + 1)
            } else {
                (code, at)
            };
            let (vtk, n, keep) = if let Some(&(_, vtk, n)) =
                ELEMENTS.iter().find(|t| t.0 == cell_code)
            {
                (vtk, n, n)
            } else if let Some(&(_, vtk, n, corners)) = CORNERS.iter().find(|t| t.0 == cell_code) {
                let note = format!(
                    "{section}: quadratic CGNS elements of type {cell_code} kept by their corners"
                );
                if !warnings.contains(&note) {
                    warnings.push(note);
                }
                (vtk, n, corners)
            } else {
                return Err(h5.invalid(&section, format!("element type {cell_code} is not read (NGON_n and NFACE_n polyhedra are not)")));
            };
            let nodes = connectivity.get(nodes_at..nodes_at + n).ok_or_else(|| {
                h5.invalid(&section, format!("element {e} past the connectivity"))
            })?;
            for &node in &nodes[..keep] {
                if node < 1 || node as usize > npoints {
                    return Err(h5.invalid(
                        &section,
                        format!("element {e} names vertex {node} of {npoints}"),
                    ));
                }
                grid.connectivity.push(node - 1);
            }
            grid.types.push(vtk);
            grid.offsets.push(grid.connectivity.len());
            at = nodes_at + n;
        }
    }
    Ok(())
}

/// The arrays of one flow solution, at the vertices or the cells, their
/// rind layers (structured zones) stripped.
fn solution_arrays(
    h5: &H5,
    solution: &str,
    structured: bool,
    vertex_dims: [usize; 3],
    cell_dims: [usize; 3],
    grid: &mut CellGrid,
) -> Result<(), CgnsError> {
    let location =
        data_text(h5, &format!("{solution}/GridLocation")).unwrap_or_else(|| "Vertex".into());
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
        data_i64(h5, &format!("{solution}/Rind")).unwrap_or_default()
    } else {
        Vec::new()
    };
    let dims = if at_cells { cell_dims } else { vertex_dims };
    let stored: [usize; 3] = std::array::from_fn(|a| {
        dims[a]
            + rind.get(2 * a).copied().unwrap_or(0).max(0) as usize
            + rind.get(2 * a + 1).copied().unwrap_or(0).max(0) as usize
    });
    for array in children(h5, solution, "DataArray_t")? {
        let (values, _) = data_f64(h5, &array)?;
        let total = product(&stored);
        if Some(values.len()) != total {
            return Err(h5.invalid(
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
