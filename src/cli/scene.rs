//! From command-line options to what the renderers need: the loaded mesh,
//! the scene (topology, boundary BVH, active scalar), the integrator and the
//! camera. Shared by `render`, `bench` and `compare`; `info` uses the loader
//! only. The work is `tetray-frame`'s (shared with the Python bindings):
//! this maps the flags onto its options, prints its progress on stdout (or
//! where `log` says) and its warnings on stderr. With `--renderer
//! shear-warp` the file is read as its regular grid alone instead
//! (`tetray_frame::shear_warp::prepare_grid`).

use anyhow::Context;

pub use tetray_frame::{plural, MeshInput, Setup};

use super::args::{CameraArgs, IntegratorArgs, MeshArgs, RendererArg, WalkArgs};

/// Loads the mesh the options name, or the embedded default, and gives
/// back what the allocator kept of the load's temporaries (for commands
/// that go on without building a scene from them: `info`, `view`, MPI).
pub fn load_mesh(args: &MeshArgs) -> anyhow::Result<MeshInput> {
    let input = tetray_frame::load_mesh(&args.options());
    crate::ALLOCATOR.release();
    Ok(input?)
}

/// What [`prepare`] makes a frame of.
#[derive(Clone, Copy)]
pub struct FrameArgs<'a> {
    pub mesh: &'a MeshArgs,
    pub integrator: &'a IntegratorArgs,
    pub camera: &'a CameraArgs,
    pub walk: &'a WalkArgs,
    pub size: (u32, u32),
}

impl FrameArgs<'_> {
    /// The flags as the frame library's options (`tf_text`: the `--tf`
    /// file's content).
    pub fn options(&self, tf_text: Option<String>) -> tetray_frame::FrameOptions {
        tetray_frame::FrameOptions {
            integrator: self.integrator.choice(tf_text),
            camera: self.camera.options(),
            bvh_preset: self.walk.bvh_preset,
            size: self.size,
        }
    }
}

/// Warnings on stderr, as every command prints them.
pub fn warn(line: String) {
    eprintln!("warning: {line}");
}

/// Loads the mesh, builds the scene, the camera (before the integrator's
/// tables, so a bad camera fails fast) and the integrator, reporting each
/// step through `log` and warnings on stderr.
pub fn prepare(frame: FrameArgs<'_>, log: &dyn Fn(String)) -> anyhow::Result<Setup> {
    // Read before the (possibly long) mesh load, so a bad path fails at once.
    let tf_text = match &frame.integrator.tf {
        Some(path) => Some(
            std::fs::read_to_string(path)
                .with_context(|| format!("--tf {}: cannot read", path.display()))?,
        ),
        None => None,
    };
    let options = frame.options(tf_text);
    let log = tetray_frame::Log {
        info: log,
        warn: &warn,
    };
    if frame.walk.renderer == RendererArg::ShearWarp {
        let mesh = frame.mesh.options();
        return Ok(tetray_frame::shear_warp::prepare_grid(
            &mesh, &options, log,
        )?);
    }
    // The scene is built in the blocks the load freed; then they go back.
    let input = tetray_frame::load_mesh(&frame.mesh.options())?;
    let setup = tetray_frame::prepare(input, &options, log);
    crate::ALLOCATOR.release();
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
