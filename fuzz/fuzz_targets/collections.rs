//! Collections read from a set of files: .pvtu, .pvts, .pvtr, .pvti, .vtm,
//! .pvd and .series with their pieces (an archive: the first file is the
//! collection, named by its `@@@` line).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some((_scratch, first)) = tetray_fuzz::unpack(data, "input.pvtu") {
        tetray_fuzz::load(&first);
    }
});
