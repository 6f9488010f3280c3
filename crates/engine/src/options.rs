//! The options a frame is made from, as plain values: the CLI maps its
//! flags onto them, the Python package its keyword arguments, the viewer its
//! pickers, the distributed renderer what its ranks agreed on.

use glam::{DVec3, Vec3};
use tetray_boundary_bvh::BuildPreset;
use tetray_core::defaults::{DEFAULT_VIEW, PREINTEGRATION_TABLE_SIZE, PSI_TABLE_SIZE, VIEW_ANGLE};
use tetray_integrate::{ColorPoint, Method, OpacityMode, OpacityPoint};
use tetray_project::SortKind;

/// Where the transfer function comes from.
#[derive(Debug, Clone, Default)]
pub enum TfSource {
    /// A cool-to-warm ramp with rising opacity over the field's range (a
    /// uniform volume for a constant field).
    #[default]
    Default,
    /// A ParaView colour-map preset (JSON text).
    ParaView {
        text: String,
        /// The preset's name when the JSON holds several.
        name: Option<String>,
        /// Rescale its scalars to the field's range (ParaView's default).
        rescale: bool,
        /// Where it came from, for messages (a file name).
        label: String,
    },
    /// Control points over [0, 1], mapped onto `range` (the field's range
    /// when `None`): a colour map and opacity curve as plotting libraries
    /// give them (PyVista's `cmap`, `opacity`, `clim`). A constant field
    /// without a range renders as the default's uniform volume.
    Normalized {
        color: Vec<ColorPoint>,
        opacity: Vec<OpacityPoint>,
        range: Option<(f32, f32)>,
    },
    /// Control points at the field's own values (an editor's curve).
    Points {
        color: Vec<ColorPoint>,
        opacity: Vec<OpacityPoint>,
    },
}

/// The scalar, the transfer function and the ray-integration method.
#[derive(Debug, Clone)]
pub struct IntegratorChoice {
    /// Point field to render; `None`: the first that varies.
    pub scalar: Option<String>,
    pub method: Method,
    pub tf: TfSource,
    /// Opacity unit distance; `None`: ParaView's default.
    pub unit_distance: Option<f32>,
    pub opacity_mode: OpacityMode,
    pub psi_size: usize,
    /// `None`: a quarter of the mean tetrahedron chord.
    pub riemann_step: Option<f32>,
    pub preintegration_size: usize,
    /// Cut segments at the transfer function's control points.
    pub knot_split: bool,
    /// The scalar range the transfer function spans (ParaView's custom
    /// range, PyVista's `clim`; an animation's range over all its steps);
    /// `None`: the field's range.
    pub range: Option<(f32, f32)>,
}

impl IntegratorChoice {
    /// The range the transfer function spans for a field of `field_range`.
    pub fn tf_range(&self, field_range: (f32, f32)) -> (f32, f32) {
        self.range.unwrap_or(field_range)
    }
}

impl Default for IntegratorChoice {
    fn default() -> Self {
        IntegratorChoice {
            scalar: None,
            method: Method::Ppi,
            tf: TfSource::Default,
            unit_distance: None,
            opacity_mode: OpacityMode::Exact,
            psi_size: PSI_TABLE_SIZE,
            riemann_step: None,
            preintegration_size: PREINTEGRATION_TABLE_SIZE,
            knot_split: true,
            range: None,
        }
    }
}

/// A VTK/ParaView camera. Whatever is not given comes from a
/// `vtkRenderer::ResetCamera` fit of the volume's bounds, looking down -z;
/// with nothing given at all, the fit is then turned to [`DEFAULT_VIEW`].
#[derive(Debug, Clone, PartialEq)]
pub struct CameraOptions {
    /// In the file's coordinates (f64; the mesh's origin is subtracted).
    pub camera_position: Option<DVec3>,
    pub focal_point: Option<DVec3>,
    pub view_up: Option<Vec3>,
    /// Full vertical view angle in degrees (perspective).
    pub view_angle: f32,
    /// Orthographic half view height.
    pub parallel_scale: Option<f32>,
    pub azimuth: Option<f32>,
    pub elevation: Option<f32>,
}

impl Default for CameraOptions {
    fn default() -> Self {
        CameraOptions {
            camera_position: None,
            focal_point: None,
            view_up: None,
            view_angle: VIEW_ANGLE,
            parallel_scale: None,
            azimuth: None,
            elevation: None,
        }
    }
}

impl CameraOptions {
    /// Azimuth and elevation to apply: VTK's exactly (0 where not given)
    /// when any of position, focal point, view-up, azimuth or elevation is
    /// given, or the parallel scale; else [`DEFAULT_VIEW`].
    pub fn rotation(&self) -> (f32, f32) {
        if self.is_given() {
            (self.azimuth.unwrap_or(0.0), self.elevation.unwrap_or(0.0))
        } else {
            DEFAULT_VIEW
        }
    }

    /// Whether any camera value is given (the view angle aside).
    pub fn is_given(&self) -> bool {
        self.camera_position.is_some()
            || self.focal_point.is_some()
            || self.view_up.is_some()
            || self.parallel_scale.is_some()
            || self.azimuth.is_some()
            || self.elevation.is_some()
    }
}

/// Which renderer draws the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RendererChoice {
    /// The GPU ray caster on a hardware adapter, else the CPU one.
    #[default]
    Auto,
    Cpu,
    Gpu,
    Project,
    /// Image data (`.vti`, legacy STRUCTURED_POINTS) only.
    ShearWarp,
}

impl RendererChoice {
    pub const NAMES: &'static str = "auto, cpu, gpu, project, shear-warp";

    pub fn name(self) -> &'static str {
        match self {
            RendererChoice::Auto => "auto",
            RendererChoice::Cpu => "cpu",
            RendererChoice::Gpu => "gpu",
            RendererChoice::Project => "project",
            RendererChoice::ShearWarp => "shear-warp",
        }
    }
}

impl std::str::FromStr for RendererChoice {
    type Err = String;
    fn from_str(text: &str) -> Result<Self, String> {
        match text.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(RendererChoice::Auto),
            "cpu" => Ok(RendererChoice::Cpu),
            "gpu" => Ok(RendererChoice::Gpu),
            "project" => Ok(RendererChoice::Project),
            "shear-warp" | "shear_warp" => Ok(RendererChoice::ShearWarp),
            _ => Err(format!(
                "unknown renderer {text:?}: expected one of {}",
                RendererChoice::NAMES
            )),
        }
    }
}

/// Which representations of the data [`crate::prepare`] makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Representation {
    /// Tetrahedra, for the ray casters and the projection.
    #[default]
    Tetrahedra,
    /// The regular grid alone (no tetrahedra, topology or BVH), for
    /// shear-warp: image data only.
    Grid,
    /// Tetrahedra, and the regular grid too when the file is image data
    /// (read once): for front ends that offer every renderer.
    Both,
}

impl Representation {
    /// What `renderer` needs.
    pub fn for_renderer(renderer: RendererChoice) -> Representation {
        match renderer {
            RendererChoice::ShearWarp => Representation::Grid,
            _ => Representation::Tetrahedra,
        }
    }
}

/// The renderer's walk limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WalkOptions {
    /// Stop a ray at this opacity, in (0, 1]; 1: never.
    pub early_termination: f32,
    /// Most tetrahedra one ray may visit (`None`: the count plus 1024).
    pub max_steps: Option<u32>,
    /// The projection's visibility sort.
    pub sort: SortKind,
    /// The projection draws each cell once per knot interval it spans.
    pub adaptive_tf: bool,
}

impl Default for WalkOptions {
    fn default() -> Self {
        WalkOptions {
            early_termination: 1.0,
            max_steps: None,
            sort: SortKind::Mpvonc,
            adaptive_tf: true,
        }
    }
}

/// What [`crate::prepare`] makes a frame of, besides the data.
#[derive(Debug, Clone, Default)]
pub struct FrameOptions {
    pub integrator: IntegratorChoice,
    pub camera: CameraOptions,
    /// `None`: see [`bvh_preset_for`].
    pub bvh_preset: Option<BuildPreset>,
    /// Width and height in pixels (the camera's fit depends on the aspect).
    pub size: (u32, u32),
    pub representation: Representation,
}

/// The BVH preset for a mesh with `faces` boundary faces: the one given, or
/// very-slow up to 100 000 boundary faces (the best tree, built in well
/// under a second), fast above (very-slow costs about 3 us per face).
pub fn bvh_preset_for(given: Option<BuildPreset>, faces: usize) -> BuildPreset {
    given.unwrap_or(if faces <= 100_000 {
        BuildPreset::VerySlow
    } else {
        BuildPreset::Fast
    })
}

/// Where [`crate::prepare`] and [`crate::Engine`] report: progress lines
/// (`info`) and warnings (`warn`, without a "warning: " prefix).
#[derive(Clone, Copy)]
pub struct Log<'a> {
    pub info: &'a dyn Fn(String),
    pub warn: &'a dyn Fn(String),
}

impl Log<'_> {
    /// A log that drops everything.
    pub fn quiet() -> Log<'static> {
        Log {
            info: &|_| {},
            warn: &|_| {},
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_oblique_default_applies_only_when_nothing_is_given() {
        assert_eq!(CameraOptions::default().rotation(), DEFAULT_VIEW);
        let zero = CameraOptions {
            azimuth: Some(0.0),
            ..CameraOptions::default()
        };
        assert_eq!(zero.rotation(), (0.0, 0.0));
        let up = CameraOptions {
            view_up: Some(Vec3::Z),
            ..CameraOptions::default()
        };
        assert_eq!(up.rotation(), (0.0, 0.0));
    }

    #[test]
    fn renderers_by_name() {
        assert_eq!("GPU".parse::<RendererChoice>(), Ok(RendererChoice::Gpu));
        assert_eq!(
            "shear-warp".parse::<RendererChoice>(),
            Ok(RendererChoice::ShearWarp)
        );
        let err = "raytrace".parse::<RendererChoice>().unwrap_err();
        assert!(err.contains(RendererChoice::NAMES), "{err}");
        for choice in [RendererChoice::Auto, RendererChoice::Project] {
            assert_eq!(choice.name().parse::<RendererChoice>(), Ok(choice));
        }
        assert_eq!(
            Representation::for_renderer(RendererChoice::ShearWarp),
            Representation::Grid
        );
    }
}
