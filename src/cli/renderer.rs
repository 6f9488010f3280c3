//! The renderer behind `render` and `bench`: the CPU reference ray caster,
//! the GPU one, the cell projection or shear-warp (`--renderer
//! cpu|gpu|project|shear-warp|auto`). The engines are `tetray-frame`'s
//! (shared with the Python bindings); [`Engine::new`] takes the
//! `--renderer` flag and [`Engine::render`] the walk flags through their
//! `From` conversions in `args.rs`.

pub use tetray_frame::{Frame, FrameStats};

/// A ready renderer (see [`tetray_frame::Engine`]).
pub type Engine = tetray_frame::Engine;
