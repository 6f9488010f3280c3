//! Display-frame times of the viewer at the default window size, headless:
//! egui_kittest drives the real app on the viewer's wgpu setup and draws
//! every frame with egui-wgpu (read back, as a screenshot would be: a
//! little more than a window's present). Startup until the first finished
//! frame, an orbit of 30 display frames (previews), then refinement until
//! the frame is done. Prints JSON.
//!
//! `cargo run --release -p tetray-viewer --example frame_times [BUDGET_MS]`
//! (the ray-casting budget per display frame; default: the viewer's).

use std::time::{Duration, Instant};

use egui::{Event, Modifiers, PointerButton, Pos2};
use egui_kittest::Harness;
use tetray_engine::{FrameOptions, Log, Representation, Source};
use tetray_viewer::{ViewerApp, ViewerOptions, WINDOW_SIZE};

const ORBIT_FRAMES: usize = 30;

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Median and largest of some frame times, in ms.
fn summary(times: &[Duration]) -> (f64, f64) {
    let mut sorted: Vec<f64> = times.iter().copied().map(ms).collect();
    sorted.sort_by(f64::total_cmp);
    let median = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    (median, sorted.last().copied().unwrap_or(0.0))
}

/// Steps until the frame is finished; the time of each step.
fn until_idle(harness: &mut Harness<'_, ViewerApp>) -> Vec<Duration> {
    let mut times = Vec::new();
    loop {
        let start = Instant::now();
        harness.step();
        times.push(start.elapsed());
        if harness.state().is_idle() || times.len() > 10_000 {
            return times;
        }
    }
}

fn main() -> anyhow::Result<()> {
    let options = FrameOptions {
        size: (64, 64),
        representation: Representation::Both,
        ..FrameOptions::default()
    };
    let setup = tetray_engine::prepare(Source::Embedded, &options, Log::quiet())?;
    let mut options = ViewerOptions::default();
    if let Some(ms) = std::env::args().nth(1) {
        options.budget = Duration::from_millis(ms.parse()?);
    }
    let start = Instant::now();
    let mut harness = Harness::builder()
        .with_size(egui::Vec2::from(WINDOW_SIZE))
        .with_render_every_step(true)
        .wgpu_setup(tetray_viewer::wgpu_setup())
        .build_eframe(|cc| ViewerApp::new(cc, setup, options).expect("viewer"));
    let startup_frames = until_idle(&mut harness);
    let startup = start.elapsed();
    let first = harness.state().frame_report();

    // Idle display frames: the UI and the display pass with no ray casting
    // (what a display frame costs whatever the renderer does).
    let idle: Vec<Duration> = (0..10)
        .map(|_| {
            let t = Instant::now();
            harness.step();
            t.elapsed()
        })
        .collect();

    // Orbit: press in the image, move 8 points per display frame.
    let centre = Pos2::new(800.0, 400.0);
    harness.event(Event::PointerMoved(centre));
    harness.event(Event::PointerButton {
        pos: centre,
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    let mut orbit = Vec::new();
    for k in 1..=ORBIT_FRAMES {
        harness.event(Event::PointerMoved(
            centre + egui::vec2(8.0 * k as f32, 0.0),
        ));
        let t = Instant::now();
        harness.step();
        orbit.push(t.elapsed());
    }
    let preview = harness.state().preview_size();
    let end = centre + egui::vec2(8.0 * ORBIT_FRAMES as f32, 0.0);
    harness.event(Event::PointerButton {
        pos: end,
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    let refine_start = Instant::now();
    let refine = until_idle(&mut harness);
    let refine_total = refine_start.elapsed();
    let report = harness.state().frame_report();
    let (orbit_median, orbit_max) = summary(&orbit);
    let (refine_median, refine_max) = summary(&refine);
    let (startup_median, _) = summary(&startup_frames);
    let (idle_median, _) = summary(&idle);
    let frame = report.or(first);
    println!("{{");
    println!("  \"adapter\": {:?},", harness.state().adapter_name());
    println!(
        "  \"window_points\": [{}, {}],",
        WINDOW_SIZE[0], WINDOW_SIZE[1]
    );
    if let Some(r) = frame {
        let s = r.elapsed.as_secs_f64().max(1e-9);
        println!("  \"image\": [{}, {}],", r.size.0, r.size.1);
        println!("  \"full_frame_ms\": {:.1},", s * 1e3);
        println!("  \"full_frame_batches\": {},", r.batches);
        println!("  \"rays_per_s\": {:.0},", r.rays() as f64 / s);
        println!("  \"segments_per_s\": {:.0},", r.segments() as f64 / s);
    }
    if let Some((w, h)) = preview {
        println!("  \"orbit_preview\": [{w}, {h}],");
    }
    println!("  \"startup_s\": {:.2},", startup.as_secs_f64());
    println!("  \"startup_display_frames\": {},", startup_frames.len());
    println!("  \"startup_median_ms_per_display_frame\": {startup_median:.1},");
    println!("  \"idle_median_ms_per_display_frame\": {idle_median:.1},");
    println!("  \"orbit_median_ms_per_display_frame\": {orbit_median:.1},");
    println!("  \"orbit_max_ms_per_display_frame\": {orbit_max:.1},");
    println!("  \"refine_display_frames\": {},", refine.len());
    println!("  \"refine_median_ms_per_display_frame\": {refine_median:.1},");
    println!("  \"refine_max_ms_per_display_frame\": {refine_max:.1},");
    println!("  \"refine_total_s\": {:.2}", refine_total.as_secs_f64());
    println!("}}");
    Ok(())
}
