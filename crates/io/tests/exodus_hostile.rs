//! Exodus files the `exodus` fuzz target found (kept in `data/fuzz/`):
//! each is an answer (a mesh or one error naming the file), never a panic
//! or an allocation of what the header claims.

use std::path::{Path, PathBuf};

use tetray_io::{LoadOptions, load};

fn finding(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/fuzz")
        .join(name)
}

/// A classic file claiming a huge number of nodal variables overflowed the
/// memory estimate (a panic where overflow is checked). The estimate
/// saturates; the file is an answer, not a panic.
#[test]
fn a_huge_variable_count_is_no_overflow() {
    let result = load(
        &finding("exodus-variable-count-overflow.exo"),
        &LoadOptions::default(),
    );
    if let Err(e) = result {
        assert!(
            e.to_string().contains("exodus-variable-count-overflow.exo"),
            "{e}"
        );
    }
}

/// A 2 kB classic file whose `num_el_blk` claims about 5e13 element
/// blocks: the reader allocated per-block lists of that length (800 TB,
/// refused by the allocator). A block count beyond the file's dimensions
/// (every block defines its own) is now one error.
#[test]
fn a_huge_block_count_is_one_error() {
    let e = load(
        &finding("exodus-huge-block-count.exo"),
        &LoadOptions::default(),
    )
    .expect_err("no such file has that many blocks");
    let text = e.to_string();
    assert!(text.contains("exodus-huge-block-count.exo"), "{text}");
    assert!(text.contains("num_el_blk"), "{text}");
}
