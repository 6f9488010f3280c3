//! EnSight Gold variable files: per node (`coordinates` or `block`, then
//! one value per node; vectors component by component) and per element
//! (one section per element type, in the geometry's order). Values go to
//! the parts they name, as point or cell arrays.

use tetray_mesh::cells::CellArray;

use super::EnSightError;
use super::geo::Part;
use super::source::Source;

/// Reads one variable file into the parts' arrays; `width` is 1 for a
/// scalar, 3 for a vector.
pub(super) fn read_variable(
    src: &mut Source,
    parts: &mut [Part],
    name: &str,
    width: usize,
    per_node: bool,
) -> Result<(), EnSightError> {
    src.line()?; // description
    let mut seen = vec![false; parts.len()];
    while !src.at_end() {
        let keyword = src.line()?;
        if keyword.to_lowercase() != "part" {
            return Err(src.invalid(&format!("{name}: expected \"part\", found \"{keyword}\"")));
        }
        let number = src.ints(1, "part number")?[0];
        let Some(index) = parts.iter().position(|p| p.number == number) else {
            return Err(src.invalid(&format!("{name}: part {number} is not in the geometry")));
        };
        seen[index] = true;
        let part = &mut parts[index];
        let values = if per_node {
            let kind = src.line()?.to_lowercase();
            if kind != "coordinates" && !kind.starts_with("block") {
                return Err(src.invalid(&format!("{name}: part {number}: \"{kind}\"")));
            }
            let n = part.grid.points.len() / 3;
            let raw = src.floats(n * width, name)?;
            interleave(&raw, n, width)
        } else {
            let mut values = Vec::new();
            for (section, (kind, count)) in part.sections.clone().iter().enumerate() {
                let line = src.line()?.to_lowercase();
                if line.trim_start_matches("g_") != kind.as_str()
                    && !(kind == "block" && line.starts_with("block"))
                {
                    return Err(src.invalid(&format!(
                        "{name}: part {number}: section \"{line}\" where the geometry has \"{kind}\""
                    )));
                }
                let raw = src.floats(count * width, name)?;
                if !part.kept[section] {
                    continue;
                }
                let mut v = interleave(&raw, *count, width);
                if let Some(mask) = &part.mask {
                    v = v
                        .chunks(width)
                        .zip(mask)
                        .filter(|(_, keep)| **keep)
                        .flat_map(|(c, _)| c.to_vec())
                        .collect();
                }
                values.extend(v);
            }
            values
        };
        let array = CellArray {
            name: name.into(),
            components: width,
            values,
            section: format!("{} part {number}", src.name),
            defined: None,
        };
        if per_node {
            part.grid.point_arrays.push(array);
        } else {
            part.grid.cell_arrays.push(array);
        }
    }
    // A part the file does not name has no value there.
    for (part, seen) in parts.iter_mut().zip(seen) {
        if seen {
            continue;
        }
        let n = if per_node {
            part.grid.points.len() / 3
        } else {
            part.grid.types.len()
        };
        let array = CellArray {
            name: name.into(),
            components: width,
            values: vec![0.0; n * width],
            section: format!("{} (part {} absent)", src.name, part.number),
            defined: Some(vec![false; n]),
        };
        if per_node {
            part.grid.point_arrays.push(array);
        } else {
            part.grid.cell_arrays.push(array);
        }
    }
    Ok(())
}

/// Values stored component by component (all x, then all y...) as tuples.
fn interleave(raw: &[f64], n: usize, width: usize) -> Vec<f64> {
    if width == 1 {
        return raw.to_vec();
    }
    (0..n)
        .flat_map(|i| (0..width).map(move |c| raw[c * n + i]))
        .collect()
}
