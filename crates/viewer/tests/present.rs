//! The display pass: its WGSL validates, its parameter struct matches the
//! host's, and on the GPU it writes what its CPU twin computes, in every
//! display mode and with the preview standing in for unfinished rows.

mod support;

use std::mem::{offset_of, size_of};

use glam::Vec3;
use tetray_gpu::{GpuContext, GpuTarget};
use tetray_viewer::present::{
    Display, DisplayTexture, PRESENT_WGSL, PresentParams, Presenter, Sources, present_image,
    read_texture,
};

#[test]
fn the_shader_validates_and_its_params_match_the_host_struct() {
    let module = naga::front::wgsl::parse_str(PRESENT_WGSL).expect("present.wgsl parses");
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .expect("present.wgsl validates");
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("PresentParams"))
        .expect("PresentParams");
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("PresentParams is not a struct");
    };
    let wgsl: Vec<(String, u32)> = members
        .iter()
        .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
        .collect();
    macro_rules! offsets {
        ($($field:ident),*) => {
            vec![$((stringify!($field).to_string(), offset_of!(PresentParams, $field) as u32)),*]
        };
    }
    let rust = offsets!(
        width,
        height,
        preview_width,
        preview_height,
        rows_done,
        mode,
        divider,
        pad,
        background,
        diff_scale
    );
    assert_eq!(wgsl, rust);
    assert_eq!(*span as usize, size_of::<PresentParams>());
}

/// Deterministic pixels with every kind of value the display meets:
/// transparent, opaque, over-bright (clamped), premultiplied.
fn pixels(n: usize, seed: u32) -> Vec<[f32; 4]> {
    let mut state = seed.wrapping_mul(2_654_435_761).wrapping_add(1);
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        (state % 10_000) as f32 / 10_000.0
    };
    (0..n)
        .map(|_| {
            let a = next();
            [next() * a * 1.2, next() * a, next() * a, a]
        })
        .collect()
}

#[test]
fn the_gpu_pass_matches_its_cpu_twin() {
    if !support::gpu_or_skip() {
        return;
    }
    let ctx = GpuContext::new().expect("adapter");
    let presenter = Presenter::new(&ctx);
    let (w, h) = (37u32, 23u32);
    let (pw, ph) = (9u32, 6u32);
    let full: Vec<Vec<[f32; 4]>> = (0..2).map(|s| pixels((w * h) as usize, s)).collect();
    let preview: Vec<Vec<[f32; 4]>> = (2..4).map(|s| pixels((pw * ph) as usize, s)).collect();
    let upload = |data: &[[f32; 4]], width: u32, height: u32| {
        let target = GpuTarget::new(&ctx, width, height).expect("target");
        ctx.queue
            .write_buffer(target.image(), 0, bytemuck::cast_slice(data));
        target
    };
    let targets = [
        upload(&full[0], w, h),
        upload(&full[1], w, h),
        upload(&preview[0], pw, ph),
        upload(&preview[1], pw, ph),
    ];
    let output = DisplayTexture::new(&ctx, w, h);
    let sources = Sources {
        full_a: &full[0],
        full_b: &full[1],
        preview_a: &preview[0],
        preview_b: &preview[1],
    };
    for (display, rows_done) in [
        (Display::Single, h),
        (Display::Single, 10),
        (Display::Divider, 0),
        (Display::Divider, 17),
        (Display::Difference, 5),
        (Display::Difference, h),
    ] {
        let params = PresentParams::new(
            (w, h),
            (pw, ph),
            rows_done,
            display,
            14,
            Vec3::new(0.1, 0.3, 0.9),
            0.25,
        );
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let [a, b, c, d] = &targets;
        presenter.encode(&ctx, &mut encoder, &params, [a, b, c, d], &output);
        ctx.queue.submit([encoder.finish()]);
        let gpu = read_texture(&ctx, &output).expect("read back");
        let twin = present_image(&params, &sources);
        // The 8-bit conversion may round either way at .5: one level.
        let worst = gpu
            .iter()
            .zip(&twin)
            .flat_map(|(g, t)| (0..4).map(move |c| g[c].abs_diff(t[c])))
            .max()
            .unwrap_or(0);
        assert!(worst <= 1, "{display:?} rows {rows_done}: off by {worst}");
    }
}
