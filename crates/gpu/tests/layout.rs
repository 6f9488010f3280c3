//! Host structs match naga's layout of the WGSL structs they are uploaded
//! into: every member's offset and the struct size.

use std::mem::{offset_of, size_of};

use tetray_gpu::layout::{IntegratorParams, Params, Tile, ViewParams};
use tetray_gpu::shaders::raycast_source;

/// (member name, offset) of WGSL struct `name`, and its size.
fn wgsl_layout(module: &naga::Module, name: &str) -> (Vec<(String, u32)>, u32) {
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no WGSL struct {name}"));
    match &ty.inner {
        naga::TypeInner::Struct { members, span } => (
            members
                .iter()
                .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                .collect(),
            *span,
        ),
        other => panic!("{name} is not a struct: {other:?}"),
    }
}

fn module() -> naga::Module {
    naga::front::wgsl::parse_str(&raycast_source()).expect("the kernel parses")
}

macro_rules! rust_offsets {
    ($ty:ty, $($field:ident),* $(,)?) => {
        vec![$((stringify!($field).to_string(), offset_of!($ty, $field) as u32)),*]
    };
}

#[test]
fn params_match_the_wgsl_struct() {
    let (members, span) = wgsl_layout(&module(), "Params");
    let rust = rust_offsets!(
        Params,
        view,
        bounds_min,
        eye_inside,
        bounds_max,
        scene_abs_max,
        width,
        height,
        max_steps,
        stop_below_sum,
        integrator,
        tet_chunk,
        point_chunk,
        prim_offset,
        face_offset,
        overlap_offset,
        overlap_count,
    );
    assert_eq!(members, rust, "member names and offsets");
    assert_eq!(span as usize, size_of::<Params>());
}

#[test]
fn the_shared_blocks_match_the_wgsl_structs() {
    let module = module();
    let (members, span) = wgsl_layout(&module, "ViewParams");
    let rust = rust_offsets!(
        ViewParams,
        position,
        orthographic,
        right,
        pixel,
        up,
        half_width,
        direction,
        half_height,
    );
    assert_eq!(members, rust, "ViewParams member names and offsets");
    assert_eq!(span as usize, size_of::<ViewParams>());
    let (members, span) = wgsl_layout(&module, "IntegratorParams");
    let rust = rust_offsets!(
        IntegratorParams,
        method,
        grey,
        split,
        knot_count,
        psi_size,
        inv_unit_distance,
        riemann_step,
        preint_size,
        preint_offset,
        preint_lo,
        preint_scale,
        preint_length,
    );
    assert_eq!(members, rust, "IntegratorParams member names and offsets");
    assert_eq!(span as usize, size_of::<IntegratorParams>());
}

/// The kernel's method constants are the ones the host uploads.
#[test]
fn method_constants_are_the_hosts_codes() {
    let module = module();
    for method in tetray_integrate::Method::ALL {
        let Some(code) = method.gpu_code() else {
            continue;
        };
        let name = format!("METHOD_{}", method.name().to_uppercase().replace('-', "_"));
        let (_, constant) = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name.as_str()))
            .unwrap_or_else(|| panic!("no WGSL constant {name}"));
        let value = &module.global_expressions[constant.init];
        assert_eq!(
            *value,
            naga::Expression::Literal(naga::Literal::U32(code)),
            "{name}"
        );
    }
}

#[test]
fn tile_matches_the_wgsl_struct() {
    let (members, span) = wgsl_layout(&module(), "Tile");
    assert_eq!(members, rust_offsets!(Tile, x0, y0, width, height));
    assert_eq!(span as usize, size_of::<Tile>());
}

#[test]
fn bvh_records_are_the_kernel_entries() {
    // FlatNode is two vec4<u32> (min.xyz + index, max.xyz + count), FlatPrim
    // one: the kernel reads them by those offsets.
    use tetray_boundary_bvh::{FlatNode, FlatPrim};
    assert_eq!(size_of::<FlatNode>(), 32);
    assert_eq!(offset_of!(FlatNode, index), 12);
    assert_eq!(offset_of!(FlatNode, count), 28);
    assert_eq!(size_of::<FlatPrim>(), 16);
    assert_eq!(offset_of!(FlatPrim, face), 12);
}

/// No shader binds a uniform buffer. Lavapipe (Mesa's Vulkan on the CPU,
/// what CI runs) specializes a shader on the values of the uniform
/// buffers it reads at every dispatch or draw whose bindings changed: about
/// 30 ms for the ray caster each time, which made every frame and every
/// viewer batch cost 30 ms whatever its size. Parameters are read-only
/// storage buffers instead.
#[test]
fn no_shader_binds_a_uniform_buffer() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders");
    let mut checked = 0;
    for entry in std::fs::read_dir(&dir).expect("the shaders folder") {
        let path = entry.expect("an entry").path();
        if path.extension().and_then(|e| e.to_str()) != Some("wgsl") {
            continue;
        }
        let source = std::fs::read_to_string(&path).expect("read a shader");
        for (i, line) in source.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            assert!(
                !code.contains("var<uniform>"),
                "{}:{}: {line}",
                path.display(),
                i + 1
            );
        }
        checked += 1;
    }
    assert!(
        checked >= 8,
        "only {checked} shaders found in {}",
        dir.display()
    );
}
