//! Where the commands find the NASA PLOT3D datasets (`tetray study speed`,
//! `tetray generate plot3d`): a folder given on the command line, else
//! `$TETRAY_DATA_DIR`, else the repository's `data/plot3d`, located from the
//! source tree the binary was built from, so no flag is needed from any
//! working directory. (The Blunt Fin, the default dataset, is embedded in
//! the binary itself: see `scene.rs`.)

use std::path::{Path, PathBuf};

use anyhow::bail;

/// The repository's PLOT3D folder, as built.
pub const BUILT_IN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/plot3d");

/// The folder holding `<name>xyz.bin` and `<name>q.bin` for bluntfin, post
/// and comb: `given` (by the command's `flag`), else `$TETRAY_DATA_DIR`,
/// else [`BUILT_IN`].
///
/// # Errors
/// When the chosen folder does not exist, naming where it came from.
pub fn plot3d_dir(given: Option<&Path>, flag: &str) -> anyhow::Result<PathBuf> {
    let (dir, from) = match (given, std::env::var_os("TETRAY_DATA_DIR")) {
        (Some(dir), _) => (dir.to_path_buf(), flag),
        (None, Some(dir)) => (PathBuf::from(dir), "TETRAY_DATA_DIR"),
        (None, None) => (
            PathBuf::from(BUILT_IN),
            "the source tree tetray was built from",
        ),
    };
    if !dir.is_dir() {
        bail!(
            "{}: no such folder ({from}); the PLOT3D datasets bluntfin, post and comb are in \
             the repository's data/plot3d (give {flag} or set TETRAY_DATA_DIR)",
            dir.display()
        );
    }
    Ok(dir)
}
