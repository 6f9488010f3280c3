//! Formats that are folders of files: an OpenFOAM case (first file
//! `system/controlDict`) or an EnSight Gold case (first file `run.case`),
//! as an archive whose first `@@@` line names the entry file.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some((_scratch, first)) = tetray_fuzz::unpack(data, "system/controlDict") {
        tetray_fuzz::load(&first);
    }
});
