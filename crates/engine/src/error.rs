//! The one error of this crate. Messages name what the user gave (a field,
//! a file, a renderer, a time step), never a command-line flag: the CLI,
//! the Python package and the viewer each spell their options their own
//! way.

use thiserror::Error;

/// Anything that stops a frame from being prepared or rendered.
#[derive(Debug, Error)]
pub enum EngineError {
    /// A file named in the options does not exist.
    #[error("{0}: no such file")]
    NoSuchFile(String),

    /// A file could not be read.
    #[error("{context}")]
    Read {
        context: String,
        #[source]
        source: std::io::Error,
    },

    /// The mesh reader (or the mesh checks after it) refused the input.
    #[error(transparent)]
    Load(#[from] tetray_io::IoError),

    /// The options cannot be used together or with this mesh.
    #[error("{0}")]
    Options(String),

    /// A step (scene, camera, integrator, GPU upload, render) failed; the
    /// source says why. Displayed as the step alone, like anyhow's
    /// context: the chain (see [`EngineError::chain`]) has the reason.
    #[error("{context}")]
    Step {
        context: String,
        #[source]
        source: Box<dyn std::error::Error + Send + Sync + 'static>,
    },
}

impl EngineError {
    /// A failed step with its reason.
    pub fn step(
        context: impl Into<String>,
        source: impl std::error::Error + Send + Sync + 'static,
    ) -> Self {
        EngineError::Step {
            context: context.into(),
            source: Box::new(source),
        }
    }

    /// The whole chain on one line, "step: reason: its reason", as the CLI
    /// prints errors; a reason the text already ends with (errors that
    /// display their source as well as return it) is not repeated.
    pub fn chain(&self) -> String {
        let mut text = self.to_string();
        let mut source = std::error::Error::source(self);
        while let Some(s) = source {
            let reason = s.to_string();
            if !text.ends_with(&reason) {
                text.push_str(": ");
                text.push_str(&reason);
            }
            source = s.source();
        }
        text.split_whitespace().collect::<Vec<_>>().join(" ")
    }

    /// Whether the error is about the file system (a missing or unreadable
    /// file) rather than about the data or the options.
    pub fn is_io(&self) -> bool {
        matches!(
            self,
            EngineError::NoSuchFile(_)
                | EngineError::Read { .. }
                | EngineError::Load(tetray_io::IoError::Io { .. })
                | EngineError::Load(tetray_io::IoError::Vtk(tetray_io::VtkError::Io { .. }))
        )
    }
}

/// An error and its sources on one line, "what: why: why that".
pub fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// `anyhow`-like context for this crate's results.
pub(crate) trait Context<T> {
    fn context(self, context: impl Into<String>) -> Result<T, EngineError>;
    fn with_context<C: Into<String>>(self, f: impl FnOnce() -> C) -> Result<T, EngineError>;
}

impl<T, E: std::error::Error + Send + Sync + 'static> Context<T> for Result<T, E> {
    fn context(self, context: impl Into<String>) -> Result<T, EngineError> {
        self.map_err(|e| EngineError::step(context, e))
    }
    fn with_context<C: Into<String>>(self, f: impl FnOnce() -> C) -> Result<T, EngineError> {
        self.map_err(|e| EngineError::step(f(), e))
    }
}

/// Returns early with [`EngineError::Options`].
macro_rules! bail {
    ($($arg:tt)*) => {
        return Err($crate::EngineError::Options(format!($($arg)*)))
    };
}
pub(crate) use bail;
