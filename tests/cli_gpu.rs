//! The GPU ray caster from the command line: `info --gpu`, `render
//! --renderer gpu` against `--renderer cpu` on the same view, `bench
//! --renderer gpu`. They need an adapter: without one they skip loudly,
//! unless `TETRAY_REQUIRE_GPU=1` (CI, with lavapipe), where that fails.

use std::path::Path;

use serde_json::Value;

mod support;
use support::{grid_vtk, have_gpu, run, text};

fn scratch(test: &str) -> std::path::PathBuf {
    support::scratch("cli-gpu", test)
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

/// `--renderer project --sort mpvo` on a convex mesh matches the GPU ray
/// caster: the same segments integrated by the same WGSL, in an order that
/// is exact for convex connected meshes. Budget 1e-4 per channel (4e-3 when
/// the adapter blends only rgba16float, 11-bit mantissas per draw), 1% of
/// pixels beyond it: pixel centres within the rasterizer's fixed-point
/// snapping of a silhouette edge (see crates/project/tests/gpu.rs).
#[test]
fn projection_matches_the_ray_caster_on_a_convex_mesh() {
    if !have_gpu() {
        return;
    }
    let dir = scratch("project");
    std::fs::write(dir.join("grid.vtk"), grid_vtk()).unwrap();
    let mut half_float = false;
    for (renderer, file) in [("gpu", "gpu.exr"), ("project", "project.exr")] {
        let out = run(
            &dir,
            &[
                "render",
                "grid.vtk",
                "--size",
                "48x40",
                "--azimuth",
                "30",
                "--elevation",
                "20",
                "--integrator",
                "exact",
                "--renderer",
                renderer,
                "--sort",
                "mpvo",
                "-o",
                file,
            ],
        );
        assert!(out.status.success(), "{renderer}: {}", text(&out.stderr));
        let said = format!("{}{}", text(&out.stdout), text(&out.stderr));
        if renderer == "project" {
            assert!(said.contains("mpvo sort"), "{said}");
            half_float = said.contains("Rgba16Float");
        }
    }
    let read = |name: &str| {
        image::open(dir.join(name))
            .expect("read EXR")
            .into_rgba32f()
            .into_raw()
    };
    let (gpu, project) = (read("gpu.exr"), read("project.exr"));
    assert_eq!(gpu.len(), project.len());
    let budget = if half_float { 4e-3 } else { 1e-4 };
    let errors: Vec<f32> = gpu
        .chunks(4)
        .zip(project.chunks(4))
        .map(|(a, b)| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f32::max)
        })
        .collect();
    let beyond = errors.iter().filter(|&&e| e > budget).count();
    let worst = errors.iter().copied().fold(0.0, f32::max);
    eprintln!("projection vs ray caster: {beyond} pixels beyond {budget}, worst {worst:.2e}");
    assert!(
        beyond * 100 <= gpu.len() / 4,
        "{beyond} pixels beyond {budget}"
    );
    assert!(project.chunks(4).filter(|p| p[3] > 0.05).count() > 100);
}

#[test]
fn projection_bench_reports_its_stages() {
    if !have_gpu() {
        return;
    }
    let out = run(
        Path::new("."),
        &[
            "bench",
            "--renderer",
            "project",
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
    assert_eq!(json["renderer"], "project");
    let stages = &json["projection"];
    assert_eq!(stages["sort"], "mpvonc");
    assert!(
        stages["sort_ms_median"].as_f64().unwrap_or(-1.0) >= 0.0,
        "{json}"
    );
    // Adaptive sampling draws at least one piece per cell.
    assert!(
        stages["draws_per_frame"].as_f64().unwrap_or(0.0) >= 187_318.0,
        "{json}"
    );
    assert!(
        json["segments_per_s"].as_f64().unwrap_or(0.0) > 0.0,
        "{json}"
    );
}
