// Shared declarations of the ray-casting kernel: parameters, bindings and
// buffer accessors. The host puts the method codes, params, common,
// predicate, bvh, integrate and raycast (in that order) into one module
// (tetray_gpu::shaders).

// Per-frame parameters (host: tetray_gpu::layout::Params).
struct Params {
    view: ViewParams,
    bounds_min: vec3<f32>,
    // Perspective eye inside the mesh bounds: rays walk from their line's
    // first entry, behind the eye too.
    eye_inside: u32,
    bounds_max: vec3<f32>,
    scene_abs_max: f32,
    width: u32,
    height: u32,
    max_steps: u32,
    // Stop once the sum of the transmittance channels is at most this.
    stop_below_sum: f32,
    integrator: IntegratorParams,
    // Tetrahedra in `tets0` (the rest are in `tets1`), points likewise.
    tet_chunk: u32,
    point_chunk: u32,
    // Offsets (in vec4 entries) of the primitives and the face table in `bvh`.
    prim_offset: u32,
    face_offset: u32,
    // Offset (in `bvh` entries) of the cells left out of the walk: the
    // bounds of their points (two entries, floats as bits), then one entry
    // of point indices per tetrahedron (overlaps.wgsl).
    overlap_offset: u32,
    overlap_count: u32,
}

// The pixels of one dispatch (a dynamic-offset binding, one per tile).
struct Tile {
    x0: u32,
    y0: u32,
    width: u32,
    height: u32,
}

// Per-frame counters (host: tetray_gpu::layout::STAT_*).
const STAT_RAYS_HIT: u32 = 0u;
const STAT_SEGMENTS_LO: u32 = 1u;
const STAT_SEGMENTS_HI: u32 = 2u;
const STAT_STEPS_LO: u32 = 3u;
const STAT_STEPS_HI: u32 = 4u;
const STAT_ENTRIES: u32 = 5u;
const STAT_BOUND_HITS: u32 = 6u;
const STAT_WALK_FAILURES: u32 = 7u;
const STAT_OVERLAP_SEGMENTS: u32 = 8u;
const STAT_OVERLAP_OVERFLOWS: u32 = 9u;
const STAT_COUNT: u32 = 10u;

// A boundary face with no neighbour, and one on the convex hull (a ray
// leaving through it is done).
const NO_NEIGHBOR: u32 = 0xffffffffu;
const FINAL_EXIT: u32 = 0xfffffffeu;

// Read-only storage, not uniform: lavapipe (Mesa) inlines the values of
// uniform buffers that steer branches into a new specialization of the
// shader at every dispatch whose bindings changed, about 30 ms each for this
// kernel (a 1 x 1 frame took 28 ms, now 0.2 ms). Storage reads of a few
// words per invocation cost a GPU nothing measurable.
@group(0) @binding(0) var<storage, read> params: Params;
@group(0) @binding(1) var<storage, read> tile: Tile;
// Per point: position and active scalar.
@group(0) @binding(2) var<storage, read> points0: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> points1: array<vec4<f32>>;
// Per tetrahedron TET_WORDS words (tetray_scene::WalkTet): the XOR of its
// point indices, then across the face opposite the vertex of each rank
// (the place of its point index among the four, ascending) the neighbour,
// NO_NEIGHBOR or FINAL_EXIT.
@group(0) @binding(4) var<storage, read> tets0: array<u32>;
@group(0) @binding(5) var<storage, read> tets1: array<u32>;
// BVH nodes (two entries each: min.xyz + index, max.xyz + count, floats as
// bits), then primitives (three point indices + boundary face), then per
// boundary face its tetrahedron << 2 | local face, four to an entry, then
// the left-out cells.
@group(0) @binding(6) var<storage, read> bvh: array<vec4<u32>>;
// Transfer-function intervals (5 entries each), then the pre-integration
// table (2 entries per (front, back) pair).
@group(0) @binding(7) var<storage, read> tables: array<vec4<f32>>;
@group(0) @binding(8) var psi_table: texture_2d<f32>;
// Premultiplied RGBA per pixel of the whole image.
@group(0) @binding(9) var<storage, read_write> image: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read_write> stats: array<atomic<u32>, STAT_COUNT>;

fn point_at(i: u32) -> vec4<f32> {
    if (i < params.point_chunk) {
        return points0[i];
    }
    return points1[i - params.point_chunk];
}

const TET_WORDS: u32 = 5u;

// Word `w` of tetrahedron `t`'s record.
fn tet_word(t: u32, w: u32) -> u32 {
    if (t < params.tet_chunk) {
        return tets0[TET_WORDS * t + w];
    }
    return tets1[TET_WORDS * (t - params.tet_chunk) + w];
}

// The XOR of tetrahedron `t`'s point indices.
fn tet_xor(t: u32) -> u32 {
    return tet_word(t, 0u);
}

// Across the face of tetrahedron `t` opposite its vertex of rank `rank`.
fn tet_next(t: u32, rank: u32) -> u32 {
    return tet_word(t, 1u + rank);
}

// Adds `value` to a 64-bit counter kept as two words.
fn add_wide(lo: u32, hi: u32, value: u32) {
    if (value == 0u) {
        return;
    }
    let old = atomicAdd(&stats[lo], value);
    if (old > 0xffffffffu - value) {
        atomicAdd(&stats[hi], 1u);
    }
}
