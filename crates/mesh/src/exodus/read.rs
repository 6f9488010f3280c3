//! From an Exodus II container to a [`RawGrid`]: coordinates, element
//! blocks (volume blocks kept in VTK node order, the others skipped), then
//! the variables of one time step (see `vars.rs`).

use super::elements::{family, vtk_cell, Family, VtkCell};
use super::nc::{times, Nc};
use super::vars::{choose_step, element_variables, nodal_variables, read_times};
use super::{ElementBlock, ExodusError, ExodusOptions};
use crate::vtk::RawGrid;

/// What the reader found besides the grid.
#[derive(Debug, Clone, Default)]
pub(super) struct ExodusMeta {
    pub times: Vec<f64>,
    pub time_step: Option<usize>,
    pub blocks: Vec<ElementBlock>,
    pub container: String,
}

/// A kept (volume) block: where its elements start among the grid's cells.
pub(super) struct KeptBlock {
    /// 1-based position among the file's blocks (the `N` of `connectN`).
    pub number: usize,
    pub first_cell: usize,
    pub cells: usize,
}

pub(super) fn read_raw(
    bytes: Vec<u8>,
    name: &str,
    opts: &ExodusOptions,
) -> Result<(RawGrid, ExodusMeta), ExodusError> {
    let nc = Nc::from_bytes(bytes, name)?;
    let num_nodes = nc.require_dim("num_nodes")?;
    let mut grid = RawGrid {
        points: coordinates(&nc, num_nodes)?,
        points_section: "coordinates".into(),
        ..RawGrid::default()
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
    grid: &mut RawGrid,
) -> Result<(Vec<ElementBlock>, Vec<KeptBlock>), ExodusError> {
    let count = nc.dim("num_el_blk").unwrap_or(0);
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
        block.kept = true;
        blocks.push(block);
        kept.push(KeptBlock {
            number,
            first_cell,
            cells,
        });
    }
    Ok((blocks, kept))
}

/// Appends one block's elements, 1-based Exodus node ids to 0-based VTK
/// point ids in VTK node order. On a bad id: (1-based element, the id).
fn append_cells(
    ids: &[i64],
    nodes: usize,
    cell: VtkCell,
    num_nodes: usize,
    grid: &mut RawGrid,
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
