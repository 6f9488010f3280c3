//! The projection on wgpu render pipelines: the mesh uploaded once, per
//! frame one instanced, indexed draw of the sorted pieces into a float
//! target with premultiplied back-to-front "over" blending, timed with
//! timestamp queries where the adapter has them, and read back.

use std::time::Duration;

use tetray_core::Image;
use tetray_gpu::readback::{PassTimestamps, read_buffer, readback_buffer};
use tetray_gpu::{GpuContext, GpuIntegrator};
use wgpu::util::DeviceExt;

use crate::ProjectError;
use crate::layout::{Params, STAT_COUNT, STAT_SEGMENTS};
use crate::scene::{FACE_VERTS, ProjectScene};
use crate::shaders::project_source;
use crate::view::View;

/// A mesh on the GPU: points and oriented tetrahedra.
pub struct GpuProjectScene {
    points: wgpu::Buffer,
    tets: wgpu::Buffer,
    tet_count: usize,
    bytes: u64,
}

impl GpuProjectScene {
    pub fn upload(ctx: &GpuContext, scene: &ProjectScene) -> Result<GpuProjectScene, ProjectError> {
        ctx.check()?;
        let limit = ctx
            .limits
            .max_storage_buffer_binding_size
            .min(ctx.limits.max_buffer_size);
        let points = storage(ctx, "points", &scene.points, limit)?;
        let tets = storage(ctx, "tetrahedra", &scene.tets, limit)?;
        Ok(GpuProjectScene {
            bytes: points.size() + tets.size(),
            points,
            tets,
            tet_count: scene.tet_count(),
        })
    }

    pub fn tet_count(&self) -> usize {
        self.tet_count
    }

    /// Bytes of mesh data on the GPU.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }
}

fn storage<T: bytemuck::Pod>(
    ctx: &GpuContext,
    what: &'static str,
    items: &[T],
    limit: u64,
) -> Result<wgpu::Buffer, ProjectError> {
    let bytes = std::mem::size_of_val(items) as u64;
    if bytes > limit {
        return Err(ProjectError::TooLarge { what, bytes, limit });
    }
    let mut data = bytemuck::cast_slice::<T, u8>(items).to_vec();
    data.resize(data.len().max(16), 0);
    Ok(ctx
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(what),
            contents: &data,
            usage: wgpu::BufferUsages::STORAGE,
        }))
}

/// What one draw pass reports.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DrawStats {
    /// Fragments integrated (a segment of a ray through one piece).
    pub segments: u64,
    /// The render pass by timestamp queries, when the adapter has them.
    pub gpu_time: Option<Duration>,
    /// Submission to completion, read-back excluded.
    pub wall_time: Duration,
}

/// The compiled pipeline.
pub struct GpuProjector {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    indices: wgpu::Buffer,
    format: wgpu::TextureFormat,
}

impl GpuProjector {
    pub fn new(ctx: &GpuContext) -> Result<GpuProjector, ProjectError> {
        let device = &ctx.device;
        // 32-bit float blending where the device has it; 16-bit float
        // (blendable everywhere) otherwise.
        let format = if device
            .features()
            .contains(wgpu::Features::FLOAT32_BLENDABLE)
        {
            wgpu::TextureFormat::Rgba32Float
        } else {
            wgpu::TextureFormat::Rgba16Float
        };
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("project.wgsl"),
            source: wgpu::ShaderSource::Wgsl(project_source().into()),
        });
        let buffer = |binding, visibility, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let read_only = wgpu::BufferBindingType::Storage { read_only: true };
        let (vertex, fragment) = (wgpu::ShaderStages::VERTEX, wgpu::ShaderStages::FRAGMENT);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("project bindings"),
            entries: &[
                buffer(0, vertex | fragment, read_only),
                buffer(1, vertex, read_only),
                buffer(2, vertex, read_only),
                buffer(3, fragment, read_only),
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: fragment,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                buffer(
                    5,
                    fragment,
                    wgpu::BufferBindingType::Storage { read_only: false },
                ),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("project"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        // Back-to-front "over" of premultiplied colour: C = C_src + (1 -
        // a_src) C_dst, and the same for alpha, so 1 - a multiplies the
        // transmittances.
        let over = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
            operation: wgpu::BlendOperation::Add,
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("project"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 8,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &[wgpu::VertexAttribute {
                        format: wgpu::VertexFormat::Uint32x2,
                        offset: 0,
                        shader_location: 0,
                    }],
                })],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                front_face: wgpu::FrontFace::Ccw,
                // A ray enters a cell through a face turned towards the eye.
                cull_mode: Some(wgpu::Face::Back),
                ..Default::default()
            },
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: Some(wgpu::BlendState {
                        color: over,
                        alpha: over,
                    }),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let pattern: Vec<u16> = FACE_VERTS.iter().flatten().map(|&v| v as u16).collect();
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("face corners"),
            contents: bytemuck::cast_slice(&pattern),
            usage: wgpu::BufferUsages::INDEX,
        });
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(ProjectError::Driver(error.to_string()));
        }
        Ok(GpuProjector {
            pipeline,
            layout,
            indices,
            format,
        })
    }

    /// The render target's format.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// Draws `draws` (back to front) and reads the image back.
    pub fn draw(
        &self,
        ctx: &GpuContext,
        scene: &GpuProjectScene,
        integrator: &GpuIntegrator,
        view: &View,
        draws: &[[u32; 2]],
    ) -> Result<(Image, DrawStats), ProjectError> {
        if !integrator.data().grey {
            return Err(ProjectError::ColouredAttenuation);
        }
        let (width, height) = (view.width, view.height);
        let side = ctx.limits.max_texture_dimension_2d;
        if width > side || height > side {
            return Err(ProjectError::ImageTooLarge {
                width,
                height,
                limit: side,
            });
        }
        let device = &ctx.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let params = Params::new(view, integrator.data());
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("project params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let stats = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("project stats"),
            contents: bytemuck::cast_slice(&[0u32; STAT_COUNT]),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        });
        let instances = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("draws"),
            contents: bytemuck::cast_slice(if draws.is_empty() {
                &[[0u32; 2]]
            } else {
                draws
            }),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("project"),
            layout: &self.layout,
            entries: &[
                entry(0, &params),
                entry(1, &scene.points),
                entry(2, &scene.tets),
                entry(3, integrator.tables_buffer()),
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(integrator.psi_view()),
                },
                entry(5, &stats),
            ],
        });
        let target = device.create_texture(&tetray_gpu::texture_2d(
            "project target",
            (width, height),
            self.format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        ));
        let target_view = target.create_view(&Default::default());
        let timestamps = ctx
            .timestamps
            .then(|| PassTimestamps::new(ctx, "project timestamps"));
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("project"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: timestamps
                    .as_ref()
                    .map(|t| wgpu::RenderPassTimestampWrites {
                        query_set: &t.set,
                        beginning_of_pass_write_index: Some(0),
                        end_of_pass_write_index: Some(1),
                    }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint16);
            pass.set_vertex_buffer(0, instances.slice(..));
            pass.draw_indexed(0..12, 0, 0..draws.len() as u32);
        }
        if let Some(t) = &timestamps {
            t.resolve(&mut encoder);
        }
        let texel = self.format.block_copy_size(None).unwrap_or(16);
        let row_bytes = (width * texel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let image_read =
            readback_buffer(ctx, "project image readback", u64::from(row_bytes * height));
        encoder.copy_texture_to_buffer(
            target.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &image_read,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row_bytes),
                    rows_per_image: Some(height),
                },
            },
            target.size(),
        );
        let stats_read = readback_buffer(ctx, "project stats readback", (STAT_COUNT * 4) as u64);
        encoder.copy_buffer_to_buffer(&stats, 0, &stats_read, 0, (STAT_COUNT * 4) as u64);
        let wall_time = ctx.submit_and_wait(encoder.finish())?;
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(ProjectError::Driver(error.to_string()));
        }
        let bytes: Vec<u8> = read_buffer(ctx, &image_read)?;
        let rgba = unpack_rows(&bytes, width, height, row_bytes, self.format);
        let counters: Vec<u32> = read_buffer(ctx, &stats_read)?;
        let gpu_time = match &timestamps {
            Some(t) => t.read(ctx)?,
            None => None,
        };
        Ok((
            Image::from_pixels(width, height, rgba)?,
            DrawStats {
                segments: u64::from(counters[STAT_SEGMENTS]),
                gpu_time,
                wall_time,
            },
        ))
    }
}

fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

/// Padded texture rows to RGBA f32 pixels.
fn unpack_rows(
    bytes: &[u8],
    width: u32,
    height: u32,
    row_bytes: u32,
    format: wgpu::TextureFormat,
) -> Vec<[f32; 4]> {
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height as usize {
        let row = &bytes[y * row_bytes as usize..];
        for x in 0..width as usize {
            out.push(if format == wgpu::TextureFormat::Rgba32Float {
                std::array::from_fn(|c| {
                    let at = 16 * x + 4 * c;
                    f32::from_le_bytes([row[at], row[at + 1], row[at + 2], row[at + 3]])
                })
            } else {
                std::array::from_fn(|c| {
                    let at = 8 * x + 2 * c;
                    f16_to_f32(u16::from_le_bytes([row[at], row[at + 1]]))
                })
            });
        }
    }
    out
}

/// IEEE binary16 to f32.
fn f16_to_f32(bits: u16) -> f32 {
    let sign = if bits >> 15 == 1 { -1.0 } else { 1.0 };
    let exponent = i32::from((bits >> 10) & 0x1f);
    let mantissa = f32::from(bits & 0x3ff);
    sign * match exponent {
        0 => mantissa * 2f32.powi(-24),
        31 if mantissa == 0.0 => f32::INFINITY,
        31 => f32::NAN,
        e => (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

#[cfg(test)]
mod tests {
    use super::f16_to_f32;

    #[test]
    fn half_floats_convert() {
        assert_eq!(f16_to_f32(0x3c00), 1.0);
        assert_eq!(f16_to_f32(0xc000), -2.0);
        assert_eq!(f16_to_f32(0x3555), 0.333_251_95);
        assert_eq!(f16_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(f16_to_f32(0), 0.0);
    }
}
