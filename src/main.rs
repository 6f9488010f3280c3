//! `tetray`: volume rendering of unstructured tetrahedral meshes.
//!
//! With no arguments it renders the embedded Blunt Fin dataset to
//! `tetray.png`; `tetray --help` lists the commands. Every error is one
//! line on stderr and exit code 1.

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    quiet_device_select();
    let args = match cli::Cli::try_parse() {
        Ok(args) => args,
        // --help and --version.
        Err(e) if e.exit_code() == 0 => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("{} (see --help)", cli::one_line(&e));
            return ExitCode::FAILURE;
        }
    };
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            // The whole context chain on one line.
            let message = format!("{err:#}");
            eprintln!(
                "error: {}",
                message.split_whitespace().collect::<Vec<_>>().join(" ")
            );
            ExitCode::FAILURE
        }
    }
}

/// Turns off Mesa's Vulkan device-selection layer where it could only
/// print errors (no Wayland display; see
/// `tetray_gpu::device_select_would_be_noisy`): its switch is an
/// environment variable the Vulkan loader reads, so it is set here, first
/// thing, while this is the process's only thread.
#[allow(unsafe_code)]
fn quiet_device_select() {
    if tetray_gpu::device_select_would_be_noisy() {
        // SAFETY: no other thread exists yet (nothing has run but this
        // function), so nothing can read the environment while it changes.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}
