//! VTK XML, inline, appended and compressed data: the first byte picks
//! .vtu, .vts, .vtr or .vti.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let ext = ["vtu", "vts", "vtr", "vti"][usize::from(pick) % 4];
    tetray_fuzz::load_bytes_as(ext, rest);
});
