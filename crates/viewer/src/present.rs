//! The display pass (shaders/present.wgsl): the ray caster's float images,
//! still on the GPU, composited into the rgba8 texture that egui draws, with
//! the preview standing in for rows not yet refined, a divider between two
//! methods or their difference. [`present_pixel`] is its CPU twin, used for
//! PNG screenshots and to test the kernel.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use tetray_gpu::{GpuContext, GpuTarget};

/// The WGSL source, embedded.
pub const PRESENT_WGSL: &str = include_str!("../../../shaders/present.wgsl");

/// Display pixels per workgroup side.
const WORKGROUP: u32 = 8;

/// How the two views are shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Display {
    /// View A alone.
    #[default]
    Single,
    /// A left of the divider, B right of it.
    Divider,
    /// max over RGB of |A - B| (premultiplied), colour-mapped.
    Difference,
}

impl Display {
    fn code(self) -> u32 {
        match self {
            Display::Single => 0,
            Display::Divider => 1,
            Display::Difference => 2,
        }
    }
}

/// WGSL `PresentParams`.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct PresentParams {
    pub width: u32,
    pub height: u32,
    pub preview_width: u32,
    pub preview_height: u32,
    /// Rows from the top that hold the refined image.
    pub rows_done: u32,
    pub mode: u32,
    /// First display column that shows B (divider mode).
    pub divider: u32,
    pub pad: u32,
    pub background: [f32; 3],
    /// Difference mapped to the top of the colour bar.
    pub diff_scale: f32,
}

impl PresentParams {
    pub fn new(
        (width, height): (u32, u32),
        (preview_width, preview_height): (u32, u32),
        rows_done: u32,
        display: Display,
        divider: u32,
        background: Vec3,
        diff_scale: f32,
    ) -> PresentParams {
        PresentParams {
            width,
            height,
            preview_width: preview_width.max(1),
            preview_height: preview_height.max(1),
            rows_done,
            mode: display.code(),
            divider,
            pad: 0,
            background: background.to_array(),
            diff_scale: diff_scale.max(f32::MIN_POSITIVE),
        }
    }
}

/// The colour map of the difference view at `t` in [0, 1] (WGSL `heat`).
pub fn heat(t: f32) -> Vec3 {
    const STOPS: [[f32; 3]; 6] = [
        [0.0, 0.0, 0.0],
        [0.35, 0.05, 0.55],
        [0.85, 0.1, 0.25],
        [1.0, 0.5, 0.0],
        [1.0, 0.9, 0.1],
        [1.0, 1.0, 1.0],
    ];
    let u = t.clamp(0.0, 1.0) * 5.0;
    let k = (u as usize).min(4);
    let f = u - k as f32;
    Vec3::from(STOPS[k]).lerp(Vec3::from(STOPS[k + 1]), f)
}

/// The four images the pass reads: refined and preview, of A and B.
pub struct Sources<'a> {
    pub full_a: &'a [[f32; 4]],
    pub full_b: &'a [[f32; 4]],
    pub preview_a: &'a [[f32; 4]],
    pub preview_b: &'a [[f32; 4]],
}

/// CPU twin of the kernel: display pixel (x, y), before the conversion to
/// 8 bits (clamped to [0, 1]).
pub fn present_pixel(p: &PresentParams, src: &Sources<'_>, x: u32, y: u32) -> Vec3 {
    let preview = |x: u32, y: u32| {
        let px = x * p.preview_width / p.width;
        let py = y * p.preview_height / p.height;
        (py * p.preview_width + px) as usize
    };
    let fetch = |full: &[[f32; 4]], prev: &[[f32; 4]]| {
        if y < p.rows_done {
            full[(y * p.width + x) as usize]
        } else {
            prev[preview(x, y)]
        }
    };
    let background = Vec3::from(p.background);
    let over = |c: [f32; 4]| Vec3::new(c[0], c[1], c[2]) + (1.0 - c[3]) * background;
    let rgb = match p.mode {
        1 if x >= p.divider => over(fetch(src.full_b, src.preview_b)),
        2 => {
            let (a, b) = (
                fetch(src.full_a, src.preview_a),
                fetch(src.full_b, src.preview_b),
            );
            let d = (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max);
            heat(d / p.diff_scale)
        }
        _ => over(fetch(src.full_a, src.preview_a)),
    };
    rgb.clamp(Vec3::ZERO, Vec3::ONE)
}

/// The whole display as 8-bit RGBA (opaque), row 0 at the top.
pub fn present_image(p: &PresentParams, src: &Sources<'_>) -> Vec<[u8; 4]> {
    let mut out = Vec::with_capacity((p.width * p.height) as usize);
    for y in 0..p.height {
        for x in 0..p.width {
            let rgb = present_pixel(p, src, x, y);
            let [r, g, b] = rgb.to_array().map(|v| (v * 255.0).round() as u8);
            out.push([r, g, b, 255]);
        }
    }
    out
}

/// The compiled display pass.
pub struct Presenter {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// The texture egui shows, at the display size of the views.
pub struct DisplayTexture {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl DisplayTexture {
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> DisplayTexture {
        let texture = ctx.device.create_texture(&tetray_gpu::texture_2d(
            "viewer display",
            (width, height),
            // egui-wgpu's native textures are Rgba8Unorm, read as sRGB-encoded
            // values: the bytes on screen are the bytes a PNG would hold.
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        ));
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        DisplayTexture { texture, view }
    }

    pub fn size(&self) -> (u32, u32) {
        (self.texture.width(), self.texture.height())
    }
}

impl Presenter {
    pub fn new(ctx: &GpuContext) -> Presenter {
        let device = &ctx.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("present.wgsl"),
            source: wgpu::ShaderSource::Wgsl(PRESENT_WGSL.into()),
        });
        let storage = |binding: u32| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("present bindings"),
            entries: &[
                storage(0),
                storage(1),
                storage(2),
                storage(3),
                storage(4),
                wgpu::BindGroupLayoutEntry {
                    binding: 5,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: wgpu::TextureFormat::Rgba8Unorm,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("present"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("present"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        Presenter { pipeline, layout }
    }

    /// Encodes the pass writing `output` from the four targets (B may be A
    /// when there is one view).
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        params: &PresentParams,
        targets: [&GpuTarget; 4],
        output: &DisplayTexture,
    ) {
        use wgpu::util::DeviceExt;
        let uniform = ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("present params"),
                contents: bytemuck::bytes_of(params),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let [full_a, full_b, preview_a, preview_b] = targets;
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("present"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                image_entry(1, full_a),
                image_entry(2, full_b),
                image_entry(3, preview_a),
                image_entry(4, preview_b),
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::TextureView(&output.view),
                },
            ],
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("present"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(
            params.width.div_ceil(WORKGROUP),
            params.height.div_ceil(WORKGROUP),
            1,
        );
    }
}

fn image_entry(binding: u32, target: &GpuTarget) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: target.image().as_entire_binding(),
    }
}

/// Reads a display texture back (screenshots and tests; not per frame).
pub fn read_texture(ctx: &GpuContext, texture: &DisplayTexture) -> anyhow::Result<Vec<[u8; 4]>> {
    let (width, height) = texture.size();
    let row_bytes = width * 4;
    let padded =
        row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = tetray_gpu::readback::readback_buffer(
        ctx,
        "display readback",
        u64::from(padded) * u64::from(height),
    );
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    ctx.queue.submit([encoder.finish()]);
    let bytes = crate::gpu_io::map_read(ctx, &buffer)?;
    let mut out = Vec::with_capacity((width * height) as usize);
    for row in bytes.chunks(padded as usize) {
        out.extend(
            row[..row_bytes as usize]
                .chunks_exact(4)
                .map(|p| [p[0], p[1], p[2], p[3]]),
        );
    }
    Ok(out)
}
