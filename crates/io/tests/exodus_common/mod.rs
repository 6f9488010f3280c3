//! Helpers of the Exodus integration tests: a spec-based netCDF classic
//! writer (`cdf.rs`) and an Exodus II model written with it, following the
//! SEACAS Exodus II API's netCDF layout (dimensions `num_nodes`,
//! `num_el_in_blkN`..., variables `coordx`, `connectN`, `vals_nod_varN`...).
#![allow(dead_code)]

mod cdf;

pub use cdf::{Cdf, Values, Version};

/// An element block: id, name, `elem_type`, nodes per element and the
/// 1-based node ids of its elements.
#[derive(Debug, Clone)]
pub struct Block {
    pub id: i32,
    pub name: String,
    pub elem_type: String,
    pub nodes_per_element: usize,
    pub connectivity: Vec<i64>,
}

impl Block {
    pub fn new(id: i32, name: &str, elem_type: &str, nodes: usize, connectivity: &[i64]) -> Self {
        Block {
            id,
            name: name.into(),
            elem_type: elem_type.into(),
            nodes_per_element: nodes,
            connectivity: connectivity.to_vec(),
        }
    }

    pub fn elements(&self) -> usize {
        self.connectivity.len() / self.nodes_per_element
    }
}

/// An element variable: per time step, per block, the values or `None`
/// where the truth table leaves the block out.
#[derive(Debug, Clone)]
pub struct ElemVar {
    pub name: String,
    pub per_step: Vec<Vec<Option<Vec<f64>>>>,
}

/// An Exodus II model to write.
#[derive(Debug, Clone)]
pub struct Model {
    /// x, y, z per node.
    pub coords: Vec<[f64; 3]>,
    pub blocks: Vec<Block>,
    pub times: Vec<f64>,
    /// Nodal variables: name, then per time step one value per node.
    pub nodal: Vec<(String, Vec<Vec<f64>>)>,
    pub elem: Vec<ElemVar>,
    /// `coord(num_dim, num_nodes)` and `vals_nod_var(time, var, node)`
    /// (the old layout) instead of `coordx..` and `vals_nod_varN`.
    pub old_layout: bool,
    /// Connectivity as 64-bit integers (CDF-5 only).
    pub int64: bool,
}

const LEN_NAME: usize = 33;

/// Names as a NUL-padded char array, one row each.
fn name_rows(names: &[&str]) -> Values {
    let mut bytes = Vec::new();
    for n in names {
        let mut row = n.as_bytes().to_vec();
        row.resize(LEN_NAME, 0);
        bytes.extend(row);
    }
    Values::Chars(bytes)
}

impl Model {
    /// The file's bytes in netCDF classic `version`.
    pub fn write(&self, version: Version) -> Vec<u8> {
        let mut nc = Cdf::new(version);
        let nnodes = self.coords.len();
        let len_name = nc.dim("len_name", LEN_NAME);
        let time = nc.record_dim("time_step", self.times.len());
        let num_dim = nc.dim("num_dim", 3);
        let num_nodes = nc.dim("num_nodes", nnodes);
        nc.dim(
            "num_elem",
            self.blocks.iter().map(Block::elements).sum::<usize>(),
        );
        let num_el_blk = nc.dim("num_el_blk", self.blocks.len());
        let block_dims: Vec<(usize, usize)> = self
            .blocks
            .iter()
            .enumerate()
            .map(|(b, block)| {
                (
                    nc.dim(&format!("num_el_in_blk{}", b + 1), block.elements()),
                    nc.dim(&format!("num_nod_per_el{}", b + 1), block.nodes_per_element),
                )
            })
            .collect();
        nc.var("time_whole", &[time], Values::Doubles(self.times.clone()));
        nc.var(
            "eb_status",
            &[num_el_blk],
            Values::Ints(vec![1; self.blocks.len()]),
        );
        nc.var(
            "eb_prop1",
            &[num_el_blk],
            Values::Ints(self.blocks.iter().map(|b| b.id).collect()),
        )
        .attr("name", Values::Chars(b"ID".to_vec()));
        let names: Vec<&str> = self.blocks.iter().map(|b| b.name.as_str()).collect();
        nc.var("eb_names", &[num_el_blk, len_name], name_rows(&names));
        if self.old_layout {
            let mut all = Vec::new();
            for axis in 0..3 {
                all.extend(self.coords.iter().map(|p| p[axis]));
            }
            nc.var("coord", &[num_dim, num_nodes], Values::Doubles(all));
        } else {
            for (axis, name) in ["coordx", "coordy", "coordz"].iter().enumerate() {
                let values = self.coords.iter().map(|p| p[axis]).collect();
                nc.var(name, &[num_nodes], Values::Doubles(values));
            }
        }
        for (b, block) in self.blocks.iter().enumerate() {
            let values = if self.int64 {
                Values::Int64s(block.connectivity.clone())
            } else {
                Values::Ints(block.connectivity.iter().map(|&i| i as i32).collect())
            };
            let (elems, per) = block_dims[b];
            nc.var(&format!("connect{}", b + 1), &[elems, per], values)
                .attr(
                    "elem_type",
                    Values::Chars(block.elem_type.as_bytes().to_vec()),
                );
        }
        self.write_nodal(&mut nc, time, len_name, num_nodes);
        self.write_elem(&mut nc, time, len_name, num_el_blk, &block_dims);
        nc.to_bytes()
    }

    fn write_nodal(&self, nc: &mut Cdf, time: usize, len_name: usize, num_nodes: usize) {
        if self.nodal.is_empty() {
            return;
        }
        let num_nod_var = nc.dim("num_nod_var", self.nodal.len());
        let names: Vec<&str> = self.nodal.iter().map(|(n, _)| n.as_str()).collect();
        nc.var("name_nod_var", &[num_nod_var, len_name], name_rows(&names));
        if self.old_layout {
            let mut all = Vec::new();
            for step in 0..self.times.len() {
                for (_, values) in &self.nodal {
                    all.extend(&values[step]);
                }
            }
            nc.var(
                "vals_nod_var",
                &[time, num_nod_var, num_nodes],
                Values::Doubles(all),
            );
        } else {
            for (i, (_, values)) in self.nodal.iter().enumerate() {
                let all = values.concat();
                nc.var(
                    &format!("vals_nod_var{}", i + 1),
                    &[time, num_nodes],
                    Values::Doubles(all),
                );
            }
        }
    }

    fn write_elem(
        &self,
        nc: &mut Cdf,
        time: usize,
        len_name: usize,
        num_el_blk: usize,
        block_dims: &[(usize, usize)],
    ) {
        if self.elem.is_empty() {
            return;
        }
        let num_elem_var = nc.dim("num_elem_var", self.elem.len());
        let names: Vec<&str> = self.elem.iter().map(|v| v.name.as_str()).collect();
        nc.var(
            "name_elem_var",
            &[num_elem_var, len_name],
            name_rows(&names),
        );
        let mut table = Vec::new();
        for b in 0..self.blocks.len() {
            for var in &self.elem {
                table.push(i32::from(var.per_step[0][b].is_some()));
            }
        }
        nc.var(
            "elem_var_tab",
            &[num_el_blk, num_elem_var],
            Values::Ints(table),
        );
        for (v, var) in self.elem.iter().enumerate() {
            for (b, &(elems, _)) in block_dims.iter().enumerate() {
                if var.per_step[0][b].is_none() {
                    continue;
                }
                let all: Vec<f64> = var
                    .per_step
                    .iter()
                    .flat_map(|step| step[b].clone().expect("same blocks every step"))
                    .collect();
                nc.var(
                    &format!("vals_elem_var{}eb{}", v + 1, b + 1),
                    &[time, elems],
                    Values::Doubles(all),
                );
            }
        }
    }
}
