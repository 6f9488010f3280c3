//! Thin access to the netCDF container (classic CDF-1/2/5 or netCDF-4)
//! through `netcdf-reader`: dimensions, variables read as f64 or strings,
//! attributes; every failure becomes an [`ExodusError`] naming the file.

use netcdf_reader::{NcFile, NcSliceInfo, NcSliceInfoElem, NcVariable};

use super::ExodusError;

/// An open Exodus container and the name used in messages.
pub(super) struct Nc<'a> {
    file: NcFile,
    pub name: &'a str,
}

impl<'a> Nc<'a> {
    /// Opens the file at `path` without reading it whole: classic files
    /// are mapped, netCDF-4 files read object by object.
    pub fn open(path: &std::path::Path, name: &'a str) -> Result<Self, ExodusError> {
        let file = NcFile::open(path).map_err(|e| ExodusError::NetCdf {
            file: name.into(),
            what: "header".into(),
            message: e.to_string(),
        })?;
        Ok(Nc { file, name })
    }

    pub fn from_bytes(bytes: Vec<u8>, name: &'a str) -> Result<Self, ExodusError> {
        let file = NcFile::from_vec(bytes).map_err(|e| ExodusError::NetCdf {
            file: name.into(),
            what: "header".into(),
            message: e.to_string(),
        })?;
        Ok(Nc { file, name })
    }

    /// Describes the container ("netCDF classic", "netCDF-4"...).
    pub fn format(&self) -> String {
        format!("{:?}", self.file.format())
    }

    /// The size of a dimension, or `None` when it is not defined.
    pub fn dim(&self, name: &str) -> Option<usize> {
        let dim = self.file.dimension(name).ok()?;
        usize::try_from(dim.size).ok()
    }

    /// How many variables the file defines.
    pub fn variable_count(&self) -> usize {
        self.file.variables().map_or(0, <[_]>::len)
    }

    /// How many dimensions the file defines.
    pub fn dimension_count(&self) -> usize {
        self.file.dimensions().map_or(0, <[_]>::len)
    }

    /// The size of dimension `dim` (0 when it is not defined), at most
    /// `limit`: the number of the file's own `things` (dimensions,
    /// variables) each counted item needs one of. A larger size is a
    /// header's claim, refused before anything is made for it.
    pub fn count_within(
        &self,
        dim: &str,
        limit: usize,
        things: &str,
    ) -> Result<usize, ExodusError> {
        let count = self.dim(dim).unwrap_or(0);
        if count > limit {
            return Err(ExodusError::Invalid {
                file: self.name.into(),
                what: format!("dimension \"{dim}\""),
                message: format!("is {count}, more than the {limit} {things} the file defines"),
            });
        }
        Ok(count)
    }

    /// The size of a dimension the format requires.
    pub fn require_dim(&self, name: &str) -> Result<usize, ExodusError> {
        self.dim(name)
            .ok_or_else(|| self.missing(format!("dimension \"{name}\"")))
    }

    pub fn var(&self, name: &str) -> Option<&NcVariable> {
        self.file.variable(name).ok()
    }

    pub fn missing(&self, what: String) -> ExodusError {
        ExodusError::Missing {
            file: self.name.into(),
            what,
        }
    }

    fn read_error(&self, variable: &str, e: netcdf_reader::Error) -> ExodusError {
        ExodusError::NetCdf {
            file: self.name.into(),
            what: format!("variable \"{variable}\""),
            message: e.to_string(),
        }
    }

    /// The whole variable in storage order, promoted to f64. Its element
    /// count must be `expected` (`what` describes that count in messages).
    pub fn read_f64(
        &self,
        name: &str,
        expected: usize,
        what: &str,
    ) -> Result<Vec<f64>, ExodusError> {
        let var = self
            .var(name)
            .ok_or_else(|| self.missing(format!("variable \"{name}\"")))?;
        self.check_len(name, var_len(var), expected, what)?;
        let array = self
            .file
            .read_variable_as_f64(name)
            .map_err(|e| self.read_error(name, e))?;
        let values: Vec<f64> = array.iter().copied().collect();
        self.check_len(name, values.len(), expected, what)?;
        Ok(values)
    }

    /// One hyperslab: `fixed` gives the index of each leading dimension,
    /// the rest are read whole; the result must hold `expected` values.
    pub fn read_f64_at(
        &self,
        name: &str,
        fixed: &[usize],
        expected: usize,
        what: &str,
    ) -> Result<Vec<f64>, ExodusError> {
        let var = self
            .var(name)
            .ok_or_else(|| self.missing(format!("variable \"{name}\"")))?;
        let shape = var.shape();
        if shape.len() <= fixed.len() {
            return Err(ExodusError::Invalid {
                file: self.name.into(),
                what: format!("variable \"{name}\""),
                message: format!(
                    "has {} dimension(s), expected more than {}",
                    shape.len(),
                    fixed.len()
                ),
            });
        }
        self.check_len(name, count(&shape[fixed.len()..]), expected, what)?;
        let mut selections: Vec<NcSliceInfoElem> = fixed
            .iter()
            .map(|&i| NcSliceInfoElem::Index(i as u64))
            .collect();
        selections.extend(
            shape[fixed.len()..]
                .iter()
                .map(|&n| NcSliceInfoElem::Slice {
                    start: 0,
                    end: n,
                    step: 1,
                }),
        );
        let array = self
            .file
            .read_variable_slice_as_f64(name, &NcSliceInfo { selections })
            .map_err(|e| self.read_error(name, e))?;
        let values: Vec<f64> = array.iter().copied().collect();
        self.check_len(name, values.len(), expected, what)?;
        Ok(values)
    }

    /// Integer data (connectivity, ids, flags) read as f64 and checked to
    /// be whole numbers.
    pub fn read_ints(
        &self,
        name: &str,
        expected: usize,
        what: &str,
    ) -> Result<Vec<i64>, ExodusError> {
        let values = self.read_f64(name, expected, what)?;
        values
            .iter()
            .enumerate()
            .map(|(i, &v)| {
                if v.fract() == 0.0 && v.abs() < 9.0e15 {
                    Ok(v as i64)
                } else {
                    Err(ExodusError::Invalid {
                        file: self.name.into(),
                        what: format!("variable \"{name}\""),
                        message: format!("value {i} is {v}, not an integer"),
                    })
                }
            })
            .collect()
    }

    /// A char array of names (one per row), cut at the first NUL and
    /// stripped of padding spaces; `None` when the variable is absent.
    pub fn names(&self, name: &str, expected: usize) -> Result<Option<Vec<String>>, ExodusError> {
        if self.var(name).is_none() {
            return Ok(None);
        }
        let rows = self
            .file
            .read_variable_as_strings(name)
            .map_err(|e| self.read_error(name, e))?;
        self.check_len(name, rows.len(), expected, "names")?;
        Ok(Some(rows.iter().map(|s| clean_name(s)).collect()))
    }

    /// A text attribute of a variable, cleaned like [`Nc::names`].
    pub fn text_attribute(&self, var: &str, attribute: &str) -> Option<String> {
        let value = &self.var(var)?.attribute(attribute)?.value;
        value.as_string().map(|s| clean_name(&s))
    }

    fn check_len(
        &self,
        name: &str,
        found: usize,
        expected: usize,
        what: &str,
    ) -> Result<(), ExodusError> {
        if found == expected {
            return Ok(());
        }
        Err(ExodusError::WrongLength {
            file: self.name.into(),
            variable: name.into(),
            what: what.into(),
            expected,
            found,
        })
    }
}

fn var_len(var: &NcVariable) -> usize {
    count(&var.shape())
}

/// Elements of a shape; `usize::MAX` for a count too large (a garbled
/// header), which then fails the length check.
fn count(shape: &[u64]) -> usize {
    shape
        .iter()
        .try_fold(1u64, |n, &d| n.checked_mul(d))
        .and_then(|n| usize::try_from(n).ok())
        .unwrap_or(usize::MAX)
}

/// `a * b` of counts from the file, saturating (see [`count`]).
pub(super) fn times(a: usize, b: usize) -> usize {
    a.saturating_mul(b)
}

/// Exodus names are fixed-length char arrays padded with NUL or spaces.
pub(super) fn clean_name(raw: &str) -> String {
    let cut = raw.split('\0').next().unwrap_or("");
    cut.trim().to_string()
}
