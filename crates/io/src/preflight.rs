//! Memory preflight: a file whose declared sizes need more memory than the
//! machine has fails at once, with the estimate, before the readers
//! allocate (instead of the kernel killing the process minutes later).

/// A read that would need more memory than is available.
#[derive(Debug, thiserror::Error)]
#[error(
    "{file}: reading {what} needs about {}, more than the {} available (memory and swap, or \
     TETRAY_MEMORY_LIMIT)",
    bytes(*needed),
    bytes(*available)
)]
pub struct MemoryError {
    pub file: String,
    /// What the estimate is of ("the mesh: 2.1e9 nodes, 1.7e9 elements").
    pub what: String,
    pub needed: u64,
    pub available: u64,
}

/// Bytes as a reader sees them: "812 MB", "17.2 GB".
pub fn bytes(n: u64) -> String {
    let n = n as f64;
    if n >= 1e9 {
        format!("{:.1} GB", n / 1e9)
    } else if n >= 1e6 {
        format!("{:.0} MB", n / 1e6)
    } else if n >= 1e3 {
        format!("{:.0} kB", n / 1e3)
    } else {
        format!("{n} bytes")
    }
}

/// The memory a process can still take: `MemAvailable` plus `SwapFree`
/// of `/proc/meminfo`; `None` where that cannot be read (no limit is then
/// applied). `TETRAY_MEMORY_LIMIT` (bytes) overrides it, so a test can
/// see the check without a huge file.
pub fn available_memory() -> Option<u64> {
    if let Some(limit) = std::env::var("TETRAY_MEMORY_LIMIT")
        .ok()
        .and_then(|v| v.trim().parse().ok())
    {
        return Some(limit);
    }
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let field = |name: &str| -> Option<u64> {
        let line = text.lines().find(|l| l.starts_with(name))?;
        let kib: u64 = line[name.len()..]
            .trim()
            .trim_end_matches("kB")
            .trim()
            .parse()
            .ok()?;
        Some(kib * 1024)
    };
    Some(field("MemAvailable:")? + field("SwapFree:").unwrap_or(0))
}

/// Fails when `needed` bytes exceed the memory available.
///
/// # Errors
/// [`MemoryError`] with the estimate and what is available.
pub fn check(file: &str, what: impl FnOnce() -> String, needed: u64) -> Result<(), MemoryError> {
    match available_memory() {
        Some(available) if needed > available => Err(MemoryError {
            file: file.into(),
            what: what(),
            needed,
            available,
        }),
        _ => Ok(()),
    }
}

/// Bytes a regular grid of `points` points and `cells` hexahedra takes
/// once made into tetrahedra: the cell model (f64 points, connectivity,
/// offsets and types) and the split's up to six tetrahedra per cell with
/// their neighbours and walk records (about 48 bytes each).
pub fn grid_bytes(points: u64, cells: u64) -> u64 {
    points
        .saturating_mul(24 + 16)
        .saturating_add(cells.saturating_mul(8 * 8 + 16))
        .saturating_add(cells.saturating_mul(6 * 48))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_a_person_would() {
        assert_eq!(bytes(512), "512 bytes");
        assert_eq!(bytes(812_400_000), "812 MB");
        assert_eq!(bytes(17_200_000_000), "17.2 GB");
    }

    #[test]
    fn this_machine_reports_some_memory() {
        // Linux has /proc/meminfo; elsewhere no limit is applied.
        if std::path::Path::new("/proc/meminfo").exists() {
            assert!(available_memory().expect("meminfo") > 0);
        }
        assert!(check("f", || "x".into(), 1).is_ok());
        let err = check("f", || "everything".into(), u64::MAX).unwrap_err();
        assert!(
            err.to_string().contains("reading everything needs about"),
            "{err}"
        );
    }
}
