//! The classic-netCDF Exodus seeds of the `exodus` fuzz target
//! (`fuzz/corpus/exodus/classic-*.exo`) are the model the Exodus tests
//! write: this test holds the committed files to it and checks that they
//! load, so the fuzzer starts from files the reader accepts.
//! `UPDATE_FUZZ_SEEDS=1 cargo test -p tetray-io --test fuzz_seeds` writes
//! them anew.

mod exodus_common;

use std::path::Path;

use exodus_common::{Block, ElemVar, Model, Version};
use tetray_io::{LoadOptions, load};

fn model(int64: bool) -> Model {
    let mut coords = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                coords.push([f64::from(i), f64::from(j), f64::from(k)]);
            }
        }
    }
    coords.extend([
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [2.0, 0.0, 1.0],
        [2.0, 1.0, 1.0],
    ]);
    let times = vec![0.0, 1.0];
    let nodal = vec![(
        "T".to_string(),
        (0..2)
            .map(|s| coords.iter().map(|p| p[0] + p[2] + f64::from(s)).collect())
            .collect(),
    )];
    let elem = vec![ElemVar {
        name: "rho".into(),
        per_step: (0..2)
            .map(|s| vec![Some(vec![1.0 + f64::from(s)]), Some(vec![2.0, 3.0])])
            .collect(),
    }];
    Model {
        coords,
        blocks: vec![
            Block::new(1, "hex", "HEX8", 8, &[1, 2, 4, 3, 5, 6, 8, 7]),
            Block::new(
                2,
                "wedges",
                "WEDGE6",
                6,
                &[2, 9, 4, 6, 11, 8, 9, 10, 4, 11, 12, 8],
            ),
        ],
        times,
        nodal,
        elem,
        old_layout: false,
        int64,
    }
}

#[test]
fn classic_exodus_seeds_are_the_test_model_and_load() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus/exodus");
    let update = std::env::var("UPDATE_FUZZ_SEEDS").as_deref() == Ok("1");
    for (name, bytes) in [
        ("classic-cdf1.exo", model(false).write(Version::Cdf1)),
        ("classic-cdf5.exo", model(true).write(Version::Cdf5)),
    ] {
        let path = folder.join(name);
        if update {
            std::fs::write(&path, &bytes).expect("write the corpus file");
        }
        let committed = std::fs::read(&path).expect("the committed file");
        assert!(
            committed == bytes,
            "{name} differs from the model; UPDATE_FUZZ_SEEDS=1 writes it"
        );
        let mesh = load(&path, &LoadOptions::default()).expect("the corpus file loads");
        let tets = mesh.mesh.tets.len();
        assert!(tets >= 5 + 6, "{name}: {tets} tetrahedra");
    }
}
