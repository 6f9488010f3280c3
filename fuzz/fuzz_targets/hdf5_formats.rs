//! The HDF5 formats: VTKHDF and CGNS over HDF5 (the first byte picks),
//! through the one HDF5 reader they share.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let ext = if pick % 2 == 0 { "vtkhdf" } else { "cgns" };
    tetray_fuzz::load_bytes_as(ext, rest);
});
