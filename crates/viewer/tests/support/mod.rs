//! Shared helpers of the viewer tests: the embedded dataset, the adapter
//! check (required in CI), a harness on the viewer's own device setup, and
//! running it until the frame is finished.

#![allow(dead_code)]

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use tetray_engine::{FrameOptions, Log, Representation, Setup, Source};
use tetray_viewer::{ViewerApp, ViewerOptions};

/// The setup of `source` as `tetray view` makes it (the regular grid of
/// image data too).
pub fn setup(source: Source) -> Setup {
    let options = FrameOptions {
        size: (64, 64),
        representation: Representation::Both,
        ..FrameOptions::default()
    };
    tetray_engine::prepare(source, &options, Log::quiet()).expect("the setup")
}

/// The default dataset, as `tetray view` loads it with no mesh.
pub fn blunt_fin() -> Setup {
    setup(Source::Embedded)
}

/// Whether a GPU adapter exists for the viewer's setup. Without one the
/// test says so loudly and returns, unless `TETRAY_REQUIRE_GPU=1` (CI),
/// where that is a failure.
pub fn gpu_or_skip() -> bool {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    if std::env::var_os("WGPU_BACKEND").is_none() {
        descriptor.backends = wgpu::Backends::PRIMARY;
    }
    let instance = wgpu::Instance::new(descriptor);
    match pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default())) {
        Ok(adapter) => {
            eprintln!("viewer tests on {}", adapter.get_info().name);
            true
        }
        Err(e) => {
            if std::env::var("TETRAY_REQUIRE_GPU").as_deref() == Ok("1") {
                panic!("TETRAY_REQUIRE_GPU=1 but no adapter: {e}");
            }
            eprintln!("\n!!! SKIPPING VIEWER TEST: no adapter ({e}) !!!\n");
            false
        }
    }
}

/// Window size of the tests (points): the image area is about 390 x 420.
pub const WINDOW: [f32; 2] = [720.0, 420.0];

/// Test options: a small image (0.2 of the display) and a budget no frame
/// exceeds, so the finished frame does not depend on the machine's speed.
pub fn options() -> ViewerOptions {
    ViewerOptions {
        image_scale: Some(0.2),
        budget: Duration::from_secs(30),
        ..ViewerOptions::default()
    }
}

/// The viewer on the default dataset in a harness drawing with wgpu.
pub fn harness(options: ViewerOptions) -> Harness<'static, ViewerApp> {
    harness_on(blunt_fin(), options)
}

/// The viewer on `setup` in a harness drawing with wgpu.
pub fn harness_on(setup: Setup, options: ViewerOptions) -> Harness<'static, ViewerApp> {
    Harness::builder()
        .with_size(egui::Vec2::from(WINDOW))
        .wgpu_setup(tetray_viewer::wgpu_setup())
        .build_eframe(move |cc| ViewerApp::new(cc, setup, options).expect("the viewer starts"))
}

/// Steps the harness until the frame is finished (a minute at most).
pub fn run_until_idle(harness: &mut Harness<'_, ViewerApp>) {
    let start = Instant::now();
    harness.step();
    while !harness.state().is_idle() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the frame did not finish in a minute"
        );
        if let Some(error) = &harness.state().error {
            panic!("the viewer shows an error: {error}");
        }
        harness.step();
    }
    // One more pass so the UI shows the finished frame's state.
    harness.step();
}

/// The displayed image as an `image` crate buffer.
pub fn displayed(harness: &Harness<'_, ViewerApp>) -> image::RgbaImage {
    let (w, h, pixels) = harness.state().displayed_image().expect("read the display");
    image::RgbaImage::from_raw(w, h, pixels.into_iter().flatten().collect()).expect("image")
}

/// Largest channel difference and the number of pixels differing by more
/// than `threshold` (8-bit units).
pub fn difference(a: &image::RgbaImage, b: &image::RgbaImage, threshold: u8) -> (u8, usize) {
    assert_eq!(a.dimensions(), b.dimensions());
    let mut worst = 0;
    let mut over = 0;
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        worst = worst.max(d);
        over += usize::from(d > threshold);
    }
    (worst, over)
}
