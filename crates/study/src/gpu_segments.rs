//! Single segments through the GPU kernel's integration methods: a small
//! compute kernel (`shaders/segments.wgsl`) that calls `piece_light` of
//! `shaders/integrate.wgsl` once per segment and writes the emitted light
//! and transmittance back, so the accuracy study sees the f32 arithmetic of
//! the kernel the GPU ray caster runs.

use bytemuck::{Pod, Zeroable};
use tetray_gpu::GpuContext;
use tetray_gpu::layout::{IntegratorParams, Params};
use tetray_gpu::readback::{read_buffer, readback_buffer};
use tetray_gpu::shaders::{COMMON, INTEGRATE, module};
use tetray_integrate::{GammaSpacing, Method, PsiTable};
use wgpu::util::DeviceExt;

use crate::StudyError;

/// The per-segment kernel.
pub const SEGMENTS: &str = include_str!("../../../shaders/segments.wgsl");

/// The module: the shared declarations, the integration methods, the
/// per-segment entry point `segments`.
pub fn segments_source() -> String {
    module(&[COMMON, INTEGRATE, SEGMENTS])
}

/// One segment as the kernel reads it (two `vec4<f32>`).
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct GpuSegment {
    pub lum_back: f32,
    pub lum_front: f32,
    /// Attenuation per unit length, or the opacity of one unit distance
    /// for the opacity methods.
    pub q_back: f32,
    pub q_front: f32,
    pub length: f32,
    pub pad: [f32; 3],
}

impl GpuSegment {
    pub fn new(lum_back: f32, lum_front: f32, q_back: f32, q_front: f32, length: f32) -> Self {
        GpuSegment {
            lum_back,
            lum_front,
            q_back,
            q_front,
            length,
            pad: [0.0; 3],
        }
    }
}

/// Invocations per workgroup (WGSL `@workgroup_size`).
const WORKGROUP: u32 = 64;

/// The compiled kernel and the Psi table it reads.
pub struct SegmentKernel {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    psi: wgpu::TextureView,
    psi_size: u32,
}

impl SegmentKernel {
    /// Compiles the kernel and uploads `psi` (the kernel reads the
    /// quadratic spacing only, as the ray caster does).
    pub fn new(ctx: &GpuContext, psi: &PsiTable) -> Result<SegmentKernel, StudyError> {
        if psi.spacing() != GammaSpacing::Quadratic {
            return Err(tetray_gpu::GpuError::PsiSpacing(psi.spacing().name()).into());
        }
        let device = &ctx.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("segments.wgsl"),
            source: wgpu::ShaderSource::Wgsl(segments_source().into()),
        });
        let entry = |binding: u32, ty: wgpu::BindingType| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty,
            count: None,
        };
        let storage = |read_only: bool| wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("segments bindings"),
            entries: &[
                entry(
                    0,
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                ),
                entry(
                    8,
                    wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                ),
                entry(11, storage(true)),
                entry(12, storage(false)),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("segments"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("segments"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("segments"),
            compilation_options: Default::default(),
            cache: None,
        });
        let size = psi.size() as u32;
        let psi = tetray_gpu::psi_texture(ctx, size, psi.values());
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(StudyError::GpuKernel {
                what: "compiling the segment kernel",
                message: error.to_string(),
            });
        }
        Ok(SegmentKernel {
            pipeline,
            layout,
            psi,
            psi_size: size,
        })
    }

    /// `(emitted, transmittance)` of every segment by `method` (one with a
    /// GPU kernel), with opacities of `unit_distance` of material.
    pub fn evaluate(
        &self,
        ctx: &GpuContext,
        method: Method,
        unit_distance: f32,
        segments: &[GpuSegment],
    ) -> Result<Vec<[f32; 2]>, StudyError> {
        let code = method.gpu_code().ok_or_else(|| StudyError::GpuKernel {
            what: "choosing the method",
            message: format!("{method} has no GPU kernel"),
        })?;
        let count = segments.len() as u64;
        let groups = count.div_ceil(u64::from(WORKGROUP));
        let max_groups = u64::from(ctx.limits.max_compute_workgroups_per_dimension);
        if segments.is_empty() || groups > max_groups {
            return Err(StudyError::GpuKernel {
                what: "dispatching segments",
                message: format!(
                    "{count} segments: need 1 to {} per call",
                    max_groups * u64::from(WORKGROUP)
                ),
            });
        }
        let params = Params {
            integrator: IntegratorParams {
                method: code,
                grey: 1,
                psi_size: self.psi_size,
                inv_unit_distance: 1.0 / unit_distance,
                ..IntegratorParams::zeroed()
            },
            ..Params::zeroed()
        };
        let device = &ctx.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let init = |label: &str, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let params_buffer = init(
            "segment params",
            bytemuck::bytes_of(&params),
            wgpu::BufferUsages::STORAGE,
        );
        let inputs = init(
            "segments",
            bytemuck::cast_slice(segments),
            wgpu::BufferUsages::STORAGE,
        );
        let out_bytes = count * 8;
        let outputs = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("segment lights"),
            size: out_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = readback_buffer(ctx, "segment lights readback", out_bytes);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("segments"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: params_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 8,
                    resource: wgpu::BindingResource::TextureView(&self.psi),
                },
                wgpu::BindGroupEntry {
                    binding: 11,
                    resource: inputs.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 12,
                    resource: outputs.as_entire_binding(),
                },
            ],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("segments"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(groups as u32, 1, 1);
        }
        encoder.copy_buffer_to_buffer(&outputs, 0, &readback, 0, out_bytes);
        ctx.queue.submit([encoder.finish()]);
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(StudyError::GpuKernel {
                what: "running the segment kernel",
                message: error.to_string(),
            });
        }
        Ok(read_buffer(ctx, &readback)?)
    }
}
