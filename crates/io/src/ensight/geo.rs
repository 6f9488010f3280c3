//! An EnSight Gold geometry file: parts, each its own coordinates and
//! element sections (unstructured) or a structured block (uniform,
//! rectilinear or curvilinear, optionally iblanked). Element types map to
//! VTK's; ghost elements (`g_` types) are dropped; points, bars and faces
//! are kept for the shared assembly to skip and count.

use tetray_mesh::cells::CellGrid;

use super::EnSightError;
use super::source::Source;

/// One part of the geometry.
pub(super) struct Part {
    pub number: i64,
    pub grid: CellGrid,
    /// Element sections in file order: (EnSight type name, count), the
    /// order per-element variables follow; a block is one `block` section.
    pub sections: Vec<(String, usize)>,
    /// Cells kept per section (ghost sections keep none).
    pub kept: Vec<bool>,
    /// For an iblanked block: which of its cells were kept.
    pub mask: Option<Vec<bool>>,
}

/// The nodes of an element type, with its VTK type (`None`: variable).
fn element(name: &str) -> Option<(i64, Option<usize>)> {
    Some(match name {
        "point" => (1, Some(1)),
        "bar2" => (3, Some(2)),
        "bar3" => (21, Some(3)),
        "tria3" => (5, Some(3)),
        "tria6" => (22, Some(6)),
        "quad4" => (9, Some(4)),
        "quad8" => (23, Some(8)),
        "tetra4" => (10, Some(4)),
        "tetra10" => (24, Some(10)),
        "pyramid5" => (14, Some(5)),
        "pyramid13" => (27, Some(13)),
        "penta6" => (13, Some(6)),
        "penta15" => (26, Some(15)),
        "hexa8" => (12, Some(8)),
        "hexa20" => (25, Some(20)),
        "nsided" => (7, None),
        "nfaced" => (42, None),
        _ => return None,
    })
}

/// EnSight's wedges turn the other way from VTK's.
fn reorder(vtk: i64, nodes: &mut [i64]) {
    match vtk {
        13 => {
            nodes.swap(1, 2);
            nodes.swap(4, 5);
        }
        26 => {
            nodes.swap(1, 2);
            nodes.swap(4, 5);
            // Mid-edge nodes: 6 (0-1), 7 (1-2), 8 (2-0), 9 (3-4), 10 (4-5),
            // 11 (5-3), 12-14 vertical; with 1 and 2 swapped, 6 and 8 swap,
            // 9 and 11 swap, 13 and 14 swap.
            nodes.swap(6, 8);
            nodes.swap(9, 11);
            nodes.swap(13, 14);
        }
        _ => {}
    }
}

pub(super) fn read_geometry(src: &mut Source) -> Result<Vec<Part>, EnSightError> {
    src.line()?;
    src.line()?;
    let node_ids = src.line()?.to_lowercase();
    let element_ids = src.line()?.to_lowercase();
    let node_ids = node_ids.contains("given") || node_ids.contains("ignore");
    let element_ids = element_ids.contains("given") || element_ids.contains("ignore");
    if src
        .peek_line()
        .is_some_and(|l| l.to_lowercase().starts_with("extents"))
    {
        src.line()?;
        src.floats(6, "extents")?;
    }
    let mut parts = Vec::new();
    while !src.at_end() {
        let keyword = src.line()?;
        if keyword.to_lowercase() != "part" {
            return Err(src.invalid(&format!("expected \"part\", found \"{keyword}\"")));
        }
        let number = src.ints(1, "part number")?[0];
        src.line()?; // description
        let kind = src.line()?.to_lowercase();
        let part = if kind == "coordinates" {
            unstructured(src, number, node_ids, element_ids)?
        } else if let Some(options) = kind.strip_prefix("block") {
            structured(src, number, options, node_ids, element_ids)?
        } else {
            return Err(src.invalid(&format!(
                "part {number}: \"{kind}\" is neither coordinates nor block"
            )));
        };
        parts.push(part);
    }
    Ok(parts)
}

fn unstructured(
    src: &mut Source,
    number: i64,
    node_ids: bool,
    element_ids: bool,
) -> Result<Part, EnSightError> {
    let nn = src.count("coordinates")?;
    if node_ids {
        src.ints(nn, "node ids")?;
    }
    let x = src.floats(nn, "x coordinates")?;
    let y = src.floats(nn, "y coordinates")?;
    let z = src.floats(nn, "z coordinates")?;
    let mut grid = CellGrid {
        points: (0..nn).flat_map(|i| [x[i], y[i], z[i]]).collect(),
        points_section: format!("part {number} coordinates"),
        dataset: "UnstructuredGrid",
        ..CellGrid::default()
    };
    grid.offsets.push(0);
    let mut sections = Vec::new();
    let mut kept = Vec::new();
    while let Some(line) = src.peek_line() {
        let name = line.to_lowercase();
        if name == "part" || src.at_end() {
            break;
        }
        src.line()?;
        let ghost = name.starts_with("g_");
        let base = name.trim_start_matches("g_");
        let Some((vtk, per)) = element(base) else {
            return Err(src.invalid(&format!("part {number}: unknown element type \"{line}\"")));
        };
        let ne = src.count(base)?;
        if element_ids {
            src.ints(ne, "element ids")?;
        }
        let mut cells: Vec<Vec<i64>> = Vec::with_capacity(ne.min(1 << 20));
        let mut faces_of: Vec<Vec<Vec<i64>>> = Vec::new();
        match per {
            Some(k) => {
                let all = src.ints(
                    ne.checked_mul(k)
                        .ok_or_else(|| src.invalid("element count overflows"))?,
                    base,
                )?;
                cells.extend(all.chunks(k).map(<[i64]>::to_vec));
            }
            None if vtk == 7 => {
                let counts = src.ints(ne, "nsided node counts")?;
                let total = sum(src, &counts)?;
                let all = src.ints(total, "nsided nodes")?;
                let mut at = 0;
                for &c in &counts {
                    cells.push(all[at..at + c as usize].to_vec());
                    at += c as usize;
                }
            }
            None => {
                let face_counts = src.ints(ne, "nfaced face counts")?;
                let nfaces = sum(src, &face_counts)?;
                let node_counts = src.ints(nfaces, "nfaced node counts")?;
                let total = sum(src, &node_counts)?;
                let all = src.ints(total, "nfaced nodes")?;
                let (mut f, mut at) = (0usize, 0usize);
                for &fc in &face_counts {
                    let mut faces = Vec::with_capacity(fc as usize);
                    for _ in 0..fc {
                        let k = node_counts[f] as usize;
                        faces.push(all[at..at + k].iter().map(|n| n - 1).collect::<Vec<i64>>());
                        at += k;
                        f += 1;
                    }
                    let mut nodes: Vec<i64> = faces.iter().flatten().copied().collect();
                    nodes.sort_unstable();
                    nodes.dedup();
                    cells.push(nodes.iter().map(|n| n + 1).collect());
                    faces_of.push(faces);
                }
            }
        }
        sections.push((base.to_string(), ne));
        kept.push(!ghost);
        if ghost {
            continue;
        }
        for (i, mut nodes) in cells.into_iter().enumerate() {
            for n in nodes.iter_mut() {
                *n -= 1;
            }
            reorder(vtk, &mut nodes);
            if vtk == 42 {
                grid.polyhedron_faces
                    .insert(grid.types.len(), std::mem::take(&mut faces_of[i]));
            }
            grid.types.push(vtk);
            grid.connectivity.extend(nodes);
            grid.offsets.push(grid.connectivity.len());
        }
    }
    Ok(Part {
        number,
        grid,
        sections,
        kept,
        mask: None,
    })
}

fn sum(src: &Source, counts: &[i64]) -> Result<usize, EnSightError> {
    counts
        .iter()
        .try_fold(0usize, |s, &c| {
            usize::try_from(c).ok().and_then(|c| s.checked_add(c))
        })
        .ok_or_else(|| src.invalid("a negative or huge count"))
}

fn structured(
    src: &mut Source,
    number: i64,
    options: &str,
    node_ids: bool,
    element_ids: bool,
) -> Result<Part, EnSightError> {
    if options.contains("range") || options.contains("with_ghost") {
        return Err(src.invalid(&format!(
            "part {number}: block{options}: ranges and ghost blocks are not read"
        )));
    }
    let dims = src.ints(3, "block dimensions")?;
    let dims: Vec<usize> = dims
        .iter()
        .map(|&d| usize::try_from(d).ok().filter(|&d| d > 0))
        .collect::<Option<_>>()
        .ok_or_else(|| src.invalid(&format!("part {number}: block dimensions {dims:?}")))?;
    let n = dims
        .iter()
        .try_fold(1usize, |a, &d| a.checked_mul(d))
        .ok_or_else(|| src.invalid("block too large"))?;
    let (x, y, z): (Vec<f64>, Vec<f64>, Vec<f64>) = if options.contains("uniform") {
        let v = src.floats(6, "origin and spacing")?;
        let axis = |a: usize| {
            (0..dims[a])
                .map(|i| v[a] + i as f64 * v[a + 3])
                .collect::<Vec<_>>()
        };
        lattice(&axis(0), &axis(1), &axis(2))
    } else if options.contains("rectilinear") {
        let xs = src.floats(dims[0], "x")?;
        let ys = src.floats(dims[1], "y")?;
        let zs = src.floats(dims[2], "z")?;
        lattice(&xs, &ys, &zs)
    } else {
        (
            src.floats(n, "x")?,
            src.floats(n, "y")?,
            src.floats(n, "z")?,
        )
    };
    let iblank = if options.contains("iblanked") {
        Some(src.ints(n, "iblanking")?)
    } else {
        None
    };
    if node_ids {
        src.ints(n, "node ids")?;
    }
    if element_ids {
        let cells: usize = dims.iter().map(|&d| d.saturating_sub(1).max(1)).product();
        src.ints(cells, "element ids")?;
    }
    let mut grid = CellGrid {
        points: (0..n).flat_map(|i| [x[i], y[i], z[i]]).collect(),
        points_section: format!("part {number} block"),
        dataset: "StructuredGrid",
        ..CellGrid::default()
    };
    tetray_mesh::cells::add_cells([dims[0], dims[1], dims[2]], &mut grid);
    let ncells = grid.types.len();
    let mut mask = None;
    if let Some(iblank) = iblank {
        // A cell with a blanked point (iblank 0) is hidden, as VTK does.
        let keep: Vec<bool> = (0..ncells)
            .map(|c| {
                grid.connectivity[grid.offsets[c]..grid.offsets[c + 1]]
                    .iter()
                    .all(|&p| iblank[p as usize] != 0)
            })
            .collect();
        let mut kept = CellGrid {
            points: std::mem::take(&mut grid.points),
            ..grid.clone()
        };
        kept.types.clear();
        kept.connectivity.clear();
        kept.offsets = vec![0];
        for c in (0..ncells).filter(|&c| keep[c]) {
            kept.types.push(grid.types[c]);
            kept.connectivity
                .extend_from_slice(&grid.connectivity[grid.offsets[c]..grid.offsets[c + 1]]);
            kept.offsets.push(kept.connectivity.len());
        }
        let hidden = ncells - kept.types.len();
        if hidden > 0 {
            kept.warnings
                .push(format!("part {number}: {hidden} blanked cells hidden"));
        }
        grid = kept;
        mask = Some(keep);
    }
    Ok(Part {
        number,
        grid,
        sections: vec![("block".into(), ncells)],
        kept: vec![true],
        mask,
    })
}

/// The points of a lattice with these coordinates along each axis, x
/// fastest.
fn lattice(xs: &[f64], ys: &[f64], zs: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = xs.len() * ys.len() * zs.len();
    let (mut x, mut y, mut z) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    for &zk in zs {
        for &yj in ys {
            for &xi in xs {
                x.push(xi);
                y.push(yj);
                z.push(zk);
            }
        }
    }
    (x, y, z)
}
