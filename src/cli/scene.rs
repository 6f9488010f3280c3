//! From command-line flags to the engine's options, and the engine's
//! progress on the terminal: `render`, `bench`, `compare`, `view` and `info`
//! all make their frames (or load their mesh) through `tetray_engine`,
//! printing its progress on stdout (or where `log` says) and its warnings
//! on stderr.

use anyhow::Context;

pub use tetray_engine::{MeshInput, Setup, plural};

use super::args::{FrameFlags, IntegratorArgs, MeshArgs, WalkArgs};

/// Loads the mesh the flags name, or the embedded default, and gives back
/// what the allocator kept of the load's temporaries (for commands that go
/// on without building a scene from it: `info`, MPI).
pub fn load_mesh(args: &MeshArgs) -> anyhow::Result<MeshInput> {
    let input = tetray_engine::load(args.source()?);
    super::ALLOCATOR.release();
    Ok(input?)
}

/// What [`prepare`] makes a frame of.
#[derive(Clone, Copy)]
pub struct FrameArgs<'a> {
    pub flags: &'a FrameFlags,
    pub walk: &'a WalkArgs,
    pub size: (u32, u32),
}

impl FrameArgs<'_> {
    /// The flags as the engine's options (`tf_text`: the `--tf` file's
    /// content), for the renderer `--renderer` names.
    pub fn options(&self, tf_text: Option<String>) -> tetray_engine::FrameOptions {
        tetray_engine::FrameOptions {
            integrator: self.flags.integrator.choice(tf_text),
            camera: self.flags.camera.options(),
            bvh_preset: self.walk.bvh_preset,
            size: self.size,
            representation: tetray_engine::Representation::for_renderer(self.walk.renderer.into()),
        }
    }
}

/// Warnings on stderr, as every command prints them.
pub fn warn(line: String) {
    eprintln!("warning: {line}");
}

/// The `--tf` file's content, read before the (possibly long) mesh load so
/// a bad path fails at once.
pub fn read_tf(integrator: &IntegratorArgs) -> anyhow::Result<Option<String>> {
    integrator
        .tf
        .as_ref()
        .map(|path| {
            std::fs::read_to_string(path)
                .with_context(|| format!("--tf {}: cannot read", path.display()))
        })
        .transpose()
}

/// Loads the mesh and makes the frame's setup through the engine, reporting
/// each step through `log` and warnings on stderr.
pub fn prepare(frame: FrameArgs<'_>, log: &dyn Fn(String)) -> anyhow::Result<Setup> {
    let options = frame.options(read_tf(&frame.flags.integrator)?);
    prepare_with(&frame.flags.mesh, &options, log)
}

/// [`prepare`] with the engine's options already made.
pub fn prepare_with(
    mesh: &MeshArgs,
    options: &tetray_engine::FrameOptions,
    log: &dyn Fn(String),
) -> anyhow::Result<Setup> {
    let log = tetray_engine::Log {
        info: log,
        warn: &warn,
    };
    let setup = tetray_engine::prepare(mesh.source()?, options, log);
    // The scene is built in the blocks the load freed; now they go back.
    super::ALLOCATOR.release();
    Ok(setup?)
}

/// Sets the size of rayon's global pool, before any parallel work.
pub fn configure_threads(threads: Option<u16>) -> anyhow::Result<()> {
    if let Some(threads) = threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(usize::from(threads))
            .build_global()
            .with_context(|| format!("--threads {threads}: cannot start the thread pool"))?;
    }
    Ok(())
}
