//! A study's output folder: SVG plots, CSV tables and a JSON summary, with
//! the list of what was written.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::StudyError;

/// The folder a study writes into, and the files it has written.
#[derive(Debug)]
pub struct OutputDir {
    dir: PathBuf,
    files: Vec<PathBuf>,
}

impl OutputDir {
    /// Creates `dir` (and its parents) if needed.
    pub fn create(dir: &Path) -> Result<OutputDir, StudyError> {
        std::fs::create_dir_all(dir).map_err(|source| StudyError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        Ok(OutputDir {
            dir: dir.to_path_buf(),
            files: Vec::new(),
        })
    }

    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Every file written so far, in order.
    pub fn files(&self) -> &[PathBuf] {
        &self.files
    }

    /// Writes `contents` to `name` in the folder.
    pub fn write(&mut self, name: &str, contents: &str) -> Result<(), StudyError> {
        let path = self.dir.join(name);
        std::fs::write(&path, contents).map_err(|source| StudyError::Io {
            path: path.clone(),
            source,
        })?;
        self.files.push(path);
        Ok(())
    }

    pub fn csv(&mut self, name: &str, table: &Csv) -> Result<(), StudyError> {
        self.write(name, &table.text)
    }

    pub fn json<T: Serialize>(&mut self, name: &str, value: &T) -> Result<(), StudyError> {
        let path = self.dir.join(name);
        let text = serde_json::to_string_pretty(value).map_err(|source| StudyError::Json {
            path: path.clone(),
            source,
        })?;
        self.write(name, &(text + "\n"))
    }
}

/// A CSV table built row by row (values are numbers or plain names, so no
/// quoting is needed; names with commas are quoted).
#[derive(Debug, Clone)]
pub struct Csv {
    text: String,
    columns: usize,
}

impl Csv {
    pub fn new(header: &[&str]) -> Csv {
        Csv {
            text: header.join(",") + "\n",
            columns: header.len(),
        }
    }

    /// Appends a row; `cells` must match the header.
    pub fn row(&mut self, cells: &[Cell]) {
        debug_assert_eq!(cells.len(), self.columns, "CSV row width");
        for (i, cell) in cells.iter().enumerate() {
            if i > 0 {
                self.text.push(',');
            }
            match cell {
                Cell::Num(v) => {
                    let _ = write!(self.text, "{v}");
                }
                Cell::Int(v) => {
                    let _ = write!(self.text, "{v}");
                }
                Cell::Text(t) if t.contains(',') || t.contains('"') => {
                    let _ = write!(self.text, "\"{}\"", t.replace('"', "\"\""));
                }
                Cell::Text(t) => self.text.push_str(t),
            }
        }
        self.text.push('\n');
    }

    pub fn text(&self) -> &str {
        &self.text
    }
}

/// One CSV cell.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Num(f64),
    Int(u64),
    Text(String),
}

impl From<f64> for Cell {
    fn from(v: f64) -> Cell {
        Cell::Num(v)
    }
}

impl From<f32> for Cell {
    fn from(v: f32) -> Cell {
        Cell::Num(f64::from(v))
    }
}

impl From<usize> for Cell {
    fn from(v: usize) -> Cell {
        Cell::Int(v as u64)
    }
}

impl From<u64> for Cell {
    fn from(v: u64) -> Cell {
        Cell::Int(v)
    }
}

impl From<&str> for Cell {
    fn from(v: &str) -> Cell {
        Cell::Text(v.to_string())
    }
}

impl From<String> for Cell {
    fn from(v: String) -> Cell {
        Cell::Text(v)
    }
}

/// `[a.into(), b.into(), ...]`: a CSV row of mixed cells.
#[macro_export]
macro_rules! cells {
    ($($value:expr_2021),* $(,)?) => {
        [$($crate::output::Cell::from($value)),*]
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_and_quoting() {
        let mut csv = Csv::new(&["name", "value", "count"]);
        csv.row(&cells!["a,b", 0.5f64, 3usize]);
        csv.row(&cells!["plain", 1e-7f64, 0u64]);
        assert_eq!(
            csv.text(),
            "name,value,count\n\"a,b\",0.5,3\nplain,0.0000001,0\n"
        );
    }
}
