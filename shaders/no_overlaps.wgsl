// The kernel of a scene with no cells left out of the walk: the overlap
// lists of overlaps.wgsl are not there (a GPU reserves their private
// memory in every invocation, used or not), and their calls fold away
// (tetray_gpu::shaders::raycast_source_without_overlaps).

const hole_count: u32 = 0u;

fn find_holes(ray: Ray) -> u32 {
    return 0u;
}

fn holes_beyond(t: f32) -> bool {
    return false;
}

struct Filled {
    segments: u32,
    opaque: bool,
}

fn fill_gap(start: f32, end: f32, color: ptr<function, vec3<f32>>, trans: ptr<function, vec3<f32>>) -> Filled {
    return Filled(0u, false);
}
