//! The CPU renderers for still frames, the reference ray caster and
//! shear-warp: each renders on a thread of its own (rayon inside), one
//! frame at a time, so the window stays live; a request made while one
//! runs waits for it and replaces any request still waiting.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, channel};
use std::thread::JoinHandle;
use std::time::Duration;

use tetray_core::Image;
use tetray_core::WalkCounters;
use tetray_integrate::ScalarIntegrator;
use tetray_raycast::{RenderOptions, render_scalar_with_progress};
use tetray_scene::Scene;
use tetray_shearwarp::{Classification, ShearWarp, ShearWarpOptions};

use crate::engine::{FrameKey, FrameReport};

/// A still frame to render: one image per view.
#[derive(Clone)]
pub struct CpuJob {
    pub key: FrameKey,
    pub work: CpuWork,
}

/// The renderer of a still frame and what it renders.
#[derive(Clone)]
pub enum CpuWork {
    /// The reference ray caster, one integrator per view.
    Raycast {
        scene: Arc<Scene>,
        integrators: Vec<Arc<ScalarIntegrator>>,
    },
    /// Shear-warp, the grid classified for each view's method.
    ShearWarp(Vec<Arc<ShearWarp>>),
}

impl CpuWork {
    fn views(&self) -> usize {
        match self {
            CpuWork::Raycast { integrators, .. } => integrators.len(),
            CpuWork::ShearWarp(renderers) => renderers.len(),
        }
    }
}

/// What came back.
pub struct CpuFrame {
    pub key: FrameKey,
    pub images: Vec<Image>,
    pub report: FrameReport,
}

struct Running {
    key: FrameKey,
    handle: JoinHandle<()>,
    result: Receiver<anyhow::Result<CpuFrame>>,
    rows_done: Arc<AtomicUsize>,
    rows: usize,
}

/// At most one render running, at most one waiting.
#[derive(Default)]
pub struct CpuWorker {
    running: Option<Running>,
    waiting: Option<CpuJob>,
}

impl CpuWorker {
    /// Asks for `job`'s frame unless it is the one running or waiting.
    pub fn request(&mut self, job: CpuJob) {
        let running = self.running.as_ref().map(|r| &r.key);
        if running == Some(&job.key) || self.waiting.as_ref().map(|j| &j.key) == Some(&job.key) {
            return;
        }
        if self.running.is_none() {
            self.running = Some(spawn(job));
        } else {
            self.waiting = Some(job);
        }
    }

    /// Whether a frame for `key` is running or waiting.
    pub fn is_working_on(&self, key: &FrameKey) -> bool {
        self.running.as_ref().is_some_and(|r| &r.key == key)
            || self.waiting.as_ref().is_some_and(|j| &j.key == key)
    }

    pub fn busy(&self) -> bool {
        self.running.is_some()
    }

    /// Fraction of the running frame's rows done.
    pub fn progress(&self) -> Option<f32> {
        self.running
            .as_ref()
            .map(|r| r.rows_done.load(Ordering::Relaxed) as f32 / r.rows.max(1) as f32)
    }

    /// A finished frame, if one is ready (starting the waiting job).
    pub fn poll(&mut self) -> Option<anyhow::Result<CpuFrame>> {
        let running = self.running.as_ref()?;
        if !running.handle.is_finished() {
            return None;
        }
        let running = self.running.take()?;
        let result = running
            .result
            .recv()
            .unwrap_or_else(|_| Err(anyhow::anyhow!("the CPU renderer stopped")));
        let _ = running.handle.join();
        if let Some(job) = self.waiting.take() {
            self.running = Some(spawn(job));
        }
        Some(result)
    }
}

fn spawn(job: CpuJob) -> Running {
    let (sender, result) = channel();
    let rows_done = Arc::new(AtomicUsize::new(0));
    let height = job.key.size.1;
    let views = job.work.views();
    let counter = Arc::clone(&rows_done);
    let key = job.key.clone();
    let handle = std::thread::spawn(move || {
        let _ = sender.send(render(&job, &counter));
    });
    Running {
        key,
        handle,
        result,
        rows_done,
        rows: height as usize * views.max(1),
    }
}

fn render(job: &CpuJob, rows_done: &AtomicUsize) -> anyhow::Result<CpuFrame> {
    match &job.work {
        CpuWork::Raycast { scene, integrators } => raycast(job, scene, integrators, rows_done),
        CpuWork::ShearWarp(renderers) => shear_warp(job, renderers, rows_done),
    }
}

fn raycast(
    job: &CpuJob,
    scene: &Scene,
    integrators: &[Arc<ScalarIntegrator>],
    rows_done: &AtomicUsize,
) -> anyhow::Result<CpuFrame> {
    let (width, height) = job.key.size;
    let options = RenderOptions {
        width,
        height,
        early_termination: job.key.early_termination,
        max_steps_per_ray: None,
        threads: None,
    };
    views(job, "CPU reference", integrators, |view, integrator| {
        let base = view * height as usize;
        let progress = |done: usize, _rows: usize| rows_done.store(base + done, Ordering::Relaxed);
        let out = render_scalar_with_progress(
            scene,
            &job.key.camera,
            integrator,
            &options,
            Some(&progress),
        )?;
        Ok((out.image, out.stats.counters, out.stats.elapsed))
    })
}

/// The frame of `job`, one image per view from `render(view, renderer)`
/// (the image, its counters and its time).
fn views<R>(
    job: &CpuJob,
    renderer: &'static str,
    renderers: &[R],
    mut render: impl FnMut(usize, &R) -> anyhow::Result<(Image, WalkCounters, Duration)>,
) -> anyhow::Result<CpuFrame> {
    let mut images = Vec::new();
    let mut stats = [WalkCounters::default(); 2];
    let mut elapsed = Duration::ZERO;
    for (view, r) in renderers.iter().enumerate() {
        let (image, counters, time) = render(view, r)?;
        if let Some(slot) = stats.get_mut(view) {
            *slot = counters;
        }
        elapsed += time;
        images.push(image);
    }
    Ok(CpuFrame {
        key: job.key.clone(),
        report: FrameReport {
            size: job.key.size,
            views: images.len() as u32,
            elapsed,
            batches: 1,
            stats,
            renderer,
        },
        images,
    })
}

/// One shear-warp frame per view. Its counters fill the ray caster's:
/// slabs composited count as segments (each slab between two slices is one
/// integrated segment of a ray).
fn shear_warp(
    job: &CpuJob,
    renderers: &[Arc<ShearWarp>],
    rows_done: &AtomicUsize,
) -> anyhow::Result<CpuFrame> {
    let (width, height) = job.key.size;
    let options = ShearWarpOptions {
        width,
        height,
        early_termination: job.key.early_termination,
        skip_empty: true,
    };
    views(job, shear_warp_name(renderers), renderers, |view, sw| {
        let out = sw
            .render(&job.key.camera, &options)
            .map_err(|e| anyhow::anyhow!("shear-warp: {e}"))?;
        rows_done.store((view + 1) * height as usize, Ordering::Relaxed);
        let counters = WalkCounters::of_image(&out.image, out.stats.slabs_composited, 0);
        Ok((out.image, counters, out.stats.elapsed))
    })
}

/// The report's name of a shear-warp frame: its classification when the
/// views share one.
fn shear_warp_name(renderers: &[Arc<ShearWarp>]) -> &'static str {
    let first = renderers.first().map(|sw| sw.classification());
    if renderers
        .iter()
        .any(|sw| Some(sw.classification()) != first)
    {
        return "shear-warp";
    }
    match first {
        Some(Classification::PostClassified) => "shear-warp, post-classified",
        _ => "shear-warp, pre-integrated",
    }
}
