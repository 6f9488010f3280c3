//! EnSight Gold (`.case`): the case file names the geometry and the
//! variables, each with an optional time set (times, and the numbers that
//! replace a file name's `*` run) and file set (several steps in one file
//! between `BEGIN TIME STEP` and `END TIME STEP`). Geometry and variable
//! files are ASCII or C binary. Parts are welded into one grid; scalars and
//! vectors per node and per element are read, tensors and complex
//! variables are passed over with a warning.

mod geo;
mod source;
mod vars;

use std::path::{Path, PathBuf};

use tetray_mesh::cells::{Linearize, ReadOptions, VtkRead};

use crate::time::choose_step;
use crate::vtk::VtkError;
use source::Source;

/// Everything that can go wrong reading an EnSight case.
#[derive(Debug, thiserror::Error)]
pub enum EnSightError {
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{file}: EnSight: {message} (at byte {at})")]
    Invalid {
        file: String,
        at: usize,
        message: String,
    },
    #[error("{file}: EnSight: {what} runs past the file's {found} bytes")]
    Truncated {
        file: String,
        what: String,
        found: u64,
    },
    #[error("{file}: {message}")]
    Time { file: String, message: String },
    #[error(transparent)]
    Assemble(#[from] VtkError),
}

/// Options of [`read_ensight`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnSightOptions {
    pub time_step: Option<usize>,
    pub time: Option<f64>,
    pub linearize: Linearize,
}

/// An EnSight case read.
#[derive(Debug)]
pub struct EnSightRead {
    pub read: VtkRead,
    pub times: Vec<f64>,
    pub time_step: Option<usize>,
}

#[derive(Debug, Default, Clone)]
struct TimeSet {
    times: Vec<f64>,
    start: i64,
    increment: i64,
    numbers: Vec<i64>,
}

/// A file the case names: its name, time set and file set.
#[derive(Debug, Clone)]
struct Named {
    file: String,
    time_set: Option<i64>,
    file_set: Option<i64>,
}

#[derive(Debug)]
struct Variable {
    name: String,
    width: usize,
    per_node: bool,
    named: Named,
}

/// Reads the case at `path`.
///
/// # Errors
/// [`EnSightError`] naming the file at fault.
pub fn read_ensight(path: &Path, opts: &EnSightOptions) -> Result<EnSightRead, EnSightError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| EnSightError::Io {
        file: name.clone(),
        source,
    })?;
    let fail = |message: String| EnSightError::Invalid {
        file: name.clone(),
        at: 0,
        message,
    };
    let mut section = String::new();
    let mut geometry = None;
    let mut variables = Vec::new();
    let mut warnings = Vec::new();
    let mut sets: Vec<(i64, TimeSet)> = Vec::new();
    let mut file_sets: Vec<i64> = Vec::new();
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .peekable();
    while let Some(line) = lines.next() {
        if !line.contains(':') {
            section = line.to_uppercase();
            continue;
        }
        let (key, value) = line.split_once(':').expect("a colon");
        let key = key.trim().to_lowercase();
        let value = value.trim();
        match (section.as_str(), key.as_str()) {
            ("FORMAT", "type") if !value.to_lowercase().contains("gold") => {
                return Err(fail(format!("type \"{value}\": only EnSight Gold is read")));
            }
            ("GEOMETRY", "model") => {
                geometry = Some(named(value, 1).ok_or_else(|| fail(format!("model: \"{value}\"")))?)
            }
            ("VARIABLE", kind) => {
                let (width, per_node) = match kind {
                    "scalar per node" => (1, true),
                    "vector per node" => (3, true),
                    "scalar per element" => (1, false),
                    "vector per element" => (3, false),
                    _ => {
                        warnings.push(format!("{kind} variables are not read: {value}"));
                        continue;
                    }
                };
                let tokens: Vec<&str> = value.split_whitespace().collect();
                let n = tokens.len();
                if n < 2 {
                    return Err(fail(format!("{kind}: \"{value}\" needs a name and a file")));
                }
                let named = named(value, 2).ok_or_else(|| fail(format!("{kind}: \"{value}\"")))?;
                variables.push(Variable {
                    name: tokens[n - 2].to_string(),
                    width,
                    per_node,
                    named,
                });
            }
            ("TIME", "time set") => {
                let id = value
                    .split_whitespace()
                    .next()
                    .and_then(|v| v.parse().ok())
                    .ok_or_else(|| fail(format!("time set \"{value}\"")))?;
                sets.push((
                    id,
                    TimeSet {
                        increment: 1,
                        ..TimeSet::default()
                    },
                ));
            }
            ("TIME", "number of steps" | "filename start number" | "filename increment") => {
                let v: i64 = value
                    .parse()
                    .map_err(|_| fail(format!("{key}: \"{value}\"")))?;
                let Some((_, set)) = sets.last_mut() else {
                    return Err(fail(format!("{key} before a time set")));
                };
                match key.as_str() {
                    "filename start number" => set.start = v,
                    "filename increment" => set.increment = v,
                    _ => {}
                }
            }
            ("TIME", "time values" | "filename numbers") => {
                let Some((_, set)) = sets.last_mut() else {
                    return Err(fail(format!("{key} before a time set")));
                };
                let mut words: Vec<String> = value.split_whitespace().map(str::to_string).collect();
                // The list runs on over the lines that hold numbers only.
                while let Some(next) = lines.peek() {
                    if next.contains(':')
                        || next.split_whitespace().any(|w| w.parse::<f64>().is_err())
                    {
                        break;
                    }
                    words.extend(next.split_whitespace().map(str::to_string));
                    lines.next();
                }
                let numbers: Vec<f64> = words
                    .iter()
                    .map(|w| w.parse().map_err(|_| fail(format!("{key}: \"{w}\""))))
                    .collect::<Result<_, _>>()?;
                if key == "time values" {
                    set.times = numbers;
                } else {
                    set.numbers = numbers.iter().map(|&v| v as i64).collect();
                }
            }
            ("FILE", "file set") => {
                file_sets.push(
                    value
                        .split_whitespace()
                        .next()
                        .and_then(|v| v.parse().ok())
                        .unwrap_or(0),
                );
            }
            _ => {}
        }
    }
    let geometry = geometry.ok_or_else(|| fail("no GEOMETRY model".into()))?;
    let set_of = |id: Option<i64>| {
        id.and_then(|id| sets.iter().find(|(i, _)| *i == id).map(|(_, s)| s.clone()))
    };
    // The case's times: those of every time set the geometry and the
    // variables use, as ParaView lists them.
    let mut times: Vec<f64> = std::iter::once(&geometry)
        .chain(variables.iter().map(|v| &v.named))
        .filter_map(|n| set_of(n.time_set))
        .flat_map(|s| s.times)
        .collect();
    times.sort_by(f64::total_cmp);
    times.dedup();
    let step = choose_step(&times, opts.time_step, opts.time).map_err(|e| EnSightError::Time {
        file: name.clone(),
        message: e.to_string(),
    })?;
    let time = step.map(|s| times[s]);
    let folder = path.parent().unwrap_or(Path::new("."));
    let open = |named: &Named| -> Result<(PathBuf, Vec<u8>, Option<usize>), EnSightError> {
        let set = set_of(named.time_set);
        // This file's own step: the one of its set nearest the time read.
        let own = match (&set, time) {
            (Some(set), Some(t)) if !set.times.is_empty() => Some(
                (0..set.times.len())
                    .min_by(|&a, &b| {
                        (set.times[a] - t)
                            .abs()
                            .total_cmp(&(set.times[b] - t).abs())
                    })
                    .unwrap_or(0),
            ),
            _ => None,
        };
        let file = match (named.file.contains('*'), &set, own) {
            (true, Some(set), Some(k)) => {
                let number = set
                    .numbers
                    .get(k)
                    .copied()
                    .unwrap_or(set.start + set.increment * k as i64);
                let stars = named.file.matches('*').count();
                let run = "*".repeat(stars);
                named.file.replacen(&run, &format!("{number:0stars$}"), 1)
            }
            _ => named.file.clone(),
        };
        let path = folder.join(&file);
        let bytes = std::fs::read(&path).map_err(|source| EnSightError::Io {
            file: path.display().to_string(),
            source,
        })?;
        // A file of a file set holds its steps itself.
        let inner = named.file_set.filter(|fs| file_sets.contains(fs)).and(own);
        Ok((path, bytes, inner))
    };
    let (geo_path, geo_bytes, geo_step) = open(&geometry)?;
    let mut src = Source::new(&geo_bytes, &geo_path.display().to_string())?;
    src.select_step(geo_step.unwrap_or(0))?;
    let mut parts = geo::read_geometry(&mut src)?;
    for v in &variables {
        let (path, bytes, inner) = open(&v.named)?;
        let mut src = Source::new(&bytes, &path.display().to_string())?;
        src.select_step(inner.unwrap_or(0))?;
        vars::read_variable(&mut src, &mut parts, &v.name, v.width, v.per_node)?;
    }
    let grids: Vec<_> = parts.into_iter().map(|p| p.grid).collect();
    let mut grid = crate::vtk::join_grids(grids, &name)?;
    grid.warnings.extend(warnings);
    let read = crate::vtk::assemble_grid(
        grid,
        &name,
        &ReadOptions {
            linearize: opts.linearize,
        },
    )?;
    Ok(EnSightRead {
        read,
        times,
        time_step: step,
    })
}

/// The file of a `model:` or variable line: the last word, after the
/// optional time set and file set numbers (`skip` words at the end are the
/// file and, for variables, the name before it).
fn named(value: &str, skip: usize) -> Option<Named> {
    // A geometry whose later steps move the points only says so last.
    let tokens: Vec<&str> = value
        .split_whitespace()
        .filter(|t| !t.eq_ignore_ascii_case("change_coords_only"))
        .collect();
    let n = tokens.len();
    if n < skip {
        return None;
    }
    let file = tokens[n - 1].to_string();
    let numbers: Vec<i64> = tokens[..n - skip]
        .iter()
        .filter_map(|t| t.parse().ok())
        .collect();
    Some(Named {
        file,
        time_set: numbers.first().copied(),
        file_set: numbers.get(1).copied(),
    })
}
