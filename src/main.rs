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
    quiet_broken_pipe();
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

/// `tetray info mesh | head` closes the pipe before the output ends: Rust
/// ignores SIGPIPE, so `println!` panics on the failed write. The reader
/// has what it wanted; end as a process killed by SIGPIPE would (exit code
/// 141), without the panic's message. Other panics print as usual.
fn quiet_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(141);
        }
        default(info);
    }));
}
