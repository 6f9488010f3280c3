// The viewer's display pass: the ray caster's float images (premultiplied
// RGBA, vec4<f32> per pixel) to the rgba8unorm texture egui draws. Rows at
// and below `rows_done` are still being refined and come from the preview
// (nearest pixel). One invocation per display pixel; the CPU twin is
// crates/viewer/src/present.rs (`present_pixel`).

struct PresentParams {
    width: u32,
    height: u32,
    preview_width: u32,
    preview_height: u32,
    rows_done: u32,
    mode: u32,
    divider: u32,
    pad: u32,
    background: vec3<f32>,
    diff_scale: f32,
}

const MODE_SINGLE: u32 = 0u;
const MODE_DIVIDER: u32 = 1u;
const MODE_DIFFERENCE: u32 = 2u;

// Read-only storage, not uniform: see common.wgsl (lavapipe specializes
// shaders on uniform values at every bind).
@group(0) @binding(0) var<storage, read> params: PresentParams;
@group(0) @binding(1) var<storage, read> full_a: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> full_b: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> preview_a: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> preview_b: array<vec4<f32>>;
@group(0) @binding(5) var output: texture_storage_2d<rgba8unorm, write>;

// Index of display pixel (x, y) in the preview.
fn preview_index(x: u32, y: u32) -> u32 {
    let px = x * params.preview_width / params.width;
    let py = y * params.preview_height / params.height;
    return py * params.preview_width + px;
}

fn pixel_a(x: u32, y: u32) -> vec4<f32> {
    if y < params.rows_done {
        return full_a[y * params.width + x];
    }
    return preview_a[preview_index(x, y)];
}

fn pixel_b(x: u32, y: u32) -> vec4<f32> {
    if y < params.rows_done {
        return full_b[y * params.width + x];
    }
    return preview_b[preview_index(x, y)];
}

// Premultiplied colour over the opaque background (as the PNG writer does).
fn over(c: vec4<f32>) -> vec3<f32> {
    return c.rgb + (1.0 - c.a) * params.background;
}

// The difference colour map at t in [0, 1]: black, purple, red, orange,
// yellow, white (five equal pieces; `heat` in present.rs).
fn heat(t: f32) -> vec3<f32> {
    let stops = array<vec3<f32>, 6>(
        vec3<f32>(0.0, 0.0, 0.0),
        vec3<f32>(0.35, 0.05, 0.55),
        vec3<f32>(0.85, 0.1, 0.25),
        vec3<f32>(1.0, 0.5, 0.0),
        vec3<f32>(1.0, 0.9, 0.1),
        vec3<f32>(1.0, 1.0, 1.0),
    );
    let u = clamp(t, 0.0, 1.0) * 5.0;
    let k = min(u32(u), 4u);
    let f = u - f32(k);
    var lo = stops[0];
    var hi = stops[1];
    // Constant indices only (a dynamically indexed local array would
    // spill on some drivers).
    for (var i = 1u; i <= 4u; i++) {
        if i == k {
            lo = stops[i];
            hi = stops[i + 1u];
        }
    }
    return mix(lo, hi, f);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let x = id.x;
    let y = id.y;
    if x >= params.width || y >= params.height {
        return;
    }
    var rgb: vec3<f32>;
    switch params.mode {
        case MODE_DIVIDER: {
            if x < params.divider {
                rgb = over(pixel_a(x, y));
            } else {
                rgb = over(pixel_b(x, y));
            }
        }
        case MODE_DIFFERENCE: {
            let d = abs(pixel_a(x, y).rgb - pixel_b(x, y).rgb);
            rgb = heat(max(d.r, max(d.g, d.b)) / params.diff_scale);
        }
        default: {
            rgb = over(pixel_a(x, y));
        }
    }
    textureStore(output, vec2<i32>(i32(x), i32(y)), vec4<f32>(clamp(rgb, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0));
}
