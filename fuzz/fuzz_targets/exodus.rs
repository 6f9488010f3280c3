//! Exodus II, classic netCDF (CDF-1, 2, 5) and netCDF-4 (HDF5).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| tetray_fuzz::load_bytes_as("exo", data));
