//! The in-situ entry points under `mpirun -n P --oversubscribe`, P =
//! 1..4: the binary `in_situ` renders a hollow box split spatially by
//! rank, as tetrahedra arrays and as hexahedral VTK cells, and checks it
//! on rank 0 against the whole mesh rendered in one process (9e-7 per
//! pixel channel, 1000 pixels lit; it exits non-zero otherwise). Without `mpirun`
//! the test skips loudly, unless `TETRAY_REQUIRE_MPI=1`.
#![cfg(feature = "mpi")]

use std::path::PathBuf;
use std::process::Command;

fn mpirun() -> Option<PathBuf> {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join("mpirun"))
            .find(|p| p.is_file())
    });
    if found.is_none() {
        assert!(
            std::env::var("TETRAY_REQUIRE_MPI").as_deref() != Ok("1"),
            "TETRAY_REQUIRE_MPI=1 but no mpirun on PATH"
        );
        eprintln!(
            "SKIPPED: no mpirun on PATH (install openmpi-bin; TETRAY_REQUIRE_MPI=1 makes this a failure)"
        );
    }
    found
}

#[test]
fn in_situ_arrays_and_cells_match_one_process_on_1_to_4_ranks() {
    let Some(mpirun) = mpirun() else { return };
    let example = env!("CARGO_BIN_EXE_in_situ");
    for (ranks, mode) in (1..=4).flat_map(|r| [(r, "tets"), (r, "cells")]) {
        let out = Command::new(&mpirun)
            .args([
                "-n",
                &ranks.to_string(),
                "--oversubscribe",
                "--bind-to",
                "none",
            ])
            .arg(example)
            .args((mode == "cells").then_some("cells"))
            .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
            .env("RAYON_NUM_THREADS", "1")
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success(),
            "{ranks} ranks failed:\n{stdout}\n{stderr}"
        );
        assert!(
            stdout.contains(&format!("over {ranks} ranks: max error")),
            "{stdout}"
        );
        println!("{stdout}");
    }
}
