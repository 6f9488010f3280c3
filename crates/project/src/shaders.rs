//! The WGSL of the projection pipeline, embedded and put together by
//! [`tetray_gpu::shaders::module`], as the ray caster's.

/// Parameters and bindings.
pub const PROJECT_COMMON: &str = include_str!("../../../shaders/project_common.wgsl");
/// The vertex and fragment stages.
pub const PROJECT: &str = include_str!("../../../shaders/project.wgsl");

/// The projection module: declarations, the ray caster's integration code
/// (shaders/integrate.wgsl, shared), then the stages.
pub fn project_source() -> String {
    tetray_gpu::shaders::module(&[PROJECT_COMMON, tetray_gpu::shaders::INTEGRATE, PROJECT])
}
