//! `--renderer shear-warp`: see `tetray_frame::shear_warp` (a `.vti` /
//! STRUCTURED_POINTS file read as the regular grid it is, rendered with
//! the flags the tetrahedral renderers take).

pub use tetray_frame::shear_warp::classification;
