// Balanced cell projection (dissertation sections 4.1-4.2) with adaptive
// transfer-function sampling (section 4.3). CPU twin:
// tetray_project::twin.
//
// One instance per draw (a tetrahedron, or one knot-interval piece of it);
// its four corners are shared by the four faces (an index pattern), back
// faces are culled, so each pixel inside the cell's projection gets one
// fragment, from the face the pixel's ray enters through.
//
// The vertex stage finds, for its corner, where the ray from the eye
// through it leaves through the opposite face's plane: the distance d
// along the view ray and the scalar s_b there (INTERSECTBACKFACE). The
// other three planes contain the corner, so their hits are the corner
// itself. Per plane j the stage outputs its hit as functions the
// rasterizer interpolates exactly, linearly in screen space
// (@interpolate(linear)): perspective 1 / z_j and s_j / z_j (both affine in
// the pixel position for a plane and a linear field), orthographic z_j and
// s_j; z is depth along the view direction. `opposite` marks the plane
// opposite the corner (Moreland's d vector without its values): over a
// face, the face's own plane has it zero at every corner, so the fragment
// never takes the entry plane for the exit.
//
// The fragment stage takes the nearest plane beyond the entry (the
// smallest positive distance), turns depths into the world length along
// its pixel's ray, clips the segment to its draw's knot interval, and
// integrates it with integrate.wgsl's segment_light, as the ray caster.

// Saturation of divisions by a plane parallel to the ray.
const BIG: f32 = 1e30;

struct Fragment {
    @builtin(position) clip: vec4<f32>,
    // The corner's own hit, (1/z, s/z) or (z, s): over a face, the entry.
    @location(0) @interpolate(linear) entry: vec2<f32>,
    // Per face plane j: 1/z_j or z_j ...
    @location(1) @interpolate(linear) plane_a: vec4<f32>,
    // ... and s_j / z_j or s_j.
    @location(2) @interpolate(linear) plane_b: vec4<f32>,
    @location(3) @interpolate(linear) opposite: vec4<f32>,
    @location(4) @interpolate(flat) clip_code: u32,
    // The cell's depth range and scalar range, (z_min, z_max, s_min,
    // s_max): the segment lies in the cell, so within both. A pixel centre
    // the rasterizer puts just outside the cell's exact projection, or a
    // plane nearly parallel to the rays (saturated at BIG, then
    // interpolated), can put the exit plane far behind the cell; the clamp
    // bounds such a segment by the cell's own thickness.
    @location(5) @interpolate(flat) bounds: vec4<f32>,
}

// num / den, saturated at +-BIG where den is (nearly) zero.
fn ratio(num: f32, den: f32) -> f32 {
    if (abs(num) < BIG * abs(den)) {
        return num / den;
    }
    return select(-BIG, BIG, (num >= 0.0) == (den >= 0.0));
}

@vertex
fn vs_main(@builtin(vertex_index) corner: u32, @location(0) draw: vec2<u32>) -> Fragment {
    let v = tets[draw.x];
    let q0 = points[v.x];
    let q1 = points[v.y];
    let q2 = points[v.z];
    let q3 = points[v.w];
    // This corner and the three of the face opposite it (in any order: the
    // results below do not change under a permutation of a, b, c).
    var me = q0;
    var a = q1;
    var b = q2;
    var c = q3;
    if (corner == 1u) {
        me = q1;
        a = q0;
    } else if (corner == 2u) {
        me = q2;
        a = q0;
        b = q1;
    } else if (corner == 3u) {
        me = q3;
        a = q0;
        b = q1;
        c = q2;
    }
    let p = me.xyz;
    let rel = p - params.view.position;
    let z = dot(rel, params.view.direction);
    let sx = dot(rel, params.view.right) / (params.view.pixel * params.view.half_width);
    let sy = dot(rel, params.view.up) / (params.view.pixel * params.view.half_height);
    let ortho = params.view.orthographic == 1u;
    // The view ray through the corner (length irrelevant below).
    let ray = select(rel, params.view.direction, ortho);
    // INTERSECTBACKFACE: the ray me + lambda ray meets the opposite plane at
    // lambda = det / (n . ray), n = X + Y + Z its normal, and the linear
    // field there is s_me + (sum of (s_k - s_me) (K . ray)) / (n . ray).
    let ea = a.xyz - p;
    let eb = b.xyz - p;
    let ec = c.xyz - p;
    let cx = cross(eb, ec);
    let cy = cross(ec, ea);
    let cz = cross(ea, eb);
    let det = dot(ea, cx);
    let xr = dot(cx, ray);
    let yr = dot(cy, ray);
    let zr = dot(cz, ray);
    let nr = xr + yr + zr;
    let sr = (a.w - me.w) * xr + (b.w - me.w) * yr + (c.w - me.w) * zr;
    var out: Fragment;
    var own: vec2<f32>;
    var far: vec2<f32>;
    if (ortho) {
        out.clip = vec4<f32>(sx, sy, 0.5, 1.0);
        own = vec2<f32>(z, me.w);
        far = vec2<f32>(z + ratio(det, nr), me.w + ratio(sr, nr));
    } else {
        // Depth 0.5 w keeps every point in front of the eye inside the
        // clip volume: no near or far plane.
        out.clip = vec4<f32>(sx, sy, 0.5 * z, z);
        // z_exit = z (1 + lambda), s_exit as above, both over z_exit.
        let den = z * (nr + det);
        own = vec2<f32>(1.0 / z, me.w / z);
        far = vec2<f32>(ratio(nr, den), ratio(me.w * nr + sr, den));
    }
    let is_far = vec4<bool>(corner == 0u, corner == 1u, corner == 2u, corner == 3u);
    out.entry = own;
    out.plane_a = select(vec4<f32>(own.x), vec4<f32>(far.x), is_far);
    out.plane_b = select(vec4<f32>(own.y), vec4<f32>(far.y), is_far);
    out.opposite = select(vec4<f32>(0.0), vec4<f32>(1.0), is_far);
    out.clip_code = draw.y;
    let depths = vec4<f32>(
        dot(q0.xyz - params.view.position, params.view.direction),
        dot(q1.xyz - params.view.position, params.view.direction),
        dot(q2.xyz - params.view.position, params.view.direction),
        dot(q3.xyz - params.view.position, params.view.direction),
    );
    let scalars = vec4<f32>(q0.w, q1.w, q2.w, q3.w);
    out.bounds = vec4<f32>(
        min(min(depths.x, depths.y), min(depths.z, depths.w)),
        max(max(depths.x, depths.y), max(depths.z, depths.w)),
        min(min(scalars.x, scalars.y), min(scalars.z, scalars.w)),
        max(max(scalars.x, scalars.y), max(scalars.z, scalars.w)),
    );
    return out;
}

@fragment
fn fs_main(f: Fragment) -> @location(0) vec4<f32> {
    var z_in: f32;
    var s_in: f32;
    var z_out: f32;
    var s_out: f32;
    var scale = 1.0;
    if (params.view.orthographic == 1u) {
        z_in = f.entry.x;
        s_in = f.entry.y;
        var best = BIG;
        var best_s = 0.0;
        for (var j = 0; j < 4; j++) {
            let zj = f.plane_a[j];
            if (f.opposite[j] > 0.0 && zj > z_in && zj < best) {
                best = zj;
                best_s = f.plane_b[j];
            }
        }
        if (best >= BIG) {
            discard;
        }
        z_out = best;
        s_out = best_s;
    } else {
        // Depth order is reverse order of 1/z (all positive here).
        let a_in = f.entry.x;
        var best = 0.0;
        var best_b = 0.0;
        for (var j = 0; j < 4; j++) {
            let aj = f.plane_a[j];
            if (f.opposite[j] > 0.0 && aj < a_in && aj > best) {
                best = aj;
                best_b = f.plane_b[j];
            }
        }
        if (!(best > 0.0)) {
            discard;
        }
        z_in = 1.0 / a_in;
        s_in = f.entry.y / a_in;
        z_out = 1.0 / best;
        s_out = best_b / best;
        // World length per unit depth along this pixel's ray.
        let x = (f.clip.x - params.view.half_width) * params.view.pixel;
        let y = (params.view.half_height - f.clip.y) * params.view.pixel;
        scale = length(params.view.direction + params.view.right * x + params.view.up * y);
    }
    z_in = max(z_in, f.bounds.x);
    z_out = min(z_out, f.bounds.y);
    s_in = clamp(s_in, f.bounds.z, f.bounds.w);
    s_out = clamp(s_out, f.bounds.z, f.bounds.w);
    let length = (z_out - z_in) * scale;
    if (!(length > 0.0)) {
        discard;
    }
    var light: Light;
    if (f.clip_code == NO_CLIP) {
        light = segment_light(sample_at(s_in), sample_at(s_out), length);
    } else {
        // Section 4.3's clip of the segment to knot interval k, in the
        // fraction t of the segment (the scalar is linear along it).
        let k = i32(f.clip_code) - 1;
        let span = s_out - s_in;
        var t_front = 0.0;
        var t_back = 1.0;
        var s_front = s_in;
        var s_back = s_out;
        if (span == 0.0) {
            if (interval_up(s_in) != k) {
                discard;
            }
        } else {
            if (k >= 0) {
                let lo = knot_scalar(u32(k));
                let t = (lo - s_in) / span;
                if (span > 0.0 && t > t_front) {
                    t_front = t;
                    s_front = lo;
                } else if (span < 0.0 && t < t_back) {
                    t_back = t;
                    s_back = lo;
                }
            }
            if (k + 1 < i32(params.integrator.knot_count)) {
                let hi = knot_scalar(u32(k + 1));
                let t = (hi - s_in) / span;
                if (span > 0.0 && t < t_back) {
                    t_back = t;
                    s_back = hi;
                } else if (span < 0.0 && t > t_front) {
                    t_front = t;
                    s_front = hi;
                }
            }
        }
        let piece = length * (t_back - t_front);
        if (!(piece > 0.0)) {
            discard;
        }
        light = segment_light(in_interval(k, s_front), in_interval(k, s_back), piece);
    }
    atomicAdd(&stats[STAT_SEGMENTS], 1u);
    // Premultiplied: emitted light, alpha = 1 - transmittance (grey).
    return vec4<f32>(light.emitted, 1.0 - light.transmittance.x);
}
