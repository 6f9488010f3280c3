//! CGNS in the ADF storage: the node tree, chunk tables and links.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| tetray_fuzz::load_bytes_as("cgns", data));
