//! The projection module parses and validates with naga (so a broken shader
//! fails `cargo test`, not a user's run), and the host `Params` matches
//! naga's layout of the WGSL struct, member by member.

use std::mem::{offset_of, size_of};

use tetray_project::layout::Params;
use tetray_project::shaders::project_source;

fn module() -> naga::Module {
    let source = project_source();
    naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("WGSL parse error:\n{}", e.emit_to_string(&source)))
}

#[test]
fn projection_module_validates() {
    let source = project_source();
    let module = module();
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    );
    validator
        .validate(&module)
        .unwrap_or_else(|e| panic!("WGSL validation error:\n{}", e.emit_to_string(&source)));
    let stages: Vec<_> = module
        .entry_points
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    assert!(
        stages.contains(&"vs_main") && stages.contains(&"fs_main"),
        "{stages:?}"
    );
}

macro_rules! rust_offsets {
    ($ty:ty, $($field:ident),* $(,)?) => {
        vec![$((stringify!($field).to_string(), offset_of!($ty, $field) as u32)),*]
    };
}

#[test]
fn params_match_the_wgsl_struct() {
    let module = module();
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Params"))
        .expect("WGSL struct Params");
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("Params is not a struct");
    };
    let wgsl: Vec<(String, u32)> = members
        .iter()
        .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
        .collect();
    // The blocks themselves are the ray caster's (tetray_gpu's layout test
    // checks them member by member).
    let rust = rust_offsets!(Params, view, integrator);
    assert_eq!(wgsl, rust, "member names and offsets");
    assert_eq!(*span as usize, size_of::<Params>());
}
