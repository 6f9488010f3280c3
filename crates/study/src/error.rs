//! Why a study could not run or write its results.

use std::path::PathBuf;

use crate::svg::heat::HeatError;

#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("writing {path}: {source}")]
    Json {
        path: PathBuf,
        #[source]
        source: serde_json::Error,
    },
    #[error("{0}")]
    Option(String),
    #[error(transparent)]
    Heat(#[from] HeatError),
    #[error(transparent)]
    Integrate(#[from] tetray_integrate::IntegrateError),
    #[error(transparent)]
    ShearWarp(#[from] tetray_shearwarp::ShearWarpError),
    #[error(transparent)]
    Mesh(#[from] tetray_mesh::MeshError),
    #[error(transparent)]
    Load(#[from] tetray_io::IoError),
    #[error(transparent)]
    Scene(#[from] tetray_scene::SceneError),
    #[error(transparent)]
    Render(#[from] tetray_raycast::RenderError),
    #[error(transparent)]
    Camera(#[from] tetray_core::CameraError),
    #[error(transparent)]
    Build(#[from] tetray_mesh::synthetic::BuildError),
    #[error(transparent)]
    Gpu(#[from] tetray_gpu::GpuError),
    #[error(transparent)]
    Project(#[from] tetray_project::ProjectError),
    #[error(transparent)]
    Engine(#[from] tetray_engine::EngineError),
    #[error("{what} on the GPU: {message}")]
    GpuKernel { what: &'static str, message: String },
}
