//! Time steps and the variables of one step: nodal variables become point
//! arrays, element variables cell arrays (masked where the truth table says
//! a block has none), and x/y/z component triples also one 3-component
//! array.

use super::nc::{Nc, times};
use super::{ExodusError, ExodusOptions, KeptBlock};
use crate::time::StepError;
use tetray_mesh::cells::CellArray;

/// The stored times (`time_whole`), one per time step.
pub(super) fn read_times(nc: &Nc) -> Result<Vec<f64>, ExodusError> {
    let steps = nc.dim("time_step").unwrap_or(0);
    if steps == 0 {
        return Ok(Vec::new());
    }
    if nc.var("time_whole").is_none() {
        return Err(nc.missing(format!(
            "variable \"time_whole\" (the times of its {steps} time steps)"
        )));
    }
    nc.read_f64("time_whole", steps, "one time per time step")
}

/// The 0-based step to read: the one asked for, the one nearest the time
/// asked for, else the first (`None` when no step is stored).
pub(super) fn choose_step(
    nc: &Nc,
    times: &[f64],
    opts: &ExodusOptions,
) -> Result<Option<usize>, ExodusError> {
    crate::time::choose_step(times, opts.time_step, opts.time).map_err(|e| match e {
        StepError::OutOfRange { requested, count } => ExodusError::TimeStepOutOfRange {
            file: nc.name.into(),
            requested,
            count,
        },
        StepError::Time(message) => ExodusError::Time {
            file: nc.name.into(),
            message,
        },
    })
}

/// The size of the variable-count dimension `dim`: each variable is a
/// variable of the file of its own (`vals_nod_var1`, `vals_elem_var1eb1`...)
/// or a row of the `combined` one, whose own dimension it then sizes.
fn variable_count(nc: &Nc, dim: &str, combined: Option<&str>) -> Result<usize, ExodusError> {
    if combined.is_some_and(|name| nc.var(name).is_some()) {
        return Ok(nc.dim(dim).unwrap_or(0));
    }
    nc.count_within(dim, nc.variable_count(), "variables")
}

/// Variable names from `name_*_var`, or `<fallback><n>` where a name is
/// absent or blank.
fn variable_names(
    nc: &Nc,
    list: &str,
    count: usize,
    fallback: &str,
) -> Result<Vec<String>, ExodusError> {
    let names = nc
        .names(list, count)?
        .unwrap_or_else(|| vec![String::new(); count]);
    Ok(names
        .into_iter()
        .enumerate()
        .map(|(i, n)| {
            if n.is_empty() {
                format!("{fallback}{}", i + 1)
            } else {
                n
            }
        })
        .collect())
}

/// Nodal variables at `step`: `vals_nod_varN(time_step, num_nodes)` (one
/// variable each) or the older `vals_nod_var(time_step, num_nod_var,
/// num_nodes)`.
pub(super) fn nodal_variables(
    nc: &Nc,
    step: usize,
    num_nodes: usize,
    warnings: &mut Vec<String>,
) -> Result<Vec<CellArray>, ExodusError> {
    let count = variable_count(nc, "num_nod_var", Some("vals_nod_var"))?;
    let names = variable_names(nc, "name_nod_var", count, "nodal_variable_")?;
    let mut arrays = Vec::with_capacity(count);
    for (i, name) in names.into_iter().enumerate() {
        let own = format!("vals_nod_var{}", i + 1);
        let values = if nc.var(&own).is_some() {
            nc.read_f64_at(&own, &[step], num_nodes, "one per node")?
        } else if nc.var("vals_nod_var").is_some() {
            nc.read_f64_at("vals_nod_var", &[step, i], num_nodes, "one per node")?
        } else {
            return Err(nc.missing(format!(
                "values of nodal variable \"{name}\" (vals_nod_var{} or vals_nod_var)",
                i + 1
            )));
        };
        arrays.push(CellArray {
            section: format!("nodal variable \"{name}\", time step {step}"),
            name,
            components: 1,
            values,
            defined: None,
        });
    }
    arrays.extend(vectors(&arrays, warnings));
    Ok(arrays)
}

/// Element variables at `step` over the kept blocks' cells. A block the
/// truth table `elem_var_tab` excludes (or, without a table, one with no
/// `vals_elem_varMebN`) has no value: its cells are masked out.
pub(super) fn element_variables(
    nc: &Nc,
    step: usize,
    num_blocks: usize,
    kept: &[KeptBlock],
    warnings: &mut Vec<String>,
) -> Result<Vec<CellArray>, ExodusError> {
    let count = variable_count(nc, "num_elem_var", None)?;
    if count == 0 {
        return Ok(Vec::new());
    }
    let names = variable_names(nc, "name_elem_var", count, "element_variable_")?;
    let table = match nc.var("elem_var_tab") {
        Some(_) => Some(nc.read_ints(
            "elem_var_tab",
            times(num_blocks, count),
            "blocks x element variables",
        )?),
        None => None,
    };
    let ncells = kept.last().map_or(0, |b| b.first_cell + b.cells);
    let mut arrays = Vec::with_capacity(count);
    for (v, name) in names.into_iter().enumerate() {
        let mut values = vec![0.0; ncells];
        let mut defined = vec![false; ncells];
        for block in kept {
            let var = format!("vals_elem_var{}eb{}", v + 1, block.number);
            let listed = table
                .as_ref()
                .map(|t| t[(block.number - 1) * count + v] != 0);
            match (listed, nc.var(&var).is_some()) {
                (Some(false), _) | (None, false) => continue,
                (Some(true), false) => {
                    return Err(nc.missing(format!(
                        "variable \"{var}\" (element variable \"{name}\" on block {}, \
                         set in the truth table elem_var_tab)",
                        block.number
                    )));
                }
                (_, true) => {}
            }
            let block_values =
                nc.read_f64_at(&var, &[step], block.cells, "one per element of the block")?;
            let range = block.first_cell..block.first_cell + block.cells;
            values[range.clone()].copy_from_slice(&block_values);
            defined[range].fill(true);
        }
        if !defined.contains(&true) {
            warnings.push(format!(
                "element variable \"{name}\" is defined on no volume block: not read"
            ));
            continue;
        }
        arrays.push(CellArray {
            section: format!("element variable \"{name}\", time step {step}"),
            name,
            components: 1,
            values,
            defined: (!defined.iter().all(|&d| d)).then_some(defined),
        });
    }
    arrays.extend(vectors(&arrays, warnings));
    Ok(arrays)
}

/// `VX VY VZ`, `V_X V_Y V_Z`, `vel_x vel_y vel_z`: the base name if `name`
/// is the x component of such a triple, with the suffixes of y and z.
fn x_component(name: &str) -> Option<(&str, [String; 2])> {
    let (base, y, z) = if let Some(base) = name.strip_suffix('X') {
        (base, "Y", "Z")
    } else {
        (name.strip_suffix('x')?, "y", "z")
    };
    let stem = base.strip_suffix('_').unwrap_or(base);
    if stem.is_empty() {
        return None;
    }
    Some((stem, [format!("{base}{y}"), format!("{base}{z}")]))
}

/// One 3-component array per x/y/z triple of single-component arrays,
/// named by the triple's base (unless an array has that name already).
fn vectors(arrays: &[CellArray], warnings: &mut Vec<String>) -> Vec<CellArray> {
    let mut out: Vec<CellArray> = Vec::new();
    for x in arrays {
        let Some((stem, [y_name, z_name])) = x_component(&x.name) else {
            continue;
        };
        let find = |n: &str| arrays.iter().find(|a| a.name == n && a.components == 1);
        let (Some(y), Some(z)) = (find(&y_name), find(&z_name)) else {
            continue;
        };
        if arrays.iter().chain(&out).any(|a| a.name == stem) {
            warnings.push(format!(
                "components {}, {y_name}, {z_name} not joined into a vector: \"{stem}\" exists",
                x.name
            ));
            continue;
        }
        let mut values = Vec::with_capacity(3 * x.values.len());
        for i in 0..x.values.len() {
            values.extend([x.values[i], y.values[i], z.values[i]]);
        }
        let masks = [&x.defined, &y.defined, &z.defined];
        let defined = if masks.iter().all(|m| m.is_none()) {
            None
        } else {
            Some(
                (0..x.values.len())
                    .map(|i| masks.iter().all(|m| m.as_ref().is_none_or(|m| m[i])))
                    .collect(),
            )
        };
        out.push(CellArray {
            name: stem.to_string(),
            components: 3,
            values,
            section: format!("vector \"{stem}\" from {}, {y_name}, {z_name}", x.name),
            defined,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn component_names() {
        let x = |n| x_component(n).map(|(s, [y, z])| (s.to_string(), y, z));
        assert_eq!(x("VX"), Some(("V".into(), "VY".into(), "VZ".into())));
        assert_eq!(x("V_X"), Some(("V".into(), "V_Y".into(), "V_Z".into())));
        assert_eq!(
            x("vel_x"),
            Some(("vel".into(), "vel_y".into(), "vel_z".into()))
        );
        assert_eq!(x("X"), None);
        assert_eq!(x("_x"), None);
        assert_eq!(x("Temp"), None);
        assert_eq!(x(""), None);
    }

    fn array(name: &str, values: &[f64], defined: Option<Vec<bool>>) -> CellArray {
        CellArray {
            name: name.into(),
            components: 1,
            values: values.to_vec(),
            section: String::new(),
            defined,
        }
    }

    #[test]
    fn triples_become_vectors_with_the_common_mask() {
        let arrays = vec![
            array("s_x", &[1.0, 2.0], Some(vec![true, true])),
            array("s_y", &[3.0, 4.0], Some(vec![true, false])),
            array("s_z", &[5.0, 6.0], None),
            array("VX", &[1.0, 1.0], None),
            array("VY", &[1.0, 1.0], None),
            array("T", &[0.0, 0.0], None),
        ];
        let mut warnings = Vec::new();
        let joined = vectors(&arrays, &mut warnings);
        assert_eq!(joined.len(), 1, "VX, VY without VZ is no vector");
        assert_eq!(joined[0].name, "s");
        assert_eq!(joined[0].components, 3);
        assert_eq!(joined[0].values, vec![1.0, 3.0, 5.0, 2.0, 4.0, 6.0]);
        assert_eq!(joined[0].defined, Some(vec![true, false]));
        assert!(warnings.is_empty());

        // A variable already named like the vector keeps its name alone.
        let mut taken = arrays.clone();
        taken.push(array("s", &[0.0, 0.0], None));
        assert!(vectors(&taken, &mut warnings).is_empty());
        assert!(warnings[0].contains("\"s\" exists"), "{warnings:?}");
    }
}
