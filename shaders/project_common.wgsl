// Declarations of the cell-projection pipeline (tetray_project): parameters
// and bindings. The host puts the method codes, params, project_common,
// integrate and project (in that order) into one module; integrate.wgsl
// reads `params.integrator`, `tables` and `psi_table`.

// Per-frame parameters (host: tetray_project::layout::Params): the camera
// as the ray casters have it (pixel (px, py) is the ray through
// right * x + up * y at unit depth from `position` (perspective) or on the
// view plane through it (orthographic)) and the integrator.
struct Params {
    view: ViewParams,
    integrator: IntegratorParams,
}

// Counters (host: tetray_project::layout::STAT_*).
const STAT_SEGMENTS: u32 = 0u;
const STAT_COUNT: u32 = 2u;

// A draw of the whole cell, transfer function sampled at the segment ends
// (host: tetray_project::draws::NO_CLIP).
const NO_CLIP: u32 = 0xffffffffu;

// Read-only storage, not uniform: see common.wgsl (lavapipe specializes
// shaders on uniform values at every bind).
@group(0) @binding(0) var<storage, read> params: Params;
// Per point: position and active scalar.
@group(0) @binding(1) var<storage, read> points: array<vec4<f32>>;
// Per tetrahedron: its points, positively oriented.
@group(0) @binding(2) var<storage, read> tets: array<vec4<u32>>;
// Transfer-function intervals, then the pre-integration table.
@group(0) @binding(3) var<storage, read> tables: array<vec4<f32>>;
@group(0) @binding(4) var psi_table: texture_2d<f32>;
@group(0) @binding(5) var<storage, read_write> stats: array<atomic<u32>, STAT_COUNT>;
