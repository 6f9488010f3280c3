//! Thin access to an HDF5 file through `hdf5-reader`: groups, attributes
//! and numeric datasets read as f64 or i64 whatever their stored type,
//! whole or a run of rows. Every size is checked before anything is
//! allocated: against the file's length for data stored as it is, against
//! the memory available for chunked (possibly compressed) data. Every
//! failure names the file and the object.

use std::path::Path;

use hdf5_reader::group::Group;
use hdf5_reader::{Dataset, Datatype, Hdf5File, SliceInfo, SliceInfoElem};

use crate::preflight::{self, MemoryError};

/// How a reader of an HDF5-based format (VTKHDF, CGNS) words the
/// failures of its container: each names the file and the object.
pub(crate) trait H5Error: Sized {
    fn io(file: String, source: std::io::Error) -> Self;
    /// The container or an object could not be read.
    fn hdf5(file: String, what: String, message: String) -> Self;
    /// Content that breaks the format's rules.
    fn invalid(file: String, what: String, message: String) -> Self;
    /// An object the format requires is absent.
    fn missing(file: String, what: String) -> Self;
    /// Data the file's length cannot hold.
    fn truncated(file: String, what: String, expected: u64, found: u64) -> Self;
    fn memory(e: MemoryError) -> Self;
}

/// An open HDF5 file and the name used in messages; `E` is the reader's
/// error type.
pub(crate) struct H5<E> {
    file: Hdf5File,
    pub name: String,
    /// The file's length in bytes.
    len: u64,
    error: std::marker::PhantomData<E>,
}

impl<E: H5Error> H5<E> {
    pub fn open(path: &Path) -> Result<H5<E>, E> {
        let name = path.display().to_string();
        let len = std::fs::metadata(path)
            .map_err(|source| E::io(name.clone(), source))?
            .len();
        let file = Hdf5File::open(path)
            .map_err(|e| E::hdf5(name.clone(), "the HDF5 container".into(), e.to_string()))?;
        H5 {
            file,
            name,
            len,
            error: std::marker::PhantomData,
        }
        .whole()
    }

    pub fn from_bytes(bytes: &[u8], name: &str) -> Result<H5<E>, E> {
        let file = Hdf5File::from_bytes(bytes)
            .map_err(|e| E::hdf5(name.into(), "the HDF5 container".into(), e.to_string()))?;
        H5 {
            file,
            name: name.into(),
            len: bytes.len() as u64,
            error: std::marker::PhantomData,
        }
        .whole()
    }

    /// The file, when it is as long as its superblock says (a truncated
    /// file may still hold every object the reader needs, but not the data
    /// its writer put there).
    fn whole(self) -> Result<H5<E>, E> {
        let superblock = self.file.superblock();
        let end = superblock
            .base_address
            .checked_add(superblock.eof_address)
            .filter(|_| superblock.eof_address != u64::MAX);
        match end {
            Some(end) if end > self.len => Err(E::truncated(
                self.name,
                "the HDF5 superblock".into(),
                end,
                self.len,
            )),
            _ => Ok(self),
        }
    }

    pub fn hdf5_error(&self, what: &str, e: impl std::fmt::Display) -> E {
        E::hdf5(self.name.clone(), what.into(), e.to_string())
    }

    pub fn invalid(&self, what: &str, message: String) -> E {
        E::invalid(self.name.clone(), what.into(), message)
    }

    /// The group at `path` (absolute), or `None` when there is none.
    pub fn group(&self, path: &str) -> Option<Group> {
        self.file.group(path).ok()
    }

    /// The group at `path`, which the format requires.
    pub fn require_group(&self, path: &str) -> Result<Group, E> {
        self.file
            .group(path)
            .map_err(|_| E::missing(self.name.clone(), format!("group {path}")))
    }

    /// The dataset `name` of `group`, or `None`.
    pub fn dataset(&self, group: &Group, name: &str) -> Option<Dataset> {
        group.dataset(name).ok()
    }

    /// The dataset `name` of `group` (at `path`), which the format
    /// requires.
    pub fn require_dataset(&self, group: &Group, path: &str, name: &str) -> Result<Dataset, E> {
        group
            .dataset(name)
            .map_err(|_| E::missing(self.name.clone(), format!("dataset {path}/{name}")))
    }

    /// The names of the datasets directly in `group`, in the file's order.
    pub fn dataset_names(&self, group: &Group, path: &str) -> Result<Vec<String>, E> {
        let (_, datasets) = group.member_names().map_err(|e| self.hdf5_error(path, e))?;
        Ok(datasets)
    }

    /// The names of the groups directly in `group`, in the file's order.
    pub fn group_names(&self, group: &Group, path: &str) -> Result<Vec<String>, E> {
        let (groups, _) = group.member_names().map_err(|e| self.hdf5_error(path, e))?;
        Ok(groups)
    }

    /// A string attribute of `group`, or `None` when it has none.
    pub fn string_attribute(&self, group: &Group, name: &str) -> Option<String> {
        let attribute = group.attribute(name).ok()?;
        let strings = attribute.read_strings().ok()?;
        strings
            .first()
            .map(|s| s.trim_end_matches('\0').trim().to_string())
    }

    /// A numeric attribute of `group` as f64 values, or `None`.
    pub fn numeric_attribute(&self, group: &Group, name: &str) -> Option<Vec<f64>> {
        let attribute = group.attribute(name).ok()?;
        let n = usize::try_from(attribute.num_elements().ok()?).ok()?;
        let dtype = attribute.datatype.clone();
        macro_rules! read {
            ($t:ty) => {
                attribute
                    .read_1d::<$t>()
                    .ok()
                    .map(|v| v.into_iter().map(|x| x as f64).collect::<Vec<f64>>())
            };
        }
        let values = match dtype {
            Datatype::FloatingPoint { size: 8, .. } => read!(f64),
            Datatype::FloatingPoint { size: 4, .. } => read!(f32),
            Datatype::FixedPoint { size, signed, .. } => match (size, signed) {
                (1, true) => read!(i8),
                (1, false) => read!(u8),
                (2, true) => read!(i16),
                (2, false) => read!(u16),
                (4, true) => read!(i32),
                (4, false) => read!(u32),
                (8, true) => read!(i64),
                (8, false) => read!(u64),
                _ => None,
            },
            _ => None,
        }?;
        (values.len() == n).then_some(values)
    }

    /// The shape of a dataset.
    pub fn shape(ds: &Dataset) -> Vec<usize> {
        ds.shape().iter().map(|&d| d as usize).collect()
    }

    /// Rows `start .. start + count` of `ds` (all of its other dimensions)
    /// as f64, with the values per row; `what` names it in messages.
    pub fn rows_f64(
        &self,
        ds: &Dataset,
        what: &str,
        start: usize,
        count: usize,
    ) -> Result<(Vec<f64>, usize), E> {
        self.rows(ds, what, start, count, Value::F64)
            .map(|(v, row)| (v.into_f64(), row))
    }

    /// As [`H5::rows_f64`], as i64 (integer data only).
    pub fn rows_i64(
        &self,
        ds: &Dataset,
        what: &str,
        start: usize,
        count: usize,
    ) -> Result<(Vec<i64>, usize), E> {
        let (values, row) = self.rows(ds, what, start, count, Value::I64)?;
        match values {
            Values::I64(v) => Ok((v, row)),
            Values::F64(_) => Err(self.invalid(
                what,
                format!("holds {}, where integers belong", describe(ds.dtype())),
            )),
        }
    }

    /// The whole of a one-dimensional integer dataset.
    pub fn all_i64(&self, ds: &Dataset, what: &str) -> Result<Vec<i64>, E> {
        let rows = Self::shape(ds).first().copied().unwrap_or(1);
        Ok(self.rows_i64(ds, what, 0, rows)?.0)
    }

    /// The whole of a one-dimensional numeric dataset as f64.
    pub fn all_f64(&self, ds: &Dataset, what: &str) -> Result<Vec<f64>, E> {
        let rows = Self::shape(ds).first().copied().unwrap_or(1);
        Ok(self.rows_f64(ds, what, 0, rows)?.0)
    }

    fn rows(
        &self,
        ds: &Dataset,
        what: &str,
        start: usize,
        count: usize,
        want: Value,
    ) -> Result<(Values, usize), E> {
        let shape = Self::shape(ds);
        if let Some(max) = ds.max_dims()
            && let Some(axis) = (0..shape.len()).find(|&a| {
                max.get(a)
                    .is_some_and(|&m| m != u64::MAX && shape[a] as u64 > m)
            })
        {
            return Err(self.invalid(
                what,
                format!(
                    "dimension {axis} has {} entries, past its maximum {}",
                    shape[axis], max[axis]
                ),
            ));
        }
        let (rows, rest) = match shape.split_first() {
            Some((&rows, rest)) => (rows, rest),
            // A scalar dataset: one row of one value.
            None => (1, &[][..]),
        };
        let end = start.checked_add(count).filter(|&e| e <= rows);
        let Some(end) = end else {
            return Err(self.invalid(
                what,
                format!(
                    "rows {start} to {} asked of a dataset of {rows}",
                    start as u128 + count as u128
                ),
            ));
        };
        let row: usize = rest
            .iter()
            .try_fold(1usize, |n, &d| n.checked_mul(d))
            .ok_or_else(|| self.invalid(what, format!("shape {shape:?} overflows")))?;
        let element = element_size(ds.dtype())
            .ok_or_else(|| self.invalid(what, format!("holds {}", describe(ds.dtype()))))?;
        let values = count
            .checked_mul(row)
            .ok_or_else(|| self.invalid(what, format!("shape {shape:?} overflows")))?;
        let stored = (values as u64).saturating_mul(element as u64);
        if ds.chunks().is_none() {
            // Stored as it is: the bytes must be in the file.
            if stored > self.len {
                return Err(E::truncated(
                    self.name.clone(),
                    what.into(),
                    stored,
                    self.len,
                ));
            }
        } else {
            // Chunked data may be compressed: the file's length says
            // nothing, the memory the result takes does.
            let result = (values as u64).saturating_mul(8);
            preflight::check(
                &self.name,
                || format!("{what} ({values} values)"),
                result.saturating_add(stored),
            )
            .map_err(E::memory)?;
        }
        if count == 0 || row == 0 {
            return Ok((want.empty(ds.dtype()), row));
        }
        let mut selections = vec![SliceInfoElem::Slice {
            start: start as u64,
            end: end as u64,
            step: 1,
        }];
        selections.extend(rest.iter().map(|&d| SliceInfoElem::Slice {
            start: 0,
            end: d as u64,
            step: 1,
        }));
        let selection = SliceInfo { selections };
        let fail = |e: hdf5_reader::error::Error| self.hdf5_error(what, e);
        macro_rules! read {
            ($t:ty, $wrap:ident) => {{
                let array = if shape.is_empty() {
                    ds.read_array::<$t>().map_err(fail)?
                } else {
                    ds.read_slice::<$t>(&selection).map_err(fail)?
                };
                // Logical (row-major) order, whatever the memory layout.
                Values::$wrap(array.iter().map(|&x| x as _).collect())
            }};
        }
        let values = match ds.dtype() {
            Datatype::FloatingPoint { size: 8, .. } => read!(f64, F64),
            Datatype::FloatingPoint { size: 4, .. } => read!(f32, F64),
            Datatype::FixedPoint { size, signed, .. } => match (size, signed) {
                (1, true) => read!(i8, I64),
                (1, false) => read!(u8, I64),
                (2, true) => read!(i16, I64),
                (2, false) => read!(u16, I64),
                (4, true) => read!(i32, I64),
                (4, false) => read!(u32, I64),
                (8, true) => read!(i64, I64),
                (8, false) => {
                    let array = ds.read_slice::<u64>(&selection).map_err(fail)?;
                    let mut out = Vec::with_capacity(array.len());
                    for &x in array.iter() {
                        out.push(i64::try_from(x).map_err(|_| {
                            self.invalid(what, format!("value {x} is beyond 64-bit signed range"))
                        })?);
                    }
                    Values::I64(out)
                }
                _ => return Err(self.invalid(what, format!("holds {}", describe(ds.dtype())))),
            },
            other => return Err(self.invalid(what, format!("holds {}", describe(other)))),
        };
        if values.len() != values_len(count, row) {
            return Err(self.invalid(
                what,
                format!(
                    "read {} values where {} belong",
                    values.len(),
                    values_len(count, row)
                ),
            ));
        }
        Ok((values, row))
    }
}

fn values_len(count: usize, row: usize) -> usize {
    count * row
}

/// What the caller will convert to; empty results keep the stored kind.
#[derive(Clone, Copy)]
enum Value {
    F64,
    I64,
}

impl Value {
    fn empty(self, dtype: &Datatype) -> Values {
        match (self, dtype) {
            (_, Datatype::FloatingPoint { .. }) | (Value::F64, _) => Values::F64(Vec::new()),
            (Value::I64, _) => Values::I64(Vec::new()),
        }
    }
}

/// Values as read: floating-point data as f64, integers as i64.
enum Values {
    F64(Vec<f64>),
    I64(Vec<i64>),
}

impl Values {
    fn len(&self) -> usize {
        match self {
            Values::F64(v) => v.len(),
            Values::I64(v) => v.len(),
        }
    }

    fn into_f64(self) -> Vec<f64> {
        match self {
            Values::F64(v) => v,
            Values::I64(v) => v.into_iter().map(|x| x as f64).collect(),
        }
    }
}

fn element_size(dtype: &Datatype) -> Option<usize> {
    match dtype {
        Datatype::FloatingPoint { size: 4 | 8, .. } => Some(dtype_size(dtype)),
        Datatype::FixedPoint {
            size: 1 | 2 | 4 | 8,
            ..
        } => Some(dtype_size(dtype)),
        _ => None,
    }
}

fn dtype_size(dtype: &Datatype) -> usize {
    match dtype {
        Datatype::FloatingPoint { size, .. } | Datatype::FixedPoint { size, .. } => {
            usize::from(*size)
        }
        _ => 0,
    }
}

/// A stored type as a message says it.
fn describe(dtype: &Datatype) -> String {
    match dtype {
        Datatype::FloatingPoint { size, .. } => {
            format!("{}-bit floats", u64::from(*size) * 8)
        }
        Datatype::FixedPoint { size, signed, .. } => format!(
            "{}-bit {} integers",
            u64::from(*size) * 8,
            if *signed { "signed" } else { "unsigned" }
        ),
        Datatype::String { .. } | Datatype::VarLen { .. } => "strings".into(),
        Datatype::Compound { .. } => "compound records".into(),
        other => format!("values of type {other:?}"),
    }
}
