//! The `Steps` group of a temporal VTKHDF file: the times, and for each
//! step where its data starts in the concatenated datasets.

use super::H5;
use super::VtkHdfError;

/// The steps of a file (none for a file without a `Steps` group).
pub(super) struct Steps {
    pub times: Vec<f64>,
    /// Each offsets dataset of the group, read whole: name -> (values, per
    /// step).
    offsets: Vec<(String, Vec<i64>, usize)>,
}

const PATH: &str = "/VTKHDF/Steps";

impl Steps {
    pub fn read(h5: &H5) -> Result<Steps, VtkHdfError> {
        let Some(group) = h5.group(PATH) else {
            return Ok(Steps {
                times: Vec::new(),
                offsets: Vec::new(),
            });
        };
        let declared = h5
            .numeric_attribute(&group, "NSteps")
            .and_then(|v| v.first().copied());
        let times = match h5.dataset(&group, "Values") {
            Some(ds) => h5.all_f64(&ds, "Steps/Values")?,
            None => {
                let n = declared.ok_or_else(|| VtkHdfError::Missing {
                    file: h5.name.clone(),
                    what: "Steps/Values or the NSteps attribute".into(),
                })?;
                if !(n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64) {
                    return Err(h5.invalid("Steps", format!("NSteps is {n}, not a step count")));
                }
                // The times are made from the count alone: a header's claim.
                crate::preflight::check(
                    &h5.name,
                    || format!("the {n} time steps NSteps declares"),
                    (n as u64).saturating_mul(8),
                )?;
                (0..n as usize).map(|i| i as f64).collect()
            }
        };
        if let Some(n) = declared
            && n as usize != times.len()
        {
            return Err(h5.invalid(
                "Steps",
                format!("NSteps is {n} but Values holds {} times", times.len()),
            ));
        }
        if let Some(t) = times.iter().find(|t| !t.is_finite()) {
            return Err(h5.invalid("Steps/Values", format!("time {t} is not a number")));
        }
        let mut offsets = Vec::new();
        for name in h5.dataset_names(&group, PATH)? {
            if name == "Values" {
                continue;
            }
            let ds = h5.require_dataset(&group, PATH, &name)?;
            let rows = H5::shape(&ds).first().copied().unwrap_or(1);
            let (values, per_step) = h5.rows_i64(&ds, &format!("Steps/{name}"), 0, rows)?;
            if rows != times.len() {
                return Err(h5.invalid(
                    &format!("Steps/{name}"),
                    format!("{rows} rows for {} time steps", times.len()),
                ));
            }
            offsets.push((name, values, per_step.max(1)));
        }
        for sub in ["PointDataOffsets", "CellDataOffsets"] {
            let path = format!("{PATH}/{sub}");
            let Some(group) = h5.group(&path) else {
                continue;
            };
            for name in h5.dataset_names(&group, &path)? {
                let ds = h5.require_dataset(&group, &path, &name)?;
                let what = format!("Steps/{sub}/{name}");
                let rows = H5::shape(&ds).first().copied().unwrap_or(1);
                let (values, per_step) = h5.rows_i64(&ds, &what, 0, rows)?;
                if rows != times.len() {
                    return Err(
                        h5.invalid(&what, format!("{rows} rows for {} time steps", times.len()))
                    );
                }
                offsets.push((format!("{sub}/{name}"), values, per_step.max(1)));
            }
        }
        Ok(Steps { times, offsets })
    }

    /// Whether the file has steps.
    pub fn temporal(&self) -> bool {
        !self.times.is_empty()
    }

    /// The value of offsets dataset `name` (`PointOffsets`,
    /// `PointDataOffsets/p`...) at `step`, or `None` when the file has no
    /// such dataset (or no steps).
    pub fn offset(&self, name: &str, step: Option<usize>) -> Option<i64> {
        let step = step?;
        let (_, values, per_step) = self.offsets.iter().find(|(n, _, _)| n == name)?;
        values.get(step * per_step).copied()
    }
}
