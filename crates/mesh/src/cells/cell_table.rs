//! The cells of a grid as validated u32 point-index slices (checked and
//! converted in parallel), and what the assembly asks of them.

use rayon::prelude::*;

use super::CellError;
use crate::{first_index, first_position};

/// Cells as validated u32 point-index slices.
pub(super) struct CellTable<'a> {
    offsets: &'a [usize],
    pub(super) ids: Vec<u32>,
}

impl<'a> CellTable<'a> {
    pub(super) fn new(
        offsets: &'a [usize],
        connectivity: &[i64],
        ncells: usize,
        npoints: usize,
        file: &str,
    ) -> Result<Self, CellError> {
        let offsets: &[usize] = if offsets.is_empty() { &[0] } else { offsets };
        let invalid = |message: String| CellError::Invalid {
            file: file.into(),
            section: "cells".into(),
            message,
        };
        if offsets.len() != ncells + 1 || offsets[0] != 0 {
            return Err(invalid(format!(
                "{} cell offsets for {ncells} cell types",
                offsets.len().saturating_sub(1)
            )));
        }
        // The first cell whose span is malformed, and the first index out
        // of range; whichever cell comes first is the error (as a pass over
        // the cells in order would find it).
        let bad_span = first_index(ncells, |c| {
            let (start, end) = (offsets[c], offsets[c + 1]);
            end < start || end > connectivity.len()
        });
        let bad_index = first_position(connectivity, |&index| {
            u32::try_from(index).map_or(true, |i| i as usize >= npoints)
        });
        // The cells before `bad_span` (all, when there is none) have
        // well-formed spans in order, covering the entries below `limit`:
        // an entry there belongs to the last of them starting at or before
        // it. Entries past the cells' end are no cell's (the count check
        // below reports them).
        let limit = bad_span.map_or(offsets[ncells], |c| offsets[c]);
        let well_formed = &offsets[..bad_span.unwrap_or(ncells)];
        let cell_of = |entry: usize| well_formed.partition_point(|&o| o <= entry) - 1;
        match (bad_index, bad_span) {
            (Some(entry), _) if entry < limit => {
                return Err(CellError::BadIndex {
                    file: file.into(),
                    cell: cell_of(entry),
                    index: connectivity[entry],
                    npoints,
                });
            }
            (_, Some(c)) => {
                let (start, end) = (offsets[c], offsets[c + 1]);
                return Err(invalid(format!(
                    "cell {c} spans connectivity entries {start}..{end} of {}",
                    connectivity.len()
                )));
            }
            _ => {}
        }
        if offsets[ncells] != connectivity.len() {
            return Err(invalid(format!(
                "the cells use {} connectivity entries but there are {}",
                offsets[ncells],
                connectivity.len()
            )));
        }
        // In range, checked above.
        let ids = connectivity.par_iter().map(|&index| index as u32).collect();
        Ok(CellTable { offsets, ids })
    }

    pub(super) fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    pub(super) fn cell(&self, c: usize) -> &[u32] {
        &self.ids[self.offsets[c]..self.offsets[c + 1]]
    }

    /// Distinct points of cell `c` (collapsed cells repeat some).
    fn distinct(&self, c: usize) -> impl Iterator<Item = u32> + '_ {
        let ids = self.cell(c);
        ids.iter()
            .enumerate()
            .filter(move |&(i, id)| !ids[..i].contains(id))
            .map(|(_, &id)| id)
    }

    /// How many volume cells use each point.
    pub(super) fn point_users(&self, volume_cell: &[bool], npoints: usize) -> Vec<u32> {
        let mut users = vec![0u32; npoints];
        for c in (0..self.len()).filter(|&c| volume_cell[c]) {
            for p in self.distinct(c) {
                users[p as usize] += 1;
            }
        }
        users
    }

    /// Mean over the volume cells using each point; 0 where none does.
    pub(super) fn average_to_points(
        &self,
        per_cell: &[f64],
        volume_cell: &[bool],
        users: &[u32],
    ) -> Vec<f64> {
        let mut sum = vec![0.0f64; users.len()];
        for c in (0..self.len()).filter(|&c| volume_cell[c]) {
            for p in self.distinct(c) {
                sum[p as usize] += per_cell[c];
            }
        }
        sum.iter()
            .zip(users)
            .map(|(&s, &n)| if n == 0 { 0.0 } else { s / n as f64 })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first error of a pass over the cells in order (span, then each
    /// index), the rule the parallel checks must keep.
    fn serial_error(offsets: &[usize], connectivity: &[i64], npoints: usize) -> Option<String> {
        let ncells = offsets.len() - 1;
        for c in 0..ncells {
            let (start, end) = (offsets[c], offsets[c + 1]);
            if end < start || end > connectivity.len() {
                return Some(format!("span {c}"));
            }
            for &index in &connectivity[start..end] {
                if index < 0 || index as usize >= npoints {
                    return Some(format!("index {index} in cell {c}"));
                }
            }
        }
        (offsets[ncells] != connectivity.len()).then(|| "count".to_string())
    }

    fn parallel_error(offsets: &[usize], connectivity: &[i64], npoints: usize) -> Option<String> {
        let ncells = offsets.len() - 1;
        match CellTable::new(offsets, connectivity, ncells, npoints, "f") {
            Ok(table) => {
                let all: Vec<u32> = (0..table.len())
                    .flat_map(|c| table.cell(c).to_vec())
                    .collect();
                let want: Vec<u32> = connectivity.iter().map(|&i| i as u32).collect();
                assert_eq!(all, want);
                None
            }
            Err(CellError::BadIndex { cell, index, .. }) => {
                Some(format!("index {index} in cell {cell}"))
            }
            Err(CellError::Invalid { message, .. }) if message.starts_with("cell ") => {
                Some(format!("span {}", message.split(' ').nth(1).unwrap_or("?")))
            }
            Err(CellError::Invalid { message, .. }) if message.starts_with("the cells use") => {
                Some("count".to_string())
            }
            Err(e) => panic!("unexpected error {e}"),
        }
    }

    #[test]
    fn parallel_checks_find_the_first_error_in_cell_order() {
        // 6 cells over 20 points; every combination of one bad index
        // position, one bad span and a short or long connectivity.
        let npoints = 20;
        let good: Vec<i64> = (0..24).map(|i| (i * 7) % 20).collect();
        let offsets: Vec<usize> = vec![0, 4, 4, 8, 14, 18, 24];
        let mut cases = 0;
        for bad_at in (0..=good.len()).chain([usize::MAX]) {
            for bad_index in [-1i64, 20, i64::MAX] {
                for span in (0..offsets.len()).chain([usize::MAX]) {
                    for span_value in [2usize, 30] {
                        for len_change in [-2i64, 0, 3] {
                            let mut connectivity = good.clone();
                            if len_change < 0 {
                                connectivity.truncate(connectivity.len() - 2);
                            } else {
                                connectivity.extend((0..len_change).map(|i| i % 20));
                            }
                            if bad_at < connectivity.len() {
                                connectivity[bad_at] = bad_index;
                            }
                            let mut offsets = offsets.clone();
                            if (1..offsets.len()).contains(&span) {
                                offsets[span] = span_value;
                            }
                            assert_eq!(
                                parallel_error(&offsets, &connectivity, npoints),
                                serial_error(&offsets, &connectivity, npoints),
                                "offsets {offsets:?}, connectivity {connectivity:?}"
                            );
                            cases += 1;
                        }
                    }
                }
            }
        }
        assert!(cases > 1000);
    }
}
