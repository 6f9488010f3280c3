//! From an Exodus II container to a [`CellGrid`]: coordinates, element
//! blocks (volume blocks kept in VTK node order, the others skipped), then
//! the variables of one time step (see `vars.rs`).

use super::elements::{Family, VtkCell, family, vtk_cell};
use super::nc::{Nc, times};
use super::vars::{choose_step, element_variables, nodal_variables, read_times};
use super::{ElementBlock, ExodusError, ExodusOptions, KeptBlock};
use tetray_mesh::cells::CellGrid;

/// What the reader found besides the grid.
#[derive(Debug, Clone, Default)]
pub(super) struct ExodusMeta {
    pub times: Vec<f64>,
    pub time_step: Option<usize>,
    pub blocks: Vec<ElementBlock>,
    pub container: String,
}

pub(super) fn read_raw(
    nc: Nc<'_>,
    name: &str,
    opts: &ExodusOptions,
) -> Result<(CellGrid, ExodusMeta), ExodusError> {
    let num_nodes = nc.require_dim("num_nodes")?;
    preflight(&nc, num_nodes)?;
    let mut grid = CellGrid {
        points: coordinates(&nc, num_nodes)?,
        points_section: "coordinates".into(),
        ..CellGrid::default()
    };
    let (blocks, kept) = element_blocks(&nc, num_nodes, &mut grid)?;
    if kept.is_empty() {
        let list: Vec<String> = blocks.iter().map(describe).collect();
        return Err(ExodusError::NoVolumeBlock {
            file: name.into(),
            blocks: if list.is_empty() {
                "none".into()
            } else {
                list.join(", ")
            },
        });
    }
    let skipped: Vec<&ElementBlock> = blocks.iter().filter(|b| !b.kept && b.cells > 0).collect();
    if !skipped.is_empty() {
        let list: Vec<String> = skipped.iter().map(|b| describe(b)).collect();
        grid.warnings.push(format!(
            "skipped {} non-volume element block(s) ({} elements): {}",
            skipped.len(),
            skipped.iter().map(|b| b.cells).sum::<usize>(),
            list.join(", ")
        ));
    }

    let times = read_times(&nc)?;
    let time_step = choose_step(&nc, &times, opts)?;
    if let Some(step) = time_step {
        grid.point_arrays = nodal_variables(&nc, step, num_nodes, &mut grid.warnings)?;
        grid.cell_arrays = element_variables(&nc, step, blocks.len(), &kept, &mut grid.warnings)?;
    } else if nc.dim("num_nod_var").unwrap_or(0) + nc.dim("num_elem_var").unwrap_or(0) > 0 {
        grid.warnings
            .push("the file declares variables but stores no time step: no fields".into());
    }
    Ok((
        grid,
        ExodusMeta {
            times,
            time_step,
            blocks,
            container: nc.format(),
        },
    ))
}

/// The memory a read of the file takes, from its header's sizes, checked
/// against what the machine has before anything large is read. Per node:
/// the coordinates in f64 and f32, one step's nodal variables in f64 and
/// as f32 fields; per element: its connectivity in i64 with an offset and
/// a type, one step's element variables, and up to 6 tetrahedra (the
/// split of a hexahedron) with their cell map and topology (neighbours,
/// about 64 bytes each).
fn preflight(nc: &Nc<'_>, num_nodes: usize) -> Result<(), ExodusError> {
    let blocks = nc.dim("num_el_blk").unwrap_or(0);
    let (mut elements, mut ids) = (0u64, 0u64);
    for number in 1..=blocks.min(1 << 20) {
        let n = nc.dim(&format!("num_el_in_blk{number}")).unwrap_or(0) as u64;
        let per = nc.dim(&format!("num_nod_per_el{number}")).unwrap_or(0) as u64;
        elements = elements.saturating_add(n);
        ids = ids.saturating_add(n.saturating_mul(per));
    }
    let nodal = nc.dim("num_nod_var").unwrap_or(0) as u64;
    let element_vars = nc.dim("num_elem_var").unwrap_or(0) as u64;
    let nodes = num_nodes as u64;
    // Saturating throughout: the counts are the file's claims.
    let per_node = nodal.saturating_mul(12).saturating_add(36);
    let per_element = element_vars.saturating_mul(8).saturating_add(16 + 6 * 84);
    let needed = nodes
        .saturating_mul(per_node)
        .saturating_add(ids.saturating_mul(8))
        .saturating_add(elements.saturating_mul(per_element));
    crate::preflight::check(
        nc.name,
        || format!("the mesh ({nodes} nodes, {elements} elements)"),
        needed,
    )?;
    Ok(())
}

/// `"name" (id 7, HEX8, 12 elements)`, for messages.
fn describe(b: &ElementBlock) -> String {
    let label = if b.name.is_empty() {
        String::new()
    } else {
        format!("\"{}\" ", b.name)
    };
    format!(
        "{label}(id {}, {}, {} elements)",
        b.id, b.elem_type, b.cells
    )
}

/// x, y, z per node in double precision, from `coordx`/`coordy`/`coordz`
/// or the old single `coord(num_dim, num_nodes)`; 2-D files get z = 0.
fn coordinates(nc: &Nc, num_nodes: usize) -> Result<Vec<f64>, ExodusError> {
    let num_dim = nc.require_dim("num_dim")?;
    if !(1..=3).contains(&num_dim) {
        return Err(ExodusError::Invalid {
            file: nc.name.into(),
            what: "dimension \"num_dim\"".into(),
            message: format!("is {num_dim}, expected 1, 2 or 3"),
        });
    }
    let axes: Vec<Vec<f64>> = if nc.var("coordx").is_some() {
        ["coordx", "coordy", "coordz"][..num_dim]
            .iter()
            .map(|v| nc.read_f64(v, num_nodes, "one per node"))
            .collect::<Result<_, _>>()?
    } else if nc.var("coord").is_some() {
        let all = nc.read_f64("coord", times(num_dim, num_nodes), "num_dim x num_nodes")?;
        all.chunks_exact(num_nodes.max(1))
            .map(<[f64]>::to_vec)
            .collect()
    } else {
        return Err(nc.missing("coordinates (variables coordx, coordy, coordz or coord)".into()));
    };
    let mut xyz = vec![0.0; 3 * num_nodes];
    for (axis, values) in axes.iter().enumerate() {
        for (i, &v) in values.iter().enumerate() {
            xyz[3 * i + axis] = v;
        }
    }
    Ok(xyz)
}

/// Every block's description, and the volume blocks' cells appended to
/// `grid` in VTK order.
fn element_blocks(
    nc: &Nc,
    num_nodes: usize,
    grid: &mut CellGrid,
) -> Result<(Vec<ElementBlock>, Vec<KeptBlock>), ExodusError> {
    // Every block defines its own dimensions (its element count at least).
    let count = nc.count_within("num_el_blk", nc.dimension_count(), "dimensions")?;
    let ids = match nc.var("eb_prop1") {
        Some(_) => nc.read_ints("eb_prop1", count, "one id per block")?,
        None => (1..=count as i64).collect(),
    };
    let names = nc
        .names("eb_names", count)?
        .unwrap_or_else(|| vec![String::new(); count]);
    let status = match nc.var("eb_status") {
        Some(_) => nc.read_ints("eb_status", count, "one status per block")?,
        None => vec![1; count],
    };
    let mut blocks = Vec::with_capacity(count);
    let mut kept = Vec::new();
    grid.offsets.push(0);
    // Elements are numbered across all blocks, skipped ones included (0-based
    // Exodus element numbers), so cells left out are reported by them.
    let mut elements_before = 0;
    for b in 0..count {
        let number = b + 1;
        let cells = if status[b] == 0 {
            0
        } else {
            nc.dim(&format!("num_el_in_blk{number}")).unwrap_or(0)
        };
        let nodes = nc.dim(&format!("num_nod_per_el{number}")).unwrap_or(0);
        let connect = format!("connect{number}");
        let elem_type = nc.text_attribute(&connect, "elem_type").unwrap_or_default();
        let mut block = ElementBlock {
            id: ids[b],
            name: names[b].clone(),
            elem_type: elem_type.clone(),
            nodes_per_element: nodes,
            cells,
            kept: false,
        };
        let fam = family(&elem_type);
        let first_element = elements_before;
        elements_before += cells;
        if cells == 0 || fam == Family::LowerDim {
            blocks.push(block);
            continue;
        }
        let label = describe(&block);
        let cell = vtk_cell(fam, nodes).map_err(|why| ExodusError::UnsupportedElement {
            file: nc.name.into(),
            block: label.clone(),
            elem_type: elem_type.clone(),
            nodes,
            why,
        })?;
        let ids = nc.read_ints(
            &connect,
            times(cells, nodes),
            "elements x nodes per element",
        )?;
        let first_cell = grid.types.len();
        append_cells(&ids, nodes, cell, num_nodes, grid).map_err(|(element, node_id)| {
            ExodusError::BadNodeId {
                file: nc.name.into(),
                block: label,
                element,
                node_id,
                num_nodes,
            }
        })?;
        grid.cell_numbers
            .extend((first_element..first_element + cells).map(|e| e as u32));
        block.kept = true;
        blocks.push(block);
        kept.push(KeptBlock {
            number,
            first_cell,
            cells,
        });
    }
    grid.cells_numbered = elements_before;
    Ok((blocks, kept))
}

/// Appends one block's elements, 1-based Exodus node ids to 0-based VTK
/// point ids in VTK node order. On a bad id: (1-based element, the id).
fn append_cells(
    ids: &[i64],
    nodes: usize,
    cell: VtkCell,
    num_nodes: usize,
    grid: &mut CellGrid,
) -> Result<(), (usize, i64)> {
    for (e, element) in ids.chunks_exact(nodes).enumerate() {
        if let Some(&bad) = element
            .iter()
            .find(|&&id| id < 1 || id as u64 > num_nodes as u64)
        {
            return Err((e + 1, bad));
        }
        grid.connectivity
            .extend(vtk_order(element, cell).map(|id| id - 1));
        grid.offsets.push(grid.connectivity.len());
        grid.types.push(cell.type_id);
    }
    Ok(())
}

/// An element's nodes in VTK order.
pub(super) fn vtk_order(element: &[i64], cell: VtkCell) -> impl Iterator<Item = i64> + '_ {
    cell.exodus_node_of_vtk.iter().map(move |&k| element[k])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A TETRA10 and a HEX20 block as a file stores them (1-based ids in
    /// Exodus node order, the nodes numbered in a scrambled order) become
    /// VTK cells 24 and 25 whose mid-edge points sit at the midpoints of
    /// VTK's edges (vtkQuadraticTetra: 4-9 on 0-1, 1-2, 2-0, 0-3, 1-3, 2-3;
    /// vtkQuadraticHexahedron: 8-11 bottom, 12-15 top, 16-19 vertical).
    #[test]
    fn quadratic_blocks_become_vtk_cells_with_edges_in_vtk_places() {
        let tet_corners = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 2.0],
        ];
        let tet_exodus_edges = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
        let hex_corners = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 2.0],
            [2.0, 0.0, 2.0],
            [2.0, 2.0, 2.0],
            [0.0, 2.0, 2.0],
        ];
        // Exodus HEX20 nodes 9-20: bottom edges, vertical edges, top edges.
        let hex_exodus_edges = [
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 0],
            [0, 4],
            [1, 5],
            [2, 6],
            [3, 7],
            [4, 5],
            [5, 6],
            [6, 7],
            [7, 4],
        ];
        let mid = |a: [f64; 3], b: [f64; 3]| {
            [
                0.5 * (a[0] + b[0]),
                0.5 * (a[1] + b[1]),
                0.5 * (a[2] + b[2]),
            ]
        };
        // Node coordinates, element by element in Exodus order.
        let mut exodus_points: Vec<[f64; 3]> = tet_corners.to_vec();
        exodus_points.extend(
            tet_exodus_edges
                .iter()
                .map(|&[a, b]| mid(tet_corners[a], tet_corners[b])),
        );
        exodus_points.extend(hex_corners);
        exodus_points.extend(
            hex_exodus_edges
                .iter()
                .map(|&[a, b]| mid(hex_corners[a], hex_corners[b])),
        );
        // Store node k (0-based, in that order) as file node 1 + (7k mod 30).
        let n = exodus_points.len();
        let file_id = |k: usize| (7 * k % n) as i64 + 1;
        let mut coords = vec![[0.0; 3]; n];
        for (k, p) in exodus_points.iter().enumerate() {
            coords[file_id(k) as usize - 1] = *p;
        }
        let tet_ids: Vec<i64> = (0..10).map(file_id).collect();
        let hex_ids: Vec<i64> = (10..30).map(file_id).collect();

        let mut grid = CellGrid {
            offsets: vec![0],
            ..CellGrid::default()
        };
        let tet = vtk_cell(Family::Tetra, 10).unwrap();
        let hex = vtk_cell(Family::Hexahedron, 20).unwrap();
        append_cells(&tet_ids, 10, tet, n, &mut grid).unwrap();
        append_cells(&hex_ids, 20, hex, n, &mut grid).unwrap();
        assert_eq!(grid.types, vec![24, 25]);
        assert_eq!(grid.offsets, vec![0, 10, 30]);

        let point = |c: usize, i: usize| coords[grid.connectivity[grid.offsets[c] + i] as usize];
        let vtk_tet_edges = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
        for (k, &[a, b]) in vtk_tet_edges.iter().enumerate() {
            assert_eq!(
                point(0, 4 + k),
                mid(point(0, a), point(0, b)),
                "tet node {}",
                4 + k
            );
        }
        let vtk_hex_edges = [
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 0],
            [4, 5],
            [5, 6],
            [6, 7],
            [7, 4],
            [0, 4],
            [1, 5],
            [2, 6],
            [3, 7],
        ];
        for (k, &[a, b]) in vtk_hex_edges.iter().enumerate() {
            assert_eq!(
                point(1, 8 + k),
                mid(point(1, a), point(1, b)),
                "hex node {}",
                8 + k
            );
        }
        for (c, corners) in [(0, &tet_corners[..]), (1, &hex_corners[..])] {
            for (i, &p) in corners.iter().enumerate() {
                assert_eq!(point(c, i), p, "cell {c} corner {i}");
            }
        }

        // Node ids 0 and n + 1: the element and the id, 1-based.
        let mut bad = tet_ids.clone();
        bad[3] = 0;
        assert_eq!(append_cells(&bad, 10, tet, n, &mut grid), Err((1, 0)));
        let mut bad = [tet_ids.clone(), tet_ids].concat();
        bad[15] = n as i64 + 1;
        assert_eq!(append_cells(&bad, 10, tet, n, &mut grid), Err((2, 31)));
    }
}
