//! PLOT3D: a grid file and, after an `@@@ q` line, its solution.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let files = tetray_fuzz::split_archive(data, "xyz");
    let xyz = files[0].1;
    let q = files.get(1).map(|f| f.1);
    let _ = tetray_io::load_plot3d_bytes(xyz, q, "fuzz");
});
