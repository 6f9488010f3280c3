//! The GPU ray caster from the command line: `info --gpu`, `render
//! --renderer gpu` against `--renderer cpu` on the same view, `bench
//! --renderer gpu`. They need an adapter: without one they skip loudly,
//! unless `TETRAY_REQUIRE_GPU=1` (CI, with lavapipe), where that fails.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_tetray");

fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("cli-gpu")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the scratch folder");
    dir
}

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run tetray")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Whether an adapter exists; panics when one is required and missing.
fn have_gpu() -> bool {
    let out = Command::new(BIN)
        .args(["info", "--gpu", "--json"])
        .output()
        .expect("run");
    if out.status.success() {
        return true;
    }
    let why = text(&out.stderr);
    if std::env::var("TETRAY_REQUIRE_GPU").as_deref() == Ok("1") {
        panic!("TETRAY_REQUIRE_GPU=1 but `tetray info --gpu` failed: {why}");
    }
    eprintln!("\n!!! SKIPPING GPU CLI TEST: {why} !!!\n");
    false
}

#[test]
fn info_describes_the_adapter() {
    if !have_gpu() {
        return;
    }
    let out = run(Path::new("."), &["info", "--gpu", "--json"]);
    let json: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let adapter = &json["adapter"];
    assert!(!adapter["name"].as_str().unwrap_or("").is_empty(), "{json}");
    assert!(
        adapter["max_storage_buffer_binding_size"]
            .as_u64()
            .unwrap_or(0)
            >= 1 << 20
    );
}

#[test]
fn gpu_render_matches_the_cpu_render() {
    if !have_gpu() {
        return;
    }
    let dir = scratch("render");
    let common = [
        "render",
        "--size",
        "64x48",
        "--azimuth",
        "30",
        "--elevation",
        "20",
    ];
    for renderer in ["gpu", "cpu"] {
        let mut args = common.to_vec();
        let file = format!("{renderer}.exr");
        args.extend(["--renderer", renderer, "-o", &file]);
        let out = run(&dir, &args);
        assert!(out.status.success(), "{renderer}: {}", text(&out.stderr));
        let stdout = text(&out.stdout);
        assert!(
            stdout.contains(&format!("renderer: {renderer}")) || renderer == "cpu",
            "{stdout}"
        );
    }
    let read = |name: &str| {
        image::open(dir.join(name))
            .expect("read EXR")
            .into_rgba32f()
            .into_raw()
    };
    let (gpu, cpu) = (read("gpu.exr"), read("cpu.exr"));
    assert_eq!(gpu.len(), 64 * 48 * 4);
    // f32 GPU walk vs the reference's f64 crossings: 3e-5 (see the
    // tetray-gpu tests for the budget), and both see the fin.
    let worst = gpu
        .iter()
        .zip(&cpu)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    assert!(worst < 3e-5, "max difference {worst}");
    assert!(gpu.chunks(4).any(|p| p[3] > 0.05));
}

#[test]
fn gpu_bench_reports_the_adapter_and_rates() {
    if !have_gpu() {
        return;
    }
    let out = run(
        Path::new("."),
        &[
            "bench",
            "--renderer",
            "gpu",
            "--frames",
            "2",
            "--size",
            "48x48",
            "--orbit-step",
            "0",
        ],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(json["renderer"], "gpu");
    assert!(
        json["segments_per_s"].as_f64().unwrap_or(0.0) > 0.0,
        "{json}"
    );
    assert_eq!(json["steps_bound_hits"], 0);
}

#[test]
fn reference_methods_refuse_the_gpu() {
    let out = run(
        Path::new("."),
        &[
            "render",
            "--renderer",
            "gpu",
            "--integrator",
            "reference",
            "--size",
            "8x8",
            "-o",
            "x.png",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains("no GPU kernel"),
        "{}",
        text(&out.stderr)
    );
}
