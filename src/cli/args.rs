//! Options shared by the commands (their values' parsers are in
//! [`super::parse`]).

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use glam::{DVec3, Vec3};
use tetray_boundary_bvh::BuildPreset;
use tetray_core::defaults::{PREINTEGRATION_TABLE_SIZE, PSI_TABLE_SIZE, VIEW_ANGLE};
use tetray_integrate::{Method, OpacityMode};
use tetray_project::SortKind;

use super::parse::{
    parse_bvh_preset, parse_dvec3, parse_early_termination, parse_finite, parse_method,
    parse_positive, parse_range, parse_rgb, parse_size, parse_sort, parse_time, parse_vec3,
    parse_view_angle,
};

/// Which mesh to load. No path means the embedded Blunt Fin dataset.
#[derive(Debug, Clone, Default, Args)]
pub struct MeshArgs {
    /// Mesh file: .vtk (unstructured, structured, rectilinear or image
    /// data), .vtu, .vts, .vtr, .vti, their parallel forms .pvtu, .pvts,
    /// .pvtr, .pvti, multi-block .vtm, Exodus II (.e, .exo, .ex2, .exii, .g,
    /// .gen), VTKHDF (.vtkhdf, .hdf), an OpenFOAM case (its folder,
    /// system/controlDict or a .foam file), EnSight Gold (.case), CGNS
    /// (.cgns, HDF5 or ADF storage), a PLOT3D grid (*xyz.bin, *.xyz, *.x), or a
    /// time series of them (*.series, .pvd). Default: the
    /// embedded Blunt Fin (PLOT3D, NASA).
    pub mesh: Option<PathBuf>,
    /// PLOT3D solution (q) file. Default: the grid's name with "xyz"
    /// replaced by "q" (postxyz.bin -> postq.bin), when it exists.
    #[arg(long, value_name = "FILE")]
    pub q: Option<PathBuf>,
    /// Files with time steps (Exodus II, VTKHDF, OpenFOAM, EnSight, *.series,
    /// .pvd):
    /// the time step to read, counted from 0 (default: 0).
    #[arg(long, value_name = "N", conflicts_with = "time")]
    pub time_step: Option<usize>,
    /// Files with time steps: read the time step whose stored time is
    /// nearest T.
    #[arg(long, value_name = "T", value_parser = parse_time, allow_hyphen_values = true)]
    pub time: Option<f64>,
    /// For a multi-block .vtm: keep only this block (its name attribute,
    /// or a path of names such as outer/inner). Default: every volume block.
    #[arg(long, value_name = "NAME")]
    pub block: Option<String>,
    /// Quadratic and order-2 Lagrange cells: subdivide them into linear
    /// tetrahedra through all their nodes, or keep their corners only (as
    /// VTK's unstructured volume mappers do).
    #[arg(long, value_enum, default_value_t = LinearizeArg::Subdivide)]
    pub linearize: LinearizeArg,
}

/// `--linearize`: see [`tetray_io::vtk::Linearize`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, ValueEnum)]
pub enum LinearizeArg {
    #[default]
    Subdivide,
    Corners,
}

impl From<LinearizeArg> for tetray_io::vtk::Linearize {
    fn from(arg: LinearizeArg) -> Self {
        match arg {
            LinearizeArg::Subdivide => tetray_io::vtk::Linearize::Subdivide,
            LinearizeArg::Corners => tetray_io::vtk::Linearize::Corners,
        }
    }
}

/// VTK/ParaView camera. Whatever is not given comes from a
/// `vtkRenderer::ResetCamera` fit of the mesh bounds, looking down -z;
/// with no camera flag at all, the fit is then turned to an oblique view
/// ([`tetray_engine::DEFAULT_VIEW`]).
#[derive(Debug, Clone, Default, Args)]
pub struct CameraArgs {
    /// Camera position x,y,z (world units: the file's coordinates, read in
    /// f64; the origin the mesh is stored relative to is subtracted).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_dvec3, allow_hyphen_values = true)]
    pub camera_position: Option<DVec3>,
    /// Focal point x,y,z (world units, as --camera-position).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_dvec3, allow_hyphen_values = true)]
    pub focal_point: Option<DVec3>,
    /// View-up vector x,y,z.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub view_up: Option<Vec3>,
    /// Full vertical view angle in degrees (perspective).
    #[arg(long, value_name = "DEGREES", default_value_t = VIEW_ANGLE, value_parser = parse_view_angle, allow_hyphen_values = true)]
    pub view_angle: f32,
    /// Orthographic projection with this half view height (world units),
    /// as VTK's ParallelScale. Without it the projection is perspective.
    #[arg(long, value_name = "S", value_parser = parse_positive, allow_hyphen_values = true)]
    pub parallel_scale: Option<f32>,
    /// Rotate the camera about the view-up by this many degrees, after the
    /// fit (vtkCamera::Azimuth). Default 0 when any camera flag is given;
    /// with none, the default view is oblique (see [`tetray_engine::DEFAULT_VIEW`]).
    #[arg(long, value_name = "DEGREES", value_parser = parse_finite, allow_hyphen_values = true)]
    pub azimuth: Option<f32>,
    /// Then rotate it up by this many degrees (vtkCamera::Elevation,
    /// followed by OrthogonalizeViewUp). Default as --azimuth.
    #[arg(long, value_name = "DEGREES", value_parser = parse_finite, allow_hyphen_values = true)]
    pub elevation: Option<f32>,
}

impl CameraArgs {
    /// The flags (their azimuth and elevation default:
    /// [`tetray_engine::CameraOptions::rotation`]) as the frame library's options.
    pub fn options(&self) -> tetray_engine::CameraOptions {
        tetray_engine::CameraOptions {
            camera_position: self.camera_position,
            focal_point: self.focal_point,
            view_up: self.view_up,
            view_angle: self.view_angle,
            parallel_scale: self.parallel_scale,
            azimuth: self.azimuth,
            elevation: self.elevation,
        }
    }
}

impl MeshArgs {
    /// The data the flags name: the file, or the embedded Blunt Fin when
    /// none is given (which takes no file options).
    pub fn source(&self) -> anyhow::Result<tetray_engine::Source> {
        let Some(path) = &self.mesh else {
            if self.q.is_some() {
                anyhow::bail!("--q needs a PLOT3D grid file (the embedded dataset has its own)");
            }
            if self.time_step.is_some() || self.time.is_some() {
                anyhow::bail!("--time-step and --time need a file with time steps");
            }
            if self.block.is_some() {
                anyhow::bail!("--block needs a multi-block file (.vtm)");
            }
            return Ok(tetray_engine::Source::Embedded);
        };
        Ok(tetray_engine::Source::File {
            path: path.clone(),
            options: tetray_io::LoadOptions {
                plot3d_q: self.q.clone(),
                time_step: self.time_step,
                time: self.time,
                block: self.block.clone(),
                linearize: self.linearize.into(),
            },
        })
    }
}

/// How a transfer-function opacity becomes an attenuation coefficient.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum OpacityModeArg {
    /// tau = -ln(1 - alpha) / u: alpha is the opacity of one unit distance.
    Exact,
    /// tau = alpha / u, as VTK's unstructured-grid integrators do.
    Vtk,
}

impl OpacityModeArg {
    pub fn name(self) -> &'static str {
        match self {
            OpacityModeArg::Exact => "exact",
            OpacityModeArg::Vtk => "vtk",
        }
    }
}

impl From<OpacityModeArg> for OpacityMode {
    fn from(mode: OpacityModeArg) -> OpacityMode {
        match mode {
            OpacityModeArg::Exact => OpacityMode::Exact,
            OpacityModeArg::Vtk => OpacityMode::Vtk,
        }
    }
}

/// The scalar, the transfer function and the ray-integration method.
#[derive(Debug, Clone, Args)]
pub struct IntegratorArgs {
    /// Point scalar field to render. Default: the mesh's first field
    /// (density for PLOT3D).
    #[arg(long, value_name = "NAME")]
    pub scalar: Option<String>,
    /// Integration method: ppi (partial pre-integration, the default),
    /// exact, average, average-opacity, lin-avg-opacity, lin-opacity,
    /// preintegrated, riemann, reference, reference-opacity.
    #[arg(long, value_name = "NAME", default_value = "ppi", value_parser = parse_method)]
    pub integrator: Method,
    /// ParaView colour-map preset JSON (RGBPoints, Points, ColorSpace).
    /// Default: a cool-to-warm ramp with rising opacity over the data range.
    #[arg(long, value_name = "FILE")]
    pub tf: Option<PathBuf>,
    /// Preset name when the JSON holds several (default: the first).
    #[arg(long, value_name = "NAME", requires = "tf")]
    pub tf_name: Option<String>,
    /// Keep the preset's scalar values instead of rescaling them to the
    /// data range (ParaView rescales by default).
    #[arg(long, requires = "tf")]
    pub no_rescale: bool,
    /// The scalar range the transfer function spans, MIN,MAX (ParaView's
    /// custom range, PyVista's clim). Default: the field's range; for
    /// `animate`, its range over all the time steps rendered.
    #[arg(long, value_name = "MIN,MAX", value_parser = parse_range, allow_hyphen_values = true)]
    pub clim: Option<(f32, f32)>,
    /// Opacity unit distance u (world units). Default: ParaView's default
    /// ScalarOpacityUnitDistance, the bounds diagonal divided by the cube
    /// root of the number of cells of the dataset as read (hexahedra for
    /// PLOT3D, the file's cells for VTK; before they are split into tets).
    #[arg(long, value_name = "U", value_parser = parse_positive, allow_hyphen_values = true)]
    pub unit_distance: Option<f32>,
    /// How opacity becomes attenuation.
    #[arg(long, value_enum, default_value_t = OpacityModeArg::Exact)]
    pub opacity_mode: OpacityModeArg,
    /// Psi table nodes per axis (ppi).
    #[arg(long, value_name = "N", default_value_t = PSI_TABLE_SIZE)]
    pub psi_size: usize,
    /// Step of the Riemann sum (world units). Default: a quarter of the
    /// mean tetrahedron chord length.
    #[arg(long, value_name = "STEP", value_parser = parse_positive, allow_hyphen_values = true)]
    pub riemann_step: Option<f32>,
    /// Full pre-integration table nodes per axis (preintegrated).
    #[arg(long, value_name = "N", default_value_t = PREINTEGRATION_TABLE_SIZE)]
    pub preintegration_size: usize,
    /// Do not cut segments at the transfer function's control points
    /// (section 4.3); only to study what the cut buys.
    #[arg(long)]
    pub no_knot_split: bool,
}

impl IntegratorArgs {
    /// The flags as the frame library's options; `tf_text` is the `--tf`
    /// file's content, read by the caller.
    pub fn choice(&self, tf_text: Option<String>) -> tetray_engine::IntegratorChoice {
        let tf = match (&self.tf, tf_text) {
            (Some(path), Some(text)) => tetray_engine::TfSource::ParaView {
                text,
                name: self.tf_name.clone(),
                rescale: !self.no_rescale,
                label: format!("--tf {}", path.display()),
            },
            _ => tetray_engine::TfSource::Default,
        };
        tetray_engine::IntegratorChoice {
            scalar: self.scalar.clone(),
            method: self.integrator,
            tf,
            unit_distance: self.unit_distance,
            opacity_mode: self.opacity_mode.into(),
            psi_size: self.psi_size,
            riemann_step: self.riemann_step,
            preintegration_size: self.preintegration_size,
            knot_split: !self.no_knot_split,
            range: self.clim,
        }
    }
}

/// Which renderer draws the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RendererArg {
    /// The GPU ray caster on a hardware adapter, else the CPU one.
    Auto,
    /// The CPU reference ray caster (rayon, one ray per pixel).
    Cpu,
    /// The wgpu compute ray caster (the adapter from WGPU_ADAPTER_NAME /
    /// WGPU_BACKEND, else the default).
    Gpu,
    /// Cell projection: projected tetrahedra on wgpu render pipelines,
    /// composited in the order of --sort (same adapter choice as gpu).
    Project,
    /// Shear-warp with pre-integrated slabs, for uniform grids (.vti,
    /// STRUCTURED_POINTS); `--integrator riemann` post-classifies.
    ShearWarp,
}

/// The renderer and its walk limits.
#[derive(Debug, Clone, Args)]
pub struct WalkArgs {
    #[arg(long, value_enum, default_value_t = RendererArg::Auto)]
    pub renderer: RendererArg,
    /// Stop a ray once its opacity reaches A, in (0, 1]; 1 disables early
    /// termination (the default: the reference renderer integrates
    /// everything).
    #[arg(long, value_name = "A", default_value_t = 1.0, value_parser = parse_early_termination, allow_hyphen_values = true)]
    pub early_termination: f32,
    /// Most tetrahedra one ray may visit; hitting the bound is counted and
    /// reported. Default: the number of tetrahedra plus 1024.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub max_steps: Option<u32>,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    /// Boundary BVH build preset: fastest, very-fast, fast, medium, slow,
    /// very-slow. Default: very-slow up to 100 000 boundary faces (the best
    /// tree, built in well under a second), fast above (very-slow costs
    /// about 3 us per face, single-threaded).
    #[arg(long, value_name = "PRESET", value_parser = parse_bvh_preset)]
    pub bvh_preset: Option<BuildPreset>,
    /// Visibility sort of --renderer project: centroid (cell-centre depth,
    /// as VTK's projected tetrahedra), mpvo (Williams; exact on convex,
    /// connected meshes), mpvonc (its heuristic for nonconvex meshes).
    #[arg(long, value_name = "SORT", default_value = "mpvonc", value_parser = parse_sort)]
    pub sort: SortKind,
    /// --renderer project: draw each cell once, the transfer function
    /// sampled at its segment ends, instead of once per knot interval it
    /// spans (adaptive transfer-function sampling, section 4.3).
    #[arg(long)]
    pub no_adaptive_tf: bool,
}

impl WalkArgs {
    /// Every flag at its default.
    pub fn defaults() -> Self {
        use clap::Parser;
        #[derive(Parser)]
        struct Wrapper {
            #[command(flatten)]
            args: WalkArgs,
        }
        Wrapper::parse_from(["tetray"]).args
    }
}

impl From<RendererArg> for tetray_engine::RendererChoice {
    fn from(arg: RendererArg) -> Self {
        match arg {
            RendererArg::Auto => tetray_engine::RendererChoice::Auto,
            RendererArg::Cpu => tetray_engine::RendererChoice::Cpu,
            RendererArg::Gpu => tetray_engine::RendererChoice::Gpu,
            RendererArg::Project => tetray_engine::RendererChoice::Project,
            RendererArg::ShearWarp => tetray_engine::RendererChoice::ShearWarp,
        }
    }
}

impl From<&WalkArgs> for tetray_engine::WalkOptions {
    fn from(walk: &WalkArgs) -> Self {
        tetray_engine::WalkOptions {
            early_termination: walk.early_termination,
            max_steps: walk.max_steps,
            sort: walk.sort,
            adaptive_tf: !walk.no_adaptive_tf,
        }
    }
}

/// Image size, file and background.
#[derive(Debug, Clone, Args)]
pub struct OutputArgs {
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "512x512")]
    pub size: (u32, u32),
    /// Output image: .png (composited over --background, 8-bit, no sRGB
    /// transform), .exr (linear float RGBA, premultiplied) or .npy (the
    /// same floats as a NumPy (height, width, 4) float32 array).
    #[arg(short, long, value_name = "FILE", default_value = "tetray.png")]
    pub output: PathBuf,
    /// Background colour r,g,b (or one grey value) for PNG output.
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, default_value = "0,0,0", allow_hyphen_values = true)]
    pub background: Vec3,
}

/// What every rendering command takes: the data, the field, transfer
/// function and integrator, and the camera.
#[derive(Debug, Clone, Args)]
pub struct FrameFlags {
    #[command(flatten)]
    pub mesh: MeshArgs,
    #[command(flatten)]
    pub integrator: IntegratorArgs,
    #[command(flatten)]
    pub camera: CameraArgs,
}

/// `tetray render`.
#[derive(Debug, Clone, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub frame: FrameFlags,
    #[command(flatten)]
    pub output: OutputArgs,
    #[command(flatten)]
    pub walk: WalkArgs,
    #[cfg(feature = "mpi")]
    #[command(flatten)]
    pub distributed: DistributedArgs,
}

impl RenderArgs {
    /// What `tetray` with no arguments does: `tetray render` with every
    /// default (the embedded Blunt Fin to tetray.png).
    pub fn defaults() -> Self {
        use clap::Parser;
        #[derive(Parser)]
        struct Wrapper {
            #[command(flatten)]
            args: RenderArgs,
        }
        Wrapper::parse_from(["tetray"]).args
    }
}

#[cfg(feature = "mpi")]
/// The flags of a distributed run.
#[derive(Debug, Clone, Args)]
pub struct DistributedArgs {
    /// Render distributed over the MPI ranks even when there is one (it is
    /// by default whenever mpirun starts more than one).
    #[arg(long)]
    pub distributed: bool,
    /// Edge in pixels of the image tiles dealt out to the ranks, which
    /// composite the fragments of their tiles' pixels.
    #[arg(long, value_name = "PIXELS", default_value_t = tetray_distributed::DEFAULT_TILE,
          value_parser = clap::value_parser!(u32).range(1..))]
    pub tile: u32,
}

#[cfg(feature = "mpi")]
impl DistributedArgs {
    /// Whether to render distributed: `--distributed`, or a launcher's
    /// world of more than one process (Open MPI's and MPICH's variables,
    /// read before initialising MPI so a plain run never does).
    pub fn wanted(&self) -> bool {
        let launched = ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"]
            .iter()
            .filter_map(|v| std::env::var(v).ok())
            .filter_map(|v| v.parse::<usize>().ok())
            .any(|n| n > 1);
        self.distributed || launched
    }
}
