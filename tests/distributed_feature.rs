//! The distributed tests (`tests/distributed.rs`) need the `mpi` feature;
//! built without it they cannot run: say so loudly, and fail when
//! `TETRAY_REQUIRE_MPI=1` (as `tools/test-mpi` and CI set it).

#[cfg(not(feature = "mpi"))]
#[test]
fn distributed_tests_need_the_mpi_feature() {
    assert!(
        std::env::var("TETRAY_REQUIRE_MPI").as_deref() != Ok("1"),
        "TETRAY_REQUIRE_MPI=1 but tetray was built without the `mpi` feature \
         (cargo test -p tetray --features mpi --test distributed)"
    );
    eprintln!(
        "SKIPPED: the distributed tests need `--features mpi` (and an MPI with libclang); \
         run tools/test-mpi"
    );
}
