//! The viewer's time steps: a step of the same mesh shows exactly what a
//! viewer started on that step shows (the same colour range, camera and
//! transfer function; only the field written over the upload), the steps
//! differ, and playing moves to the next step once a frame is finished.

mod support;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glam::Vec3;
use support::{difference, displayed, gpu_or_skip, harness_on, options, run_until_idle};
use tetray_engine::{FrameOptions, Log, Representation, Setup, TimeSteps};
use tetray_io::vtk::write_legacy;
use tetray_mesh::synthetic::{CellSplit, ScalarSpec, add_field, box_grid};
use tetray_viewer::TimeSeries;

/// Legacy VTK: a unit cube of 6 tetrahedra, f = scale * (x + 2y + 3z).
fn write_step(path: &Path, scale: f32) {
    let mut mesh = box_grid(Vec3::ZERO, Vec3::ONE, [1, 1, 1], CellSplit::Six).expect("the cube");
    let spec = ScalarSpec::Linear {
        offset: 0.0,
        gradient: Vec3::new(1.0, 2.0, 3.0) * scale,
    };
    add_field(&mut mesh, "f", spec);
    let mut file = std::fs::File::create(path).expect("create a step");
    write_legacy(&mesh, &mut file, false).expect("write a step");
}

fn series(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("tetray-viewer-{name}"));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    for k in 0..3 {
        write_step(&dir.join(format!("s{k}.vtk")), (k + 1) as f32);
    }
    let path = dir.join("run.series");
    std::fs::write(
        &path,
        r#"{"file-series-version": "1.0", "files": [{"name": "s0.vtk", "time": 0},
            {"name": "s1.vtk", "time": 0.5}, {"name": "s2.vtk", "time": 1}]}"#,
    )
    .expect("write the series");
    path
}

/// As `tetray view` makes them: the colour range over the three steps.
fn frame_options() -> FrameOptions {
    let mut options = FrameOptions {
        size: (64, 64),
        representation: Representation::Both,
        ..FrameOptions::default()
    };
    options.integrator.range = Some((0.0, 18.0));
    options
}

fn setup_at(path: &Path, step: usize) -> (Setup, TimeSeries) {
    let mut steps = TimeSteps::new(path, Default::default());
    let times = steps.times().expect("times");
    let setup = steps
        .prepare(Some(step), &frame_options(), Log::quiet())
        .expect("the setup");
    (setup, TimeSeries::new(steps, frame_options(), times, step))
}

#[test]
fn a_step_shows_what_a_viewer_started_on_it_shows() {
    if !gpu_or_skip() {
        return;
    }
    let path = series("step");
    let (setup, series) = setup_at(&path, 0);
    let mut harness = harness_on(setup, options());
    harness.state_mut().set_time_series(series);
    run_until_idle(&mut harness);
    let first = displayed(&harness);
    harness.state_mut().go_to_step(2).expect("step 2");
    assert_eq!(harness.state().time_step(), Some(2));
    run_until_idle(&mut harness);
    let moved = displayed(&harness);

    let (setup, series) = setup_at(&path, 2);
    let mut fresh = harness_on(setup, options());
    fresh.state_mut().set_time_series(series);
    run_until_idle(&mut fresh);
    // The same device, kernel and inputs: bit for bit.
    assert_eq!(difference(&moved, &displayed(&fresh), 0), (0, 0));
    let (worst, _) = difference(&first, &moved, 0);
    assert!(worst > 8, "the steps look alike: {worst}");
    assert!(harness.state_mut().go_to_step(3).is_err());
}

#[test]
fn playing_moves_to_the_next_step_once_the_frame_is_finished() {
    if !gpu_or_skip() {
        return;
    }
    let (setup, series) = setup_at(&series("play"), 0);
    let mut harness = harness_on(setup, options());
    harness.state_mut().set_time_series(series);
    run_until_idle(&mut harness);
    harness.state_mut().set_playing(true);
    let start = Instant::now();
    while harness.state().time_step() == Some(0) {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no step in a minute"
        );
        harness.step();
    }
    assert_eq!(harness.state().time_step(), Some(1));
    assert_eq!(harness.state().error, None);
}

/// Recording the time steps writes one frame per step with `tetray
/// animate`'s writer: each frame is the engine's GPU render of that step
/// from the viewer's camera at the view's size, written by the same
/// writer; the viewer is back on its step afterwards. An orbit records
/// the frames asked for.
#[test]
fn recording_writes_each_step_as_the_engine_renders_it() {
    if !gpu_or_skip() {
        return;
    }
    let path = series("record");
    let (setup, series) = setup_at(&path, 1);
    let mut harness = harness_on(setup, options());
    harness.state_mut().set_time_series(series);
    run_until_idle(&mut harness);
    let dir = path.with_file_name("recorded/");
    let app = harness.state_mut();
    let frames = app
        .record(&dir, tetray_viewer::Recording::TimeSteps, 10)
        .expect("record the steps");
    assert_eq!(frames, 3);
    assert_eq!(app.time_step(), Some(1));
    let camera = app.camera().expect("camera");
    let (w, h, _) = app.displayed_image().expect("display");
    let reference = path.with_file_name("reference/");
    let mut movie =
        tetray_core::Movie::create(&reference, (w, h), 10, glam::Vec3::ZERO).expect("writer");
    for step in 0..3 {
        let (setup, _) = setup_at(&path, step);
        let engine =
            tetray_engine::Engine::new(tetray_engine::RendererChoice::Gpu, &setup, &|_| {})
                .expect("engine");
        let frame = engine
            .render(
                &setup,
                &camera,
                tetray_engine::WalkOptions::default(),
                (w, h),
                None,
            )
            .expect("render");
        movie.add(&frame.image).expect("add");
    }
    movie.finish().expect("finish");
    for step in 0..3 {
        let name = format!("frame_{step:04}.png");
        let a = image::open(dir.join(&name)).expect("recorded").to_rgba8();
        let b = image::open(reference.join(&name))
            .expect("reference")
            .to_rgba8();
        assert_eq!(difference(&a, &b, 0), (0, 0), "step {step}");
    }
    let orbit = path.with_file_name("orbit.gif");
    let recording = tetray_viewer::Recording::Orbit {
        degrees: 90.0,
        frames: 4,
    };
    assert_eq!(
        harness
            .state_mut()
            .record(&orbit, recording, 10)
            .expect("orbit"),
        4
    );
    assert!(std::fs::metadata(&orbit).expect("the GIF").len() > 0);
}
