//! Where the commands find the NASA PLOT3D datasets (`tetray study speed`,
//! `tetray generate plot3d`): a folder given on the command line, else
//! `$TETRAY_DATA_DIR`, else a `data/plot3d` folder in the current
//! directory or above the executable (a checkout, as `cargo run` or
//! `target/release/tetray` run it). Nothing of the machine the binary was
//! built on is compiled in. (The Blunt Fin, the default dataset, is
//! embedded in the binary itself.)

use std::path::{Path, PathBuf};

use anyhow::bail;

/// The folder holding `<name>xyz.bin` and `<name>q.bin` for bluntfin, post
/// and comb: `given` (by the command's `flag`), else `$TETRAY_DATA_DIR`,
/// else `data/plot3d` in the current directory or in a folder above the
/// executable.
///
/// # Errors
/// When the chosen folder does not exist, naming where it came from; when
/// none is given and none is found, saying how to give one.
pub fn plot3d_dir(given: Option<&Path>, flag: &str) -> anyhow::Result<PathBuf> {
    let (dir, from) = match (given, std::env::var_os("TETRAY_DATA_DIR")) {
        (Some(dir), _) => (dir.to_path_buf(), flag),
        (None, Some(dir)) => (PathBuf::from(dir), "TETRAY_DATA_DIR"),
        (None, None) => match found() {
            Some(dir) => return Ok(dir),
            None => bail!(
                "no data/plot3d folder here or above the tetray executable: the PLOT3D \
                 datasets bluntfin, post and comb are in the repository's data/plot3d (give \
                 {flag} or set TETRAY_DATA_DIR)"
            ),
        },
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

/// `data/plot3d` in the current directory, else in the nearest folder
/// above the executable that has one.
fn found() -> Option<PathBuf> {
    let here = Path::new("data/plot3d");
    if here.is_dir() {
        return Some(here.to_path_buf());
    }
    let exe = std::env::current_exe().ok()?;
    exe.ancestors()
        .skip(1)
        .map(|dir| dir.join("data/plot3d"))
        .find(|dir| dir.is_dir())
}
