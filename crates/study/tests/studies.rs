//! Every study at a small size: the files exist, parse as what they claim,
//! and the numbers say what the dissertation says (and what the integrate
//! crate's own tests pin down). GPU halves run on whatever adapter exists;
//! with `TETRAY_REQUIRE_GPU=1` a missing adapter is a failure.

use std::path::{Path, PathBuf};

use tetray_study::accuracy::{self, AccuracyOptions, Device};
use tetray_study::psi_study::{self, Lookup, PsiOptions};
use tetray_study::{OutputDir, failed};

fn out_dir(name: &str) -> OutputDir {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("study")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    OutputDir::create(&dir).expect("output folder")
}

fn quiet(_: &str) {}

/// Each expected file exists; SVGs are whole documents with a title, CSVs
/// have a header and rows, JSON parses.
fn assert_files(out: &OutputDir, names: &[&str]) {
    for name in names {
        let path = out.path().join(name);
        assert!(out.files().contains(&path), "{name} not reported");
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        match Path::new(name).extension().and_then(|e| e.to_str()) {
            Some("svg") => {
                assert!(
                    text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
                    "{name}"
                );
                assert!(
                    text.matches("<text").count() >= 4,
                    "{name}: titles and labels"
                );
            }
            Some("csv") => assert!(text.lines().count() >= 2, "{name}: no rows"),
            Some("json") => {
                serde_json::from_str::<serde_json::Value>(&text)
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
            }
            _ => {}
        }
    }
}

fn gpu_required() -> bool {
    std::env::var("TETRAY_REQUIRE_GPU").as_deref() == Ok("1")
}

#[test]
fn psi_study_small() {
    let mut out = out_dir("psi");
    let options = PsiOptions {
        table_sizes: vec![16, 64],
        grid: 48,
        cells: 100,
    };
    let summary = psi_study::run(&options, &mut out, &quiet).unwrap();
    assert_files(
        &out,
        &[
            "psi_surface.svg",
            "psi_error_uniform_nearest.svg",
            "psi_error_uniform_bilinear.svg",
            "psi_error_quadratic_nearest.svg",
            "psi_error_quadratic_bilinear.svg",
            "psi_cumulative.svg",
            "psi_error_by_size.svg",
            "psi_errors.csv",
            "psi_grid.csv",
            "psi.json",
        ],
    );
    assert_eq!(summary.tables.len(), 8);
    assert!(
        failed(&summary.checks).is_empty(),
        "{:?}",
        failed(&summary.checks)
    );
    for t in &summary.tables {
        // Sane magnitudes: a table error is a fraction of Psi's range.
        assert!(t.max_error > 0.0 && t.max_error < 0.5, "{t:?}");
        assert!(t.mean_error <= t.max_error);
        // Through 100 cells at most 100 times one cell's error.
        assert!(t.max_cumulative >= t.max_error && t.max_cumulative <= 100.0 * t.max_error);
    }
    let get = |spacing: &str, lookup, size| {
        summary
            .tables
            .iter()
            .find(|t| t.spacing == spacing && t.lookup == lookup && t.size == size)
            .unwrap()
            .max_error
    };
    // Nearest lookup errs by about half a cell of slope; bilinear by a
    // fraction of that which shrinks faster with size.
    for spacing in ["uniform", "quadratic"] {
        assert!(get(spacing, Lookup::Nearest, 64) < get(spacing, Lookup::Nearest, 16));
        assert!(get(spacing, Lookup::Bilinear, 64) < get(spacing, Lookup::Bilinear, 16));
    }
    assert!(get("quadratic", Lookup::Bilinear, 64) < 0.1 * get("quadratic", Lookup::Nearest, 64));
}

#[test]
fn accuracy_study_small() {
    let mut out = out_dir("accuracy");
    let options = AccuracyOptions {
        steps: 9,
        lengths: vec![0.001, 1.0, 100.0],
        gpu: true,
    };
    let summary = accuracy::run(&options, &mut out, &quiet).unwrap();
    if gpu_required() {
        assert!(
            summary.gpu_adapter.is_some(),
            "TETRAY_REQUIRE_GPU=1: {:?}",
            summary.gpu_note
        );
    }
    let mut names = vec![
        "accuracy_by_length.svg".to_string(),
        "accuracy_points.csv".into(),
        "accuracy_summary.csv".into(),
        "accuracy.json".into(),
    ];
    let devices: &[&str] = if summary.gpu_adapter.is_some() {
        &["cpu", "gpu"]
    } else {
        &["cpu"]
    };
    for model in ["attenuation", "opacity"] {
        for d in ["0.001", "1", "100"] {
            for device in devices {
                names.push(format!("accuracy_{model}_d{d}_{device}.svg"));
            }
        }
    }
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    assert_files(&out, &names);
    assert!(
        failed(&summary.checks).is_empty(),
        "{:?}",
        failed(&summary.checks)
    );
    let get = |device: Device, method: &str, d: f64| {
        summary
            .sweeps
            .iter()
            .find(|s| s.device == device && s.method == method && s.length == d)
            .map(|s| s.max_error)
    };
    for d in [0.001, 1.0, 100.0] {
        let ppi = get(Device::Cpu, "ppi", d).unwrap();
        let average = get(Device::Cpu, "average", d).unwrap();
        eprintln!(
            "D = {d}: cpu ppi {ppi:.2e}, gpu ppi {:?}, gpu exact {:?}",
            get(Device::Gpu, "ppi", d),
            get(Device::Gpu, "exact", d)
        );
        // PPI: the 1024^2 Psi table's bilinear lookup in f32. Measured
        // 2.4e-7 to 3.8e-7 (CPU and lavapipe alike); 2e-6 leaves 5x for
        // other devices' exp / log and table filtering.
        assert!(
            ppi < 2e-6 && ppi < average,
            "D = {d}: ppi {ppi} average {average}"
        );
        if let Some(gpu_ppi) = get(Device::Gpu, "ppi", d) {
            // f32 in the kernel: eq. 5.5 and the bilinear lookup, as on the CPU.
            assert!(gpu_ppi < 2e-6, "D = {d}: gpu ppi {gpu_ppi}");
            let gpu_exact = get(Device::Gpu, "exact", d).unwrap();
            // The kernel's f32 erfcx / Dawson forms (2e-7 to 4e-7 relative):
            // measured 6.5e-8 to 6.1e-7 on lavapipe, 1.8e-6 reported on
            // an earlier build; 3e-6 is that with a margin of 1.7x.
            assert!(gpu_exact < 3e-6, "D = {d}: gpu exact {gpu_exact}");
        }
    }
    // Averaging's error grows with D towards one half (figs. 6.5-6.8).
    let avg: Vec<f64> = [0.001, 1.0, 100.0]
        .iter()
        .map(|&d| get(Device::Cpu, "average", d).unwrap())
        .collect();
    assert!(
        avg[0] < avg[1] && avg[1] < avg[2] && avg[2] > 0.3 && avg[2] < 0.5,
        "{avg:?}"
    );
}

#[test]
fn smoothness_study_small() {
    use tetray_study::smoothness::{self, SmoothnessOptions};
    let mut out = out_dir("smoothness");
    let options = SmoothnessOptions {
        pixels: 120,
        cells: 2,
        centre_sigma_px: 1.5,
        gpu: true,
    };
    let summary = smoothness::run(&options, &mut out, &quiet).unwrap();
    if gpu_required() {
        assert!(
            summary.gpu_adapter.is_some(),
            "TETRAY_REQUIRE_GPU=1: {:?}",
            summary.gpu_note
        );
    }
    let mut names: Vec<String> = ["attenuation", "opacity"]
        .iter()
        .flat_map(|m| ["constant", "back", "front"].map(|c| format!("smoothness_{m}_{c}.svg")))
        .collect();
    names.extend(["smoothness_profiles.csv".into(), "smoothness.json".into()]);
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    assert_files(&out, &names);
    assert_eq!(summary.profiles.len(), 6 * 3 * 3);
    for check in &summary.checks {
        eprintln!("{}: {}", check.name, check.detail);
    }
    assert!(
        failed(&summary.checks).is_empty(),
        "{:?}",
        failed(&summary.checks)
    );
    // The slab is 2 cells of 5 tetrahedra.
    assert_eq!(summary.tetrahedra, 10);
    for p in &summary.profiles {
        // Every method's mean is within the averaging error of the truth.
        assert!((p.mean - p.reference).abs() < 0.3, "{p:?}");
        assert!(p.range >= 0.0 && p.response >= 0.0);
    }
    // Averaging luminance varies visibly across the face (Mach bands).
    let average_range = summary
        .profiles
        .iter()
        .filter(|p| p.method == "average")
        .map(|p| p.range)
        .fold(0.0, f64::max);
    assert!(average_range > 1e-2, "{average_range}");
}

#[test]
fn centre_surround_kernel_ignores_constant_fields() {
    use tetray_study::smoothness::{centre_surround, convolve};
    let kernel = centre_surround(2.0);
    assert!(kernel.iter().sum::<f64>().abs() < 1e-12);
    let flat = convolve(&[0.7; 50], &kernel);
    assert!(flat.iter().all(|r| r.abs() < 1e-12));
    // A kink gives a response at the kink and none (a symmetric kernel of
    // zero sum cancels a linear ramp) more than a kernel radius from the
    // kink and from the ends, where the extended profile bends too.
    let radius = kernel.len() / 2;
    let kink: Vec<f64> = (0..200)
        .map(|i| {
            if i < 100 {
                0.0
            } else {
                0.01 * (i - 100) as f64
            }
        })
        .collect();
    let r = convolve(&kink, &kernel);
    let (left, right) = (100 - radius - 5, 100 + radius + 5);
    assert!(right + radius < kink.len() - 1, "{radius}");
    assert!(
        r[100].abs() > 1e-3 && r[left].abs() < 1e-9 && r[right].abs() < 1e-9,
        "{} {} {}",
        r[100],
        r[left],
        r[right]
    );
}

#[test]
fn speed_study_small() {
    use tetray_integrate::Method;
    use tetray_study::speed::{self, SpeedOptions};
    let data_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let mut out = out_dir("speed");
    let options = SpeedOptions {
        size: (32, 32),
        frames: 1,
        methods: vec![Method::Ppi, Method::Average, Method::LinOpacity],
        resolutions: vec![16, 128],
        scaling_tets: vec![5_000, 40_000],
        ..SpeedOptions::small(data_dir)
    };
    let start = std::time::Instant::now();
    let log = |line: &str| eprintln!("{:.1} s {line}", start.elapsed().as_secs_f64());
    let summary = speed::run(&options, &mut out, &log).unwrap();
    if gpu_required() {
        assert!(
            summary.gpu_adapter.is_some(),
            "TETRAY_REQUIRE_GPU=1: {:?}",
            summary.notes
        );
    }
    assert_files(
        &out,
        &[
            "speed_table.csv",
            "speed_table.svg",
            "speed_table.md",
            "speed_resolution.csv",
            "speed_resolution.svg",
            "speed_scaling.csv",
            "speed_scaling.svg",
            "speed.json",
        ],
    );
    assert!(
        failed(&summary.checks).is_empty(),
        "{:?}",
        failed(&summary.checks)
    );
    // CPU ray caster, and with an adapter the GPU ray caster and the cell
    // projection.
    let renderers = if summary.gpu_adapter.is_some() { 3 } else { 1 };
    assert_eq!(summary.table.len(), 3 * 3 * renderers);
    assert_eq!(summary.resolution.len(), 2 * renderers);
    assert_eq!(summary.scaling.len(), 2 * renderers);
    assert!(summary.notes.iter().any(|n| n.contains("tetray-project")));
    if summary.gpu_adapter.is_some() {
        // The projection integrates segments of the same mesh.
        assert!(
            summary
                .table
                .iter()
                .filter(|r| r.renderer == "projection")
                .all(|r| r.segments_per_frame > 0.0)
        );
    }
    // The datasets as the dissertation counts them (table 6.1, our split).
    let tets = |name: &str| summary.table.iter().find(|r| r.mesh == name).unwrap().tets;
    assert_eq!(tets("Blunt Fin"), 187_318);
    assert_eq!(tets("Oxygen Post"), 513_375);
    // The boxes: 10^3 and 20^3 hexahedra of 5 tetrahedra.
    assert_eq!(
        summary.generated.iter().map(|g| g.tets).collect::<Vec<_>>(),
        [5_000, 40_000]
    );
    for r in summary
        .table
        .iter()
        .chain(&summary.resolution)
        .chain(&summary.scaling)
    {
        assert!(r.fps.is_finite() && r.fps > 0.0, "{r:?}");
        assert!((r.tets_per_s - r.tets as f64 * r.fps).abs() <= 1e-6 * r.tets_per_s);
    }
}
