//! What the kernel reads, uploaded once per mesh ([`GpuScene`]) and once
//! per transfer function and method ([`GpuIntegrator`]).
//!
//! Large meshes: the tetrahedron and point arrays may each be split over
//! two storage bindings when they exceed the adapter's
//! `max_storage_buffer_binding_size`; beyond twice that the upload fails
//! naming the limit.

use bytemuck::Pod;
use glam::Vec3;
use tetray_integrate::{GammaSpacing, Method, Model, ScalarIntegrator};
use tetray_scene::Scene;
use wgpu::util::DeviceExt;

use crate::layout::{INTERVAL_ENTRIES, IntegratorParams, PREINT_ENTRIES, SceneLayout};
use crate::{GpuContext, GpuError};

/// Storage bindings an array may be split over.
const MAX_CHUNKS: u64 = 2;

/// Words per tetrahedron in the kernel's array of them (20 bytes).
pub const TET_WORDS: usize = 5;

/// What the kernel reads of a mesh, as host arrays (uploaded by
/// [`GpuScene::new`]; read directly by the CPU twin).
#[derive(Debug, Clone)]
pub struct SceneData {
    /// Per point: position and active scalar.
    pub points: Vec<[f32; 4]>,
    /// Per tetrahedron [`TET_WORDS`] words, its [`tetray_scene::WalkTet`]:
    /// the XOR of its point indices, then its neighbours by the rank of the
    /// vertex opposite each (or a boundary marker).
    pub tets: Vec<u32>,
    /// BVH nodes (two entries each), primitives, the face table, then the
    /// left-out cells (`tetray_scene::overlaps`): the bounds of their
    /// points (minimum, maximum: two entries of f32 bits) and one entry of
    /// point indices per tetrahedron.
    pub bvh: Vec<[u32; 4]>,
    pub prim_offset: u32,
    pub face_offset: u32,
    pub overlap_offset: u32,
    pub overlap_count: u32,
    pub bounds: (Vec3, Vec3),
    pub scene_abs_max: f32,
}

impl SceneData {
    pub fn new(scene: &Scene) -> Result<SceneData, GpuError> {
        let flat = scene.bvh.flatten()?;
        let walk = scene.walk_records();
        let mut tets: Vec<u32> = Vec::with_capacity(TET_WORDS * walk.len());
        for record in walk {
            tets.push(record.vert_xor);
            tets.extend(record.next);
        }
        let mut bvh: Vec<[u32; 4]> = Vec::new();
        for node in flat.nodes() {
            let words: [u32; 8] = bytemuck::cast(*node);
            bvh.push([words[0], words[1], words[2], words[3]]);
            bvh.push([words[4], words[5], words[6], words[7]]);
        }
        let prim_offset = bvh.len() as u32;
        bvh.extend(
            flat.prims()
                .iter()
                .map(|p| bytemuck::cast::<_, [u32; 4]>(*p)),
        );
        let face_offset = bvh.len() as u32;
        let faces: Vec<u32> = scene
            .topology
            .boundary_faces
            .iter()
            .map(|f| (f.tet << 2) | u32::from(f.local_face))
            .collect();
        bvh.extend(faces.chunks(4).map(|c| {
            let mut entry = [0u32; 4];
            entry[..c.len()].copy_from_slice(c);
            entry
        }));
        let overlap_offset = bvh.len() as u32;
        let overlaps = scene.overlaps();
        let (lo, hi) = overlaps.bounds;
        for corner in [lo, hi] {
            bvh.push(corner.extend(0.0).to_array().map(f32::to_bits));
        }
        bvh.extend(&overlaps.tets);
        Ok(SceneData {
            points: scene.point_records().to_vec(),
            tets,
            bvh,
            prim_offset,
            face_offset,
            overlap_offset,
            overlap_count: overlaps.tets.len() as u32,
            bounds: scene.bounds(),
            scene_abs_max: flat.scene_abs_max(),
        })
    }

    pub fn tet_count(&self) -> usize {
        self.tets.len() / TET_WORDS
    }
}

/// A mesh on the GPU.
pub struct GpuScene {
    pub(crate) points: [wgpu::Buffer; 2],
    pub(crate) tets: [wgpu::Buffer; 2],
    pub(crate) bvh: wgpu::Buffer,
    pub(crate) point_chunk: u32,
    point_count: usize,
    pub(crate) tet_chunk: u32,
    pub(crate) prim_offset: u32,
    pub(crate) face_offset: u32,
    pub(crate) overlap_offset: u32,
    pub(crate) overlap_count: u32,
    pub(crate) bounds: (Vec3, Vec3),
    pub(crate) scene_abs_max: f32,
    tet_count: usize,
    bytes: u64,
}

impl GpuScene {
    /// Uploads a mesh ([`SceneData::new`] then [`GpuScene::upload`]).
    pub fn new(ctx: &GpuContext, scene: &Scene) -> Result<GpuScene, GpuError> {
        GpuScene::upload(ctx, &SceneData::new(scene)?)
    }

    pub fn upload(ctx: &GpuContext, data: &SceneData) -> Result<GpuScene, GpuError> {
        let limit = ctx
            .limits
            .max_storage_buffer_binding_size
            .min(ctx.limits.max_buffer_size);
        GpuScene::upload_with_binding_limits(ctx, data, limit, limit)
    }

    /// [`GpuScene::upload`] with the tetrahedron and the point array split
    /// at the given bytes per binding (at most the adapter's), as a mesh
    /// larger than one binding is; for testing the split on small meshes.
    pub fn upload_with_binding_limits(
        ctx: &GpuContext,
        data: &SceneData,
        tet_limit: u64,
        point_limit: u64,
    ) -> Result<GpuScene, GpuError> {
        ctx.check()?;
        let limits = &ctx.limits;
        let cap = |limit: u64| {
            limit
                .min(limits.max_storage_buffer_binding_size)
                .min(limits.max_buffer_size)
        };
        let (tets, tet_chunk) = chunked(ctx, "tetrahedra", &data.tets, TET_WORDS, cap(tet_limit))?;
        let (points, point_chunk) = chunked(ctx, "points", &data.points, 1, cap(point_limit))?;
        let point_count = data.points.len();
        let bvh_bytes = std::mem::size_of_val(data.bvh.as_slice()) as u64;
        if bvh_bytes > limits.max_storage_buffer_binding_size {
            return Err(GpuError::TooLarge {
                what: "the boundary BVH",
                bytes: bvh_bytes,
                limit_name: "max_storage_buffer_binding_size",
                limit: limits.max_storage_buffer_binding_size,
                chunks: 1,
            });
        }
        let bvh = storage(ctx, "boundary bvh", &data.bvh);
        let bytes = std::mem::size_of_val(data.tets.as_slice()) as u64
            + std::mem::size_of_val(data.points.as_slice()) as u64
            + bvh_bytes;
        Ok(GpuScene {
            points,
            tets,
            bvh,
            point_chunk,
            point_count,
            tet_chunk,
            prim_offset: data.prim_offset,
            face_offset: data.face_offset,
            overlap_offset: data.overlap_offset,
            overlap_count: data.overlap_count,
            bounds: data.bounds,
            scene_abs_max: data.scene_abs_max,
            tet_count: data.tet_count(),
            bytes,
        })
    }

    /// Writes the points' scalars of `scene` (another time step of the
    /// uploaded mesh: the same points and tetrahedra, new fields) over the
    /// uploaded points; the tetrahedra and the BVH stay.
    ///
    /// # Errors
    /// [`GpuError::Mismatch`] for a scene of another point count; a lost
    /// device.
    pub fn write_points(&self, ctx: &GpuContext, scene: &Scene) -> Result<(), GpuError> {
        ctx.check()?;
        let points = scene.point_records();
        if points.len() != self.point_count {
            return Err(GpuError::Mismatch(format!(
                "the scene has {} points, the uploaded mesh {}",
                points.len(),
                self.point_count
            )));
        }
        let (head, tail) = points.split_at(self.point_chunk as usize);
        ctx.queue
            .write_buffer(&self.points[0], 0, bytemuck::cast_slice(head));
        if !tail.is_empty() {
            ctx.queue
                .write_buffer(&self.points[1], 0, bytemuck::cast_slice(tail));
        }
        ctx.queue.submit([]);
        Ok(())
    }

    /// Bytes of mesh data on the GPU.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    pub fn tet_count(&self) -> usize {
        self.tet_count
    }

    pub fn layout(&self) -> SceneLayout {
        SceneLayout {
            bounds: self.bounds,
            scene_abs_max: self.scene_abs_max,
            tet_count: self.tet_count,
            tet_chunk: self.tet_chunk,
            point_chunk: self.point_chunk,
            prim_offset: self.prim_offset,
            face_offset: self.face_offset,
            overlap_offset: self.overlap_offset,
            overlap_count: self.overlap_count,
        }
    }
}

impl SceneData {
    /// The layout of this data in single (unsplit) arrays, as the CPU twin
    /// reads it.
    pub fn layout(&self) -> SceneLayout {
        SceneLayout {
            bounds: self.bounds,
            scene_abs_max: self.scene_abs_max,
            tet_count: self.tet_count(),
            tet_chunk: self.tet_count() as u32,
            point_chunk: self.points.len() as u32,
            prim_offset: self.prim_offset,
            face_offset: self.face_offset,
            overlap_offset: self.overlap_offset,
            overlap_count: self.overlap_count,
        }
    }
}

/// `items` in up to [`MAX_CHUNKS`] storage buffers: the buffers (an unused
/// second one is a small placeholder) and the number of logical elements
/// (`per_element` items each) in the first.
fn chunked<T: Pod>(
    ctx: &GpuContext,
    what: &'static str,
    items: &[T],
    per_element: usize,
    limit: u64,
) -> Result<([wgpu::Buffer; 2], u32), GpuError> {
    let element_bytes = (std::mem::size_of::<T>() * per_element) as u64;
    let elements = items.len() / per_element;
    let per_chunk = (limit / element_bytes) as usize;
    let bytes = elements as u64 * element_bytes;
    if elements > per_chunk * MAX_CHUNKS as usize || elements > u32::MAX as usize {
        return Err(GpuError::TooLarge {
            what,
            bytes,
            limit_name: "max_storage_buffer_binding_size",
            limit,
            chunks: MAX_CHUNKS,
        });
    }
    let first = elements.min(per_chunk);
    let split = first * per_element;
    // Written again when a time step brings new fields (points only).
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
    let head = storage_with(ctx, what, &items[..split], usage);
    let tail = storage_with(ctx, what, &items[split..], usage);
    Ok(([head, tail], first as u32))
}

/// A read-only storage buffer holding `items` (at least 16 bytes: WGSL
/// arrays may not be bound empty).
pub(crate) fn storage<T: Pod>(ctx: &GpuContext, label: &str, items: &[T]) -> wgpu::Buffer {
    storage_with(ctx, label, items, wgpu::BufferUsages::STORAGE)
}

fn storage_with<T: Pod>(
    ctx: &GpuContext,
    label: &str,
    items: &[T],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let mut bytes = bytemuck::cast_slice::<T, u8>(items).to_vec();
    bytes.resize(bytes.len().max(16), 0);
    ctx.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: &bytes,
            usage,
        })
}

/// What the kernel reads of a transfer function and method, as host
/// arrays (uploaded by [`GpuIntegrator::new`]; read by the CPU twin).
#[derive(Debug, Clone)]
pub struct IntegratorData {
    pub method: u32,
    pub grey: bool,
    pub split: bool,
    pub knot_count: u32,
    pub inv_unit_distance: f32,
    pub riemann_step: f32,
    /// Knot intervals, then the pre-integration table.
    pub tables: Vec<[f32; 4]>,
    /// The Psi table, `psi_size` squared (a 2 x 2 placeholder when unused).
    pub psi: Vec<f32>,
    pub psi_size: u32,
    pub preint: Option<PreintParams>,
}

/// Where the pre-integration table is in `tables` and how it is indexed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreintParams {
    pub size: u32,
    pub offset: u32,
    pub lo: f32,
    pub scale: f32,
    pub length: f32,
}

impl IntegratorData {
    /// What integrate.wgsl reads of this integrator; `split`: whether
    /// segments are cut at the knots (the projection draws one knot
    /// interval at a time and never splits).
    pub fn params(&self, split: bool) -> IntegratorParams {
        let preint = self.preint;
        IntegratorParams {
            method: self.method,
            grey: u32::from(self.grey),
            split: u32::from(split),
            knot_count: self.knot_count,
            psi_size: self.psi_size,
            inv_unit_distance: self.inv_unit_distance,
            riemann_step: self.riemann_step,
            preint_size: preint.map_or(0, |p| p.size),
            preint_offset: preint.map_or(0, |p| p.offset),
            preint_lo: preint.map_or(0.0, |p| p.lo),
            preint_scale: preint.map_or(0.0, |p| p.scale),
            preint_length: preint.map_or(1.0, |p| p.length),
        }
    }

    pub fn new(integrator: &ScalarIntegrator) -> Result<IntegratorData, GpuError> {
        let method = integrator.method();
        let code = method.gpu_code().ok_or(GpuError::Driver(format!(
            "the {method} integrator (f64 quadrature) has no GPU kernel; use --renderer cpu"
        )))?;
        let knots = integrator.knots();
        let opacity = method.model() == Model::LinearOpacity;
        let mut tables = pack_intervals(knots, opacity);
        let mut preint = None;
        if let Some(table) = integrator.preintegration_table() {
            let (lo, hi) = table.scalar_range();
            let size = table.size();
            let offset = tables.len() as u32;
            let (emitted, transmittance) = table.entries();
            for (e, t) in emitted.iter().zip(transmittance) {
                tables.push([e.x, e.y, e.z, 0.0]);
                tables.push([t.x, t.y, t.z, 0.0]);
            }
            debug_assert_eq!(tables.len() - offset as usize, PREINT_ENTRIES * size * size);
            preint = Some(PreintParams {
                size: size as u32,
                offset,
                lo,
                scale: if hi > lo {
                    (size - 1) as f32 / (hi - lo)
                } else {
                    0.0
                },
                length: table.length(),
            });
        }
        let (psi, psi_size) = match integrator.psi_table() {
            Some(table) if method == Method::Ppi => {
                if table.spacing() != GammaSpacing::Quadratic {
                    return Err(GpuError::PsiSpacing(table.spacing().name()));
                }
                (table.values().to_vec(), table.size() as u32)
            }
            _ => (vec![1.0; 4], 2),
        };
        Ok(IntegratorData {
            method: code,
            grey: knots.is_grey(),
            split: integrator.splits_at_knots(),
            knot_count: knots.len() as u32,
            inv_unit_distance: 1.0 / integrator.unit_distance(),
            riemann_step: integrator.riemann_step(),
            tables,
            psi,
            psi_size,
            preint,
        })
    }
}

/// A transfer function and method on the GPU.
pub struct GpuIntegrator {
    pub(crate) data: IntegratorData,
    pub(crate) tables: wgpu::Buffer,
    pub(crate) psi: wgpu::TextureView,
}

impl GpuIntegrator {
    /// Uploads a transfer function and method ([`IntegratorData::new`] then
    /// [`GpuIntegrator::upload`]).
    pub fn new(ctx: &GpuContext, integrator: &ScalarIntegrator) -> Result<GpuIntegrator, GpuError> {
        ctx.check()?;
        Ok(GpuIntegrator::upload(ctx, IntegratorData::new(integrator)?))
    }

    pub fn upload(ctx: &GpuContext, data: IntegratorData) -> GpuIntegrator {
        GpuIntegrator {
            tables: storage(ctx, "transfer function tables", &data.tables),
            psi: psi_texture(ctx, data.psi_size, &data.psi),
            data,
        }
    }

    /// What was uploaded.
    pub fn data(&self) -> &IntegratorData {
        &self.data
    }

    /// The knot intervals and pre-integration table (WGSL `tables`), for
    /// other kernels that integrate with shaders/integrate.wgsl.
    pub fn tables_buffer(&self) -> &wgpu::Buffer {
        &self.tables
    }

    /// The Psi table texture (WGSL `psi_table`).
    pub fn psi_view(&self) -> &wgpu::TextureView {
        &self.psi
    }
}

/// The knot intervals as the kernel reads them (shaders/integrate.wgsl):
/// interval k (-1 below the first knot .. n - 1 above the last) at
/// `INTERVAL_ENTRIES * (k + 1)`: luminance start + x0, luminance delta +
/// 1 / width, quantity start, quantity delta; the quantity is the opacity
/// for the opacity methods, else the attenuation.
fn pack_intervals(knots: &tetray_integrate::TfKnots, opacity: bool) -> Vec<[f32; 4]> {
    let scalars = knots.scalars();
    let materials = knots.materials();
    let n = scalars.len();
    let quantity = |k: usize| {
        let m = &materials[k];
        if opacity { m.alpha } else { m.tau }
    };
    let mut out = Vec::with_capacity(INTERVAL_ENTRIES * (n + 1));
    let mut push = |x0: f32, inv_width: f32, k0: usize, k1: usize| {
        let (l0, l1) = (materials[k0].lum, materials[k1].lum);
        let (q0, q1) = (quantity(k0), quantity(k1));
        let dl = l1 - l0;
        let dq = q1 - q0;
        out.push([l0.x, l0.y, l0.z, x0]);
        out.push([dl.x, dl.y, dl.z, inv_width]);
        out.push([q0.x, q0.y, q0.z, 0.0]);
        out.push([dq.x, dq.y, dq.z, 0.0]);
    };
    push(scalars[0], 0.0, 0, 0);
    for k in 0..n - 1 {
        let (x0, x1) = (scalars[k], scalars[k + 1]);
        let inv_width = if x1 > x0 { 1.0 / (x1 - x0) } else { 0.0 };
        push(x0, inv_width, k, k + 1);
    }
    push(scalars[n - 1], 0.0, n - 1, n - 1);
    out
}

/// An r32float texture of the Psi table (row = gamma_f, column = gamma_b),
/// `size` texels a side.
pub fn psi_texture(ctx: &GpuContext, size: u32, values: &[f32]) -> wgpu::TextureView {
    let texture = ctx.device.create_texture_with_data(
        &ctx.queue,
        &crate::texture_2d(
            "psi table",
            (size, size),
            wgpu::TextureFormat::R32Float,
            wgpu::TextureUsages::TEXTURE_BINDING,
        ),
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(values),
    );
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}
