//! The WGSL kernel parses and validates with naga, so a broken shader fails
//! `cargo test`, not a user's run.

use tetray_gpu::shaders::{raycast_source, raycast_source_without_overlaps};

#[test]
fn raycast_kernel_validates() {
    validates(&raycast_source());
    validates(&raycast_source_without_overlaps());
}

fn validates(source: &str) {
    let source = source.to_string();
    let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| {
        panic!("WGSL parse error:\n{}", e.emit_to_string(&source));
    });
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    );
    validator.validate(&module).unwrap_or_else(|e| {
        panic!("WGSL validation error:\n{}", e.emit_to_string(&source));
    });
    assert!(module.entry_points.iter().any(|e| e.name == "main"));
}
