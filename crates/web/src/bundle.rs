//! What a page holds: the scene's GPU buffers exactly as the wgpu ray
//! caster uploads them ([`tetray_gpu::SceneData`]), an integrator per
//! colour map and GPU method ([`tetray_gpu::IntegratorData`]), and the
//! manifest that says where each is and how the frame parameters are
//! made.
//!
//! Each buffer is stored as its little-endian bytes split into four byte
//! planes (every word's first bytes, then its second bytes, ...: floats
//! and indices compress far better so) and deflated (raw DEFLATE, which
//! browsers inflate with `DecompressionStream("deflate-raw")`).

use std::collections::{BTreeMap, HashMap};
use std::io::Write;

use serde::{Deserialize, Serialize};
use tetray_core::{Camera, Method, Model};
use tetray_engine::Setup;
use tetray_gpu::{IntegratorData, SceneData};

use crate::WebError;
use crate::colormaps::{EXPORTED, colormaps};

/// A buffer as stored in the page.
#[derive(Debug, Clone)]
pub struct StoredBuffer {
    pub id: String,
    /// Bytes of the buffer as uploaded.
    pub bytes: usize,
    /// Its byte planes, deflated.
    pub deflated: Vec<u8>,
}

/// The manifest (JSON in the page) and the buffers it names.
#[derive(Debug, Clone)]
pub struct Bundle {
    pub manifest: Manifest,
    pub buffers: Vec<StoredBuffer>,
}

/// What the page reads first; every name matches the page script's.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Manifest {
    pub name: String,
    pub field: String,
    pub range: [f32; 2],
    pub unit_distance: f32,
    pub tet_count: usize,
    pub point_count: usize,
    pub boundary_faces: usize,
    pub bounds: [[f32; 3]; 2],
    pub scene_abs_max: f32,
    pub prim_offset: u32,
    pub face_offset: u32,
    /// The left-out cells in the BVH array (`tetray_gpu::SceneData`).
    pub overlap_offset: u32,
    pub overlap_count: u32,
    /// The file's coordinates are `origin + point`.
    pub origin: [f64; 3],
    pub camera: CameraSpec,
    pub size: [u32; 2],
    pub background: [f32; 3],
    pub early_termination: f32,
    /// Tetrahedra one ray may visit.
    pub max_steps: u32,
    /// The method the page starts with.
    pub method: String,
    /// Every method with a GPU kernel: name, WGSL code, model.
    pub methods: Vec<MethodSpec>,
    pub colormaps: Vec<ColormapSpec>,
    /// Buffer id -> bytes as uploaded.
    pub buffers: BTreeMap<String, usize>,
    pub bench: Option<BenchSpec>,
}

#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct CameraSpec {
    pub position: [f32; 3],
    pub focal_point: [f32; 3],
    pub view_up: [f32; 3],
    pub view_angle: f32,
    pub parallel_scale: Option<f32>,
}

impl From<&Camera> for CameraSpec {
    fn from(c: &Camera) -> CameraSpec {
        CameraSpec {
            position: c.position.to_array(),
            focal_point: c.focal_point.to_array(),
            view_up: c.view_up.to_array(),
            view_angle: c.view_angle,
            parallel_scale: c.parallel_scale,
        }
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct MethodSpec {
    pub name: String,
    pub code: u32,
    /// "attenuation", "opacity" or "preintegrated": which parameter the
    /// page's opacity scale changes.
    pub scale: String,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ColormapSpec {
    pub name: String,
    /// Method name -> its integrator (a method missing here is not offered
    /// with this colour map).
    pub integrators: BTreeMap<String, IntegratorSpec>,
}

/// WGSL `IntegratorParams` but for the tables, which are buffers.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct IntegratorSpec {
    pub method: u32,
    pub grey: bool,
    pub split: bool,
    pub knot_count: u32,
    pub inv_unit_distance: f32,
    pub riemann_step: f32,
    pub tables: String,
    pub psi: String,
    pub psi_size: u32,
    pub preint: Option<PreintSpec>,
}

#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct PreintSpec {
    pub size: u32,
    pub offset: u32,
    pub lo: f32,
    pub scale: f32,
    pub length: f32,
}

/// The page's benchmark: `frames` frames at each of `views` azimuths.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct BenchSpec {
    pub frames: u32,
    pub views: u32,
}

/// How the page starts.
#[derive(Debug, Clone, PartialEq)]
pub struct PageOptions {
    pub size: (u32, u32),
    pub background: [f32; 3],
    pub early_termination: f32,
    pub max_steps: Option<u32>,
    pub bench: Option<(u32, u32)>,
    /// Pre-integration tables for every colour map, not only the exported
    /// one (each is `2 x 16 x size^2` bytes).
    pub preintegrate_all: bool,
}

impl Default for PageOptions {
    fn default() -> Self {
        PageOptions {
            size: (512, 512),
            background: [1.0; 3],
            early_termination: 1.0,
            max_steps: None,
            bench: None,
            preintegrate_all: false,
        }
    }
}

/// The bundle of `setup`'s scene, its transfer function in every colour
/// map and every GPU method, starting with `setup`'s method and camera.
pub fn bundle(setup: &Setup, options: &PageOptions) -> Result<Bundle, WebError> {
    let scene = setup.scene().map_err(|e| WebError::Setup(e.to_string()))?;
    let data = SceneData::new(scene).map_err(|e| WebError::Setup(e.to_string()))?;
    let mut store = Store::default();
    store.add("points", bytemuck::cast_slice(&data.points));
    store.add("tets", bytemuck::cast_slice(&data.tets));
    store.add("bvh", bytemuck::cast_slice(&data.bvh));

    let methods: Vec<Method> = Method::ALL
        .into_iter()
        .filter(|m| m.has_gpu_kernel())
        .collect();
    let range = setup.choice.tf_range(setup.extent.range);
    let mut maps = Vec::new();
    for (name, tf) in colormaps(&setup.tf, range)? {
        let mut integrators = BTreeMap::new();
        for &method in &methods {
            if method == Method::Preintegrated && name != EXPORTED && !options.preintegrate_all {
                continue;
            }
            let integrator = setup
                .integrator_with(
                    method,
                    &tf,
                    setup.unit_distance,
                    setup.integrator_options.opacity_mode,
                )
                .map_err(|e| WebError::Setup(e.to_string()))?;
            let data =
                IntegratorData::new(&integrator).map_err(|e| WebError::Setup(e.to_string()))?;
            let spec = IntegratorSpec {
                method: data.method,
                grey: data.grey,
                split: data.split,
                knot_count: data.knot_count,
                inv_unit_distance: data.inv_unit_distance,
                riemann_step: data.riemann_step,
                tables: store.add(
                    &format!("tables-{name}-{method}"),
                    bytemuck::cast_slice(&data.tables),
                ),
                psi: store.add(
                    &format!("psi-{}", data.psi_size),
                    bytemuck::cast_slice(&data.psi),
                ),
                psi_size: data.psi_size,
                preint: data.preint.map(|p| PreintSpec {
                    size: p.size,
                    offset: p.offset,
                    lo: p.lo,
                    scale: p.scale,
                    length: p.length,
                }),
            };
            integrators.insert(method.name().to_string(), spec);
        }
        maps.push(ColormapSpec { name, integrators });
    }
    let (lo, hi) = data.bounds;
    let manifest = Manifest {
        name: setup.name().to_string(),
        field: setup.extent.field.clone(),
        range: [range.0, range.1],
        unit_distance: setup.unit_distance,
        tet_count: data.tet_count(),
        point_count: data.points.len(),
        boundary_faces: setup.boundary_faces(),
        bounds: [lo.to_array(), hi.to_array()],
        scene_abs_max: data.scene_abs_max,
        prim_offset: data.prim_offset,
        face_offset: data.face_offset,
        overlap_offset: data.overlap_offset,
        overlap_count: data.overlap_count,
        origin: setup.extent.origin.to_array(),
        camera: CameraSpec::from(&setup.camera),
        size: [options.size.0, options.size.1],
        background: options.background,
        early_termination: options.early_termination,
        max_steps: options
            .max_steps
            .unwrap_or_else(|| tetray_gpu::default_max_steps(data.tet_count())),
        method: setup.method.gpu_stand_in().name().to_string(),
        methods: methods
            .iter()
            .map(|&m| MethodSpec {
                name: m.name().to_string(),
                code: m.gpu_code().unwrap_or(u32::MAX),
                scale: match (m, m.model()) {
                    (Method::Preintegrated, _) => "preintegrated",
                    (_, Model::LinearOpacity) => "opacity",
                    _ => "attenuation",
                }
                .to_string(),
            })
            .collect(),
        colormaps: maps,
        buffers: store
            .buffers
            .iter()
            .map(|b| (b.id.clone(), b.bytes))
            .collect(),
        bench: options
            .bench
            .map(|(frames, views)| BenchSpec { frames, views }),
    };
    Ok(Bundle {
        manifest,
        buffers: store.buffers,
    })
}

/// The buffers, each stored once however many integrators share it.
#[derive(Default)]
struct Store {
    buffers: Vec<StoredBuffer>,
    by_content: HashMap<Vec<u8>, String>,
}

impl Store {
    /// Stores `bytes` under `id` (or finds the same bytes stored before)
    /// and returns the id to name it by.
    fn add(&mut self, id: &str, bytes: &[u8]) -> String {
        if let Some(existing) = self.by_content.get(bytes) {
            return existing.clone();
        }
        let id = id.replace(|c: char| !c.is_ascii_alphanumeric() && c != '-', "_");
        self.buffers.push(StoredBuffer {
            id: id.clone(),
            bytes: bytes.len(),
            deflated: deflate(&byte_planes(bytes)),
        });
        self.by_content.insert(bytes.to_vec(), id.clone());
        id
    }
}

/// The bytes of 4-byte words as four planes: byte 0 of every word, then
/// byte 1, ... (the length is a multiple of 4: every buffer is words).
pub fn byte_planes(bytes: &[u8]) -> Vec<u8> {
    debug_assert_eq!(bytes.len() % 4, 0);
    let words = bytes.len() / 4;
    let mut out = vec![0u8; bytes.len()];
    for (w, word) in bytes.chunks_exact(4).enumerate() {
        for (plane, &b) in word.iter().enumerate() {
            out[plane * words + w] = b;
        }
    }
    out
}

fn deflate(bytes: &[u8]) -> Vec<u8> {
    let mut encoder = flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::best());
    // Writing to a Vec cannot fail.
    encoder.write_all(bytes).expect("deflate into memory");
    encoder.finish().expect("deflate into memory")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_planes_hold_each_byte_of_each_word_in_its_plane() {
        let words: [u32; 3] = [0x0403_0201, 0x1413_1211, 0x2423_2221];
        let planes = byte_planes(bytemuck::cast_slice(&words));
        assert_eq!(
            planes,
            [
                0x01, 0x11, 0x21, 0x02, 0x12, 0x22, 0x03, 0x13, 0x23, 0x04, 0x14, 0x24
            ]
        );
    }

    #[test]
    fn the_same_bytes_are_stored_once() {
        let mut store = Store::default();
        let a = store.add("a", &[1, 2, 3, 4]);
        let b = store.add("b", &[1, 2, 3, 4]);
        let c = store.add("c/d", &[5, 6, 7, 8]);
        assert_eq!((a.as_str(), b.as_str(), c.as_str()), ("a", "a", "c_d"));
        assert_eq!(store.buffers.len(), 2);
    }
}
