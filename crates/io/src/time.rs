//! Which stored time step to read, the same way for every format: the one
//! asked for by number, the one nearest a time asked for, else the first.

/// Why no step could be chosen; its message is the one every reader
/// gives after the file's name.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StepError {
    /// A step number beyond those stored.
    #[error("{}", out_of_range(*requested, *count))]
    OutOfRange { requested: usize, count: usize },
    /// A time asked of a file without times, a time that is not a number,
    /// or a step and a time both given.
    #[error("{0}")]
    Time(String),
}

/// The 0-based step to read among `times` (`None` when none is stored and
/// none was asked for).
///
/// # Errors
/// [`StepError`] as above.
pub fn choose_step(
    times: &[f64],
    step: Option<usize>,
    time: Option<f64>,
) -> Result<Option<usize>, StepError> {
    match (step, time) {
        (Some(_), Some(_)) => Err(StepError::Time(
            "give a time step or a time, not both".into(),
        )),
        (Some(step), None) if step < times.len() => Ok(Some(step)),
        (Some(step), None) => Err(StepError::OutOfRange {
            requested: step,
            count: times.len(),
        }),
        (None, Some(t)) if !t.is_finite() => {
            Err(StepError::Time(format!("time {t} is not a finite number")))
        }
        (None, Some(t)) if times.is_empty() => Err(StepError::Time(format!(
            "time {t} asked for, but the file stores no time steps"
        ))),
        (None, Some(t)) => {
            let mut best = 0;
            for (i, ti) in times.iter().enumerate() {
                if (ti - t).abs() < (times[best] - t).abs() {
                    best = i;
                }
            }
            Ok(Some(best))
        }
        (None, None) => Ok((!times.is_empty()).then_some(0)),
    }
}

/// "time step 3 is out of range: the file stores 2 time step(s) (0..=1)".
pub fn out_of_range(requested: usize, count: usize) -> String {
    let range = if count > 0 {
        format!(" (0..={})", count - 1)
    } else {
        String::new()
    };
    format!("time step {requested} is out of range: the file stores {count} time step(s){range}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn by_number_by_time_or_the_first() {
        let times = [0.0, 0.5, 1.0];
        assert_eq!(choose_step(&times, None, None), Ok(Some(0)));
        assert_eq!(choose_step(&times, Some(2), None), Ok(Some(2)));
        assert_eq!(choose_step(&times, None, Some(0.7)), Ok(Some(1)));
        assert_eq!(choose_step(&[], None, None), Ok(None));
        assert_eq!(
            choose_step(&times, Some(3), None),
            Err(StepError::OutOfRange {
                requested: 3,
                count: 3
            })
        );
        assert!(matches!(
            choose_step(&times, Some(0), Some(0.0)),
            Err(StepError::Time(_))
        ));
        assert!(matches!(
            choose_step(&[], None, Some(1.0)),
            Err(StepError::Time(_))
        ));
        assert_eq!(
            out_of_range(3, 2),
            "time step 3 is out of range: the file stores 2 time step(s) (0..=1)"
        );
    }
}
