//! Rendering a frame: parameters from the camera, one compute pass of tiled
//! dispatches, optional timestamp queries, and the read-back of the image
//! and the counters.

use std::ops::Range;
use std::sync::OnceLock;
use std::time::Duration;

use tetray_core::{Camera, Image, WalkCounters};
use wgpu::util::DeviceExt;

use crate::layout::{self, Params, SceneLayout, Tile, ViewParams};
use crate::readback::{PassTimestamps, read_buffer, readback_buffer};
use crate::shaders::{raycast_source, raycast_source_without_overlaps};
use crate::upload::{GpuIntegrator, GpuScene, IntegratorData};
use crate::{GpuContext, GpuError, GpuTarget};

/// Pixels per side of one dispatch; a frame is as many dispatches as it
/// takes (each short, and within the workgroup-count limit).
pub const TILE: u32 = 512;
/// Kernel workgroup edge (8 x 8 invocations).
const WORKGROUP: u32 = 8;

/// What to render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuRenderOptions {
    pub width: u32,
    pub height: u32,
    /// Stop a ray once its opacity reaches this; 1 disables.
    pub early_termination: f32,
    /// Bound on tetrahedra visited per ray; `None`: tetrahedra + 1024.
    pub max_steps_per_ray: Option<u32>,
}

impl Default for GpuRenderOptions {
    fn default() -> Self {
        GpuRenderOptions {
            width: 512,
            height: 512,
            early_termination: 1.0,
            max_steps_per_ray: None,
        }
    }
}

/// Counters and times of one GPU frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpuStats {
    /// The kernel's counters, read back from its counter array.
    pub counters: WalkCounters,
    /// GPU time of the pass (timestamp queries), when the adapter has them.
    pub gpu_time: Option<Duration>,
    /// Submission to completion, read-back excluded.
    pub wall_time: Duration,
}

impl GpuStats {
    /// The pass time: GPU timestamps when available, else wall time.
    pub fn frame_time(&self) -> Duration {
        self.gpu_time.unwrap_or(self.wall_time)
    }
}

/// A rendered frame.
#[derive(Debug, Clone)]
pub struct GpuFrame {
    pub image: Image,
    pub stats: GpuStats,
}

/// The compiled kernel and its binding layout.
pub struct GpuRaycaster {
    /// The kernel for scenes with no cells left out of the walk.
    pipeline: wgpu::ComputePipeline,
    /// The kernel with the overlap lists, compiled for the first scene
    /// that has left-out cells.
    with_overlaps: OnceLock<wgpu::ComputePipeline>,
    pipeline_layout: wgpu::PipelineLayout,
    device: wgpu::Device,
    layout: wgpu::BindGroupLayout,
}

impl GpuRaycaster {
    pub fn new(ctx: &GpuContext) -> Result<GpuRaycaster, GpuError> {
        let device = &ctx.device;
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        // Parameters: read-only storage, not uniform (see common.wgsl).
        let parameters = |binding: u32, dynamic: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: dynamic,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("raycast bindings"),
            entries: &[
                parameters(0, false),
                parameters(1, true),
                storage(2, true),
                storage(3, true),
                storage(4, true),
                storage(5, true),
                storage(6, true),
                storage(7, true),
                wgpu::BindGroupLayoutEntry {
                    binding: 8,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                storage(9, false),
                storage(10, false),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("raycast"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = compile(device, &pipeline_layout, &raycast_source_without_overlaps())?;
        Ok(GpuRaycaster {
            pipeline,
            with_overlaps: OnceLock::new(),
            pipeline_layout,
            device: device.clone(),
            layout,
        })
    }

    /// The kernel for `scene`: with the overlap lists when it has cells
    /// left out of the walk.
    fn pipeline_for(&self, scene: &GpuScene) -> Result<&wgpu::ComputePipeline, GpuError> {
        if scene.overlap_count == 0 {
            return Ok(&self.pipeline);
        }
        if let Some(pipeline) = self.with_overlaps.get() {
            return Ok(pipeline);
        }
        let pipeline = compile(&self.device, &self.pipeline_layout, &raycast_source())?;
        Ok(self.with_overlaps.get_or_init(|| pipeline))
    }

    /// Renders `scene` seen by `camera` with `integrator` and reads the
    /// image and counters back.
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &GpuScene,
        integrator: &GpuIntegrator,
        camera: &Camera,
        opts: &GpuRenderOptions,
    ) -> Result<GpuFrame, GpuError> {
        ctx.check()?;
        let (width, height) = (opts.width, opts.height);
        let target = GpuTarget::new(ctx, width, height)?;
        let device = &ctx.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let queries = ctx
            .timestamps
            .then(|| PassTimestamps::new(ctx, "raycast timestamps"));
        let mut encoder = device.create_command_encoder(&Default::default());
        let timestamp_writes = queries.as_ref().map(|q| wgpu::ComputePassTimestampWrites {
            query_set: &q.set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        });
        let job = FrameJob {
            scene,
            integrator,
            camera,
            opts,
        };
        self.encode_rows(
            ctx,
            &job,
            &target,
            0..height,
            &mut encoder,
            timestamp_writes,
        )?;
        if let Some(q) = &queries {
            q.resolve(&mut encoder);
        }
        let image_bytes = target.image_bytes();
        let image_read = readback_buffer(ctx, "image readback", image_bytes);
        let stats_read = target.encode_stats_readback(ctx, &mut encoder);
        encoder.copy_buffer_to_buffer(target.image(), 0, &image_read, 0, image_bytes);
        let wall_time = ctx.submit_and_wait(encoder.finish())?;
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Driver(error.to_string()));
        }
        let counters: Vec<u32> = read_buffer(ctx, &stats_read)?;
        let rgba: Vec<[f32; 4]> = read_buffer(ctx, &image_read)?;
        let gpu_time = match &queries {
            Some(q) => q.read(ctx)?,
            None => None,
        };
        let pixels = u64::from(width) * u64::from(height);
        Ok(GpuFrame {
            image: Image::from_pixels(width, height, rgba)?,
            stats: GpuStats::from_counters(&counters, pixels, gpu_time, wall_time),
        })
    }

    /// Encodes one compute pass rendering rows `rows` of `target` (every
    /// tile of them) into `encoder`, without submitting: the counters
    /// accumulate in the target, so a frame may be rendered a few rows per
    /// submission (as the viewer does to stay responsive) and the image
    /// used on the GPU without a read-back.
    pub fn encode_rows(
        &self,
        ctx: &GpuContext,
        job: &FrameJob<'_>,
        target: &GpuTarget,
        rows: Range<u32>,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), GpuError> {
        let opts = job.opts;
        if (opts.width, opts.height) != (target.width(), target.height()) {
            return Err(GpuError::TargetSize {
                frame: (opts.width, opts.height),
                target: (target.width(), target.height()),
            });
        }
        let params = frame_params(&job.scene.layout(), &job.integrator.data, job.camera, opts)?;
        let rows = rows.start.min(opts.height)..rows.end.min(opts.height);
        let device = &ctx.device;
        let params_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let (tiles, stride) = tile_buffer(ctx, opts.width, rows);
        let (scene, integrator) = (job.scene, job.integrator);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("raycast"),
            layout: &self.layout,
            entries: &[
                buffer_entry(0, &params_buffer),
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &tiles.buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(std::mem::size_of::<Tile>() as u64),
                    }),
                },
                buffer_entry(2, &scene.points[0]),
                buffer_entry(3, &scene.points[1]),
                buffer_entry(4, &scene.tets[0]),
                buffer_entry(5, &scene.tets[1]),
                buffer_entry(6, &scene.bvh),
                buffer_entry(7, &integrator.tables),
                wgpu::BindGroupEntry {
                    binding: 8,
                    resource: wgpu::BindingResource::TextureView(&integrator.psi),
                },
                buffer_entry(9, target.image()),
                buffer_entry(10, target.stats()),
            ],
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("raycast"),
            timestamp_writes,
        });
        pass.set_pipeline(self.pipeline_for(job.scene)?);
        for (i, tile) in tiles.tiles.iter().enumerate() {
            pass.set_bind_group(0, &bind_group, &[(i as u64 * stride) as u32]);
            pass.dispatch_workgroups(
                tile.width.div_ceil(WORKGROUP),
                tile.height.div_ceil(WORKGROUP),
                1,
            );
        }
        Ok(())
    }
}

/// One frame's inputs: what [`GpuRaycaster::encode_rows`] renders.
#[derive(Clone, Copy)]
pub struct FrameJob<'a> {
    pub scene: &'a GpuScene,
    pub integrator: &'a GpuIntegrator,
    pub camera: &'a Camera,
    pub opts: &'a GpuRenderOptions,
}

/// The counters of `rays` rays from the kernel's counter array.
pub fn walk_counters(counters: &[u32], rays: u64) -> WalkCounters {
    let at = |i: usize| u64::from(counters.get(i).copied().unwrap_or(0));
    let wide = |lo: usize, hi: usize| at(lo) | (at(hi) << 32);
    WalkCounters {
        rays,
        rays_hit: at(layout::STAT_RAYS_HIT),
        segments: wide(layout::STAT_SEGMENTS_LO, layout::STAT_SEGMENTS_HI),
        steps: wide(layout::STAT_STEPS_LO, layout::STAT_STEPS_HI),
        entries: at(layout::STAT_ENTRIES),
        steps_bound_hits: at(layout::STAT_BOUND_HITS),
        walk_failures: at(layout::STAT_WALK_FAILURES),
        overlap_segments: at(layout::STAT_OVERLAP_SEGMENTS),
        overlap_overflows: at(layout::STAT_OVERLAP_OVERFLOWS),
    }
}

impl GpuStats {
    /// The stats of `rays` rays from the kernel's counter array (read back
    /// from [`GpuTarget::stats`]) and the times measured around it.
    pub fn from_counters(
        counters: &[u32],
        rays: u64,
        gpu_time: Option<Duration>,
        wall_time: Duration,
    ) -> GpuStats {
        GpuStats {
            counters: walk_counters(counters, rays),
            gpu_time,
            wall_time,
        }
    }
}

/// The kernel's bound on tetrahedra visited per ray when none is given: a
/// ray enters each convex cell at most once, plus cells it only touches
/// (tetrahedra + 1024, at most `u32::MAX`).
pub fn default_max_steps(tet_count: usize) -> u32 {
    (tet_count as u64 + 1024).min(u64::from(u32::MAX)) as u32
}

/// The frame's parameters (WGSL `Params`) for `camera` and `opts`.
pub fn frame_params(
    scene: &SceneLayout,
    integrator: &IntegratorData,
    camera: &Camera,
    opts: &GpuRenderOptions,
) -> Result<Params, GpuError> {
    if opts.early_termination.is_nan() || opts.early_termination <= 0.0 {
        return Err(GpuError::EarlyTermination(opts.early_termination));
    }
    let rays = camera.pixel_rays(opts.width, opts.height)?;
    let (lo, hi) = scene.bounds;
    Ok(Params {
        view: ViewParams::new(&rays),
        bounds_min: lo.to_array(),
        eye_inside: u32::from(!rays.is_orthographic() && camera.is_inside_bounds(lo, hi)),
        bounds_max: hi.to_array(),
        scene_abs_max: scene.scene_abs_max,
        width: opts.width,
        height: opts.height,
        max_steps: opts
            .max_steps_per_ray
            .unwrap_or_else(|| default_max_steps(scene.tet_count)),
        stop_below_sum: 3.0 * (1.0 - opts.early_termination),
        integrator: integrator.params(integrator.split),
        tet_chunk: scene.tet_chunk,
        point_chunk: scene.point_chunk,
        prim_offset: scene.prim_offset,
        face_offset: scene.face_offset,
        overlap_offset: scene.overlap_offset,
        overlap_count: scene.overlap_count,
        _pad: [0; 2],
    })
}

struct Tiles {
    buffer: wgpu::Buffer,
    tiles: Vec<Tile>,
}

/// Rows `rows` of a frame `width` wide cut into [`TILE`]-sized
/// dispatches, one `Tile` each at a stride the dynamic offsets
/// accept.
fn tile_buffer(ctx: &GpuContext, width: u32, rows: Range<u32>) -> (Tiles, u64) {
    let stride = u64::from(ctx.limits.min_storage_buffer_offset_alignment).max(16);
    let mut tiles = Vec::new();
    for y0 in rows.clone().step_by(TILE as usize) {
        for x0 in (0..width).step_by(TILE as usize) {
            tiles.push(Tile {
                x0,
                y0,
                width: TILE.min(width - x0),
                height: TILE.min(rows.end - y0),
            });
        }
    }
    // A buffer binding may not be empty: an empty row range binds one
    // unused entry and dispatches nothing.
    let mut bytes = vec![0u8; tiles.len().max(1) * stride as usize];
    for (i, tile) in tiles.iter().enumerate() {
        let at = i * stride as usize;
        bytes[at..at + 16].copy_from_slice(bytemuck::bytes_of(tile));
    }
    let buffer = ctx
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("tiles"),
            contents: &bytes,
            usage: wgpu::BufferUsages::STORAGE,
        });
    (Tiles { buffer, tiles }, stride)
}

fn buffer_entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

/// Compiles the ray-casting kernel `source` for `layout`; a validation
/// error of the driver is an error, not a panic.
fn compile(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    source: &str,
) -> Result<wgpu::ComputePipeline, GpuError> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("raycast.wgsl"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("raycast"),
        layout: Some(layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    if let Some(error) = pollster::block_on(scope.pop()) {
        return Err(GpuError::Driver(error.to_string()));
    }
    Ok(pipeline)
}
