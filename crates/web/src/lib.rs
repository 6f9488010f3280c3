//! `tetray export-html`: a scene as one web page that renders it on the
//! visitor's GPU through WebGPU, with the same WGSL kernel and the same
//! buffers as the wgpu ray caster (`tetray render --renderer gpu`).
//!
//! - [`bundle()`]: the scene's buffers as uploaded, an integrator per colour
//!   map and GPU method, and the manifest the page reads;
//! - [`page()`]: the HTML (one file, or `index.html` and `scene.js`);
//! - `page/`: the page's script (plain JavaScript, no build step): the VTK
//!   camera in the CLI's arithmetic, the buffers' decoding, the WebGPU host
//!   of the kernel, and the controls, stats, benchmark and test hook.
//!
//! What a page can hold: the tetrahedra and the points may each be split
//! over two storage bindings, as the native upload does, so a page needs an
//! adapter whose `maxStorageBufferBindingSize` is at least half the larger
//! array ([`Limits`]); WebGPU guarantees 128 MiB (6.7 M tetrahedra per
//! binding, 13.4 M in all). Each buffer's text must fit in one browser
//! string ([`page::MAX_BUFFER_TEXT`]).

pub mod bundle;
mod colormaps;
pub mod page;

pub use bundle::{Bundle, Manifest, PageOptions, bundle};
pub use colormaps::EXPORTED;
pub use page::{Layout, PageFiles, page};

/// What went wrong making a page.
#[derive(Debug, thiserror::Error)]
pub enum WebError {
    #[error("{0}")]
    Setup(String),
    #[error("colour map {0}")]
    Colormap(String),
    #[error("the page cannot hold this scene: {0}")]
    TooLarge(String),
}

/// WebGPU's guaranteed `maxStorageBufferBindingSize` (128 MiB): a page
/// whose arrays fit in two such bindings each opens on every adapter.
pub const GUARANTEED_BINDING: u64 = 128 << 20;

/// Bytes per tetrahedron in the kernel's array ([`tetray_scene::WalkTet`]).
const TET_BYTES: u64 = 4 * tetray_gpu::TET_WORDS as u64;

/// The binding size a page's adapter needs, from its arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The smallest `maxStorageBufferBindingSize` that holds every array
    /// (tetrahedra and points in two bindings each, the BVH in one).
    pub binding_bytes: u64,
}

impl Limits {
    pub fn of(manifest: &Manifest) -> Limits {
        let half = |bytes: usize, element: u64| (bytes as u64 / element).div_ceil(2) * element;
        let tets = half(
            manifest.buffers.get("tets").copied().unwrap_or(0),
            TET_BYTES,
        );
        let points = half(manifest.buffers.get("points").copied().unwrap_or(0), 16);
        let bvh = manifest.buffers.get("bvh").copied().unwrap_or(0) as u64;
        Limits {
            binding_bytes: tets.max(points).max(bvh),
        }
    }

    /// Whether every WebGPU adapter can open the page.
    pub fn guaranteed(&self) -> bool {
        self.binding_bytes <= GUARANTEED_BINDING
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn manifest(tets: usize, points: usize, bvh: usize) -> Manifest {
        let json = serde_json::json!({
            "name": "m", "field": "f", "range": [0.0, 1.0], "unit_distance": 1.0,
            "tet_count": tets, "point_count": points, "boundary_faces": 0,
            "bounds": [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]], "scene_abs_max": 1.0,
            "prim_offset": 0, "face_offset": 0, "overlap_offset": 0, "overlap_count": 0, "origin": [0.0, 0.0, 0.0],
            "camera": {"position": [0.0, 0.0, 1.0], "focal_point": [0.0, 0.0, 0.0],
                       "view_up": [0.0, 1.0, 0.0], "view_angle": 30.0, "parallel_scale": null},
            "size": [8, 8], "background": [1.0, 1.0, 1.0], "early_termination": 1.0,
            "max_steps": 1, "method": "ppi", "methods": [], "colormaps": [], "bench": null,
            "buffers": {"tets": tets * TET_BYTES as usize, "points": points * 16, "bvh": bvh},
        });
        serde_json::from_value(json).expect("a manifest")
    }

    /// The page's script splits the tetrahedra at whole records.
    #[test]
    fn the_page_knows_the_record_size() {
        let script = include_str!("../page/gpu.js");
        let line = script
            .lines()
            .find_map(|l| l.strip_prefix("const TET_BYTES = "))
            .expect("TET_BYTES in gpu.js");
        assert_eq!(line.trim_end_matches(';').parse::<u64>(), Ok(TET_BYTES));
    }

    #[test]
    fn a_page_needs_half_its_larger_array_per_binding() {
        // 13.4 M tetrahedra: two 128 MiB bindings hold them.
        let most = 2 * (GUARANTEED_BINDING / TET_BYTES) as usize;
        let fits = Limits::of(&manifest(most, 1000, 4096));
        assert_eq!(
            fits.binding_bytes,
            GUARANTEED_BINDING / TET_BYTES * TET_BYTES
        );
        assert!(fits.guaranteed());
        let more = Limits::of(&manifest(most + 1, 1000, 4096));
        assert!(more.binding_bytes > GUARANTEED_BINDING);
        assert!(!more.guaranteed());
        // A BVH is never split.
        let bvh = Limits::of(&manifest(10, 10, 200 << 20));
        assert_eq!(bvh.binding_bytes, 200 << 20);
    }
}
