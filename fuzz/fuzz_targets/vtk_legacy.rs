//! Legacy VTK (.vtk): every dataset type, ASCII and binary, through the
//! whole load.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| tetray_fuzz::load_bytes_as("vtk", data));
