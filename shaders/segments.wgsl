// Single segments through the integration methods, for the accuracy study
// (host: tetray_study::gpu_segments). One invocation per segment builds
// grey samples from the segment's end values and calls piece_light of
// integrate.wgsl, the function the ray-casting kernel integrates every
// piece with. Concatenated after common.wgsl and integrate.wgsl.

// Per segment two entries: (lum_back, lum_front, q_back, q_front), then
// (length, 0, 0, 0); q is the attenuation per unit length, or for the
// opacity methods the opacity of one unit distance.
@group(0) @binding(11) var<storage, read> segment_inputs: array<vec4<f32>>;
// Per segment: (emitted light, transmittance).
@group(0) @binding(12) var<storage, read_write> segment_outputs: array<vec2<f32>>;

@compute @workgroup_size(64)
fn segments(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&segment_outputs)) {
        return;
    }
    let ends = segment_inputs[2u * i];
    let length = segment_inputs[2u * i + 1u].x;
    let front = Sample(vec3<f32>(ends.y), vec3<f32>(ends.w), 1.0, 0);
    let back = Sample(vec3<f32>(ends.x), vec3<f32>(ends.z), 0.0, 0);
    let light = piece_light(front, back, length);
    segment_outputs[i] = vec2<f32>(light.emitted.x, light.transmittance.x);
}
