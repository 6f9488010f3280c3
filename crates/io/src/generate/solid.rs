//! A procedural nonconvex solid with analytic point scalars: a thick torus
//! shell (a hollow ring tube), tetrahedralized from its structured
//! parametrization.
//!
//! Point `(iu, iv, iw)` sits at angle `u = 2 pi iu / nu` around the z axis,
//! angle `v = 2 pi iv / nv` around the tube, and tube radius `rho` from
//! `inner_radius` (`iw = 0`) to `outer_radius` (`iw = nw`):
//! `((R + rho cos v) cos u, (R + rho cos v) sin u, rho sin v)`. Both angles
//! wrap around, so the grid is closed in u and v with no seam: with `nu`
//! and `nv` even, the alternating 5-tetrahedra split
//! ([`tetray_mesh::structured`]) matches its diagonals across the wrap too, and
//! the mesh is conforming everywhere. `(u, v, rho)` is right-handed, so
//! every tetrahedron comes out positively oriented.
//!
//! The boundary is two tori (the outer surface and the inner one around the
//! hollow), each of genus 1: rays leave and re-enter the mesh through the
//! hollow and through the ring's hole, up to four times each.

use std::f64::consts::TAU;
use std::fs::File;
use std::io;
use std::path::Path;

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::plan::check_requested;
use super::{GenerateError, MAX_TETS};
use crate::vtk::{TetChunks, VtuIndex, VtuStreamOptions, write_vtu_streamed};
use tetray_mesh::structured::{Templates, templates};
use tetray_mesh::{ScalarField, TetMesh};

/// Hexahedra per chunk of streamed tetrahedra.
pub(super) const CHUNK_HEXES: usize = 1 << 14;

/// The 5 tetrahedra of the hexahedron whose first corner is point
/// `(iu, iv, iw)` of the shell, in the shell's alternating split; each
/// corner `(iu, iv, iw)` (unwrapped) is numbered by `index`.
pub(super) fn cell_tets(
    t: &Templates,
    (iu, iv, iw): (usize, usize, usize),
    index: impl Fn(usize, usize, usize) -> u32,
) -> [[u32; 4]; 5] {
    t[(iu + iv + iw) % 2].map(|tet| {
        tet.map(|[du, dv, dw]| index(iu + du as usize, iv + dv as usize, iw + dw as usize))
    })
}

/// A thick torus shell around the z axis, centred at the origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorusShell {
    /// Distance from the z axis to the centre circle of the tube.
    pub major_radius: f64,
    /// Radius of the hollow inside the tube.
    pub inner_radius: f64,
    /// Outer radius of the tube.
    pub outer_radius: f64,
    /// Cells around the z axis (`nu`, even), around the tube (`nv`, even)
    /// and across the wall (`nw`).
    pub cells: [usize; 3],
}

/// The smooth analytic scalar, `wave = sin 3x cos 3y + sin(6z) / 2`
/// (values in [-1.5, 1.5]), computed in f64 at the stored f32 position.
pub fn wave(p: Vec3) -> f32 {
    let p = p.as_dvec3();
    ((3.0 * p.x).sin() * (3.0 * p.y).cos() + 0.5 * (6.0 * p.z).sin()) as f32
}

/// A linear scalar, `x + 2y + 3z`: piecewise-linear interpolation over any
/// tetrahedralization reproduces it exactly, so ray integrals through it
/// have closed forms.
pub fn linear(p: Vec3) -> f32 {
    let p = p.as_dvec3();
    (p.x + 2.0 * p.y + 3.0 * p.z) as f32
}

/// Names of the point fields, in order: [`wave`], [`linear`].
pub const FIELDS: [&str; 2] = ["wave", "linear"];

impl TorusShell {
    /// Ring radius 1, tube radii 0.25 (hollow) and 0.5 (outer).
    ///
    /// # Errors
    /// [`GenerateError::BadShell`] unless `nu` and `nv` are even and at
    /// least 4 and `nw` is at least 1; [`GenerateError::TooLarge`] beyond
    /// 32-bit point indices or [`MAX_TETS`] tetrahedra.
    pub fn new(cells: [usize; 3]) -> Result<Self, GenerateError> {
        let bad = |reason: &str| GenerateError::BadShell {
            cells,
            reason: reason.into(),
        };
        let [nu, nv, nw] = cells;
        if nu < 4 || nv < 4 || nu % 2 == 1 || nv % 2 == 1 {
            return Err(bad(
                "the cells around the axis and around the tube must be even (the split \
                 conforms across the wrap) and at least 4",
            ));
        }
        if nw == 0 {
            return Err(bad("at least one cell across the wall is needed"));
        }
        let too_large = |what: String, max: usize| GenerateError::TooLarge {
            dims: [nu, nv, nw + 1],
            factors: [1; 3],
            what,
            max,
        };
        let points = nu
            .checked_mul(nv)
            .and_then(|n| n.checked_mul(nw + 1))
            .filter(|&n| n <= u32::MAX as usize)
            .ok_or_else(|| too_large("too many points".into(), u32::MAX as usize))?;
        let tets = (points / (nw + 1) * nw).saturating_mul(5);
        if tets > MAX_TETS {
            return Err(too_large(format!("{tets} tetrahedra"), MAX_TETS));
        }
        Ok(TorusShell {
            major_radius: 1.0,
            inner_radius: 0.25,
            outer_radius: 0.5,
            cells,
        })
    }

    /// The shell with nearly cubic cells and at least `requested`
    /// tetrahedra, as few over as the cell counts allow: `nw` is rounded
    /// from the cubic cell edge that gives the count, then among the even
    /// `nu` within 10 % of the cubic ratio `nu : nv`, the one whose
    /// smallest even `nv` reaching the count overshoots least. The smallest
    /// shell is 4 x 4 x 1 cells (80 tetrahedra).
    ///
    /// # Errors
    /// [`GenerateError::TetCount`] for 0 or more than [`MAX_TETS`]; as
    /// [`TorusShell::new`].
    pub fn with_tets(requested: usize) -> Result<Self, GenerateError> {
        check_requested(requested)?;
        let shape = TorusShell::new([4, 4, 1])?;
        let thickness = shape.outer_radius - shape.inner_radius;
        let around = TAU * shape.major_radius;
        let tube = TAU * 0.5 * (shape.inner_radius + shape.outer_radius);
        let hexes = requested.div_ceil(5);
        let h = (around * tube * thickness / hexes as f64).cbrt();
        let nw = ((thickness / h).round() as usize).max(1);
        // nu / nv = around / tube, nu nv = hexes / nw.
        let ideal = (hexes as f64 / nw as f64 * around / tube).sqrt();
        let even_at_least = |x: usize| 2 * x.div_ceil(2).max(2);
        let lo = (2 * ((0.9 * ideal) as usize / 2)).max(4);
        let hi = even_at_least((1.1 * ideal).ceil() as usize);
        let (nu, nv) = (lo..=hi)
            .step_by(2)
            .map(|nu| (nu, even_at_least(hexes.div_ceil(nu * nw))))
            .min_by(|a, b| {
                let over = |(nu, nv): (usize, usize)| nu * nv;
                let off = |(nu, _): (usize, usize)| (nu as f64 - ideal).abs();
                over(*a).cmp(&over(*b)).then(off(*a).total_cmp(&off(*b)))
            })
            .unwrap_or((4, 4));
        TorusShell::new([nu, nv, nw])
    }

    pub fn point_count(&self) -> usize {
        let [nu, nv, nw] = self.cells;
        nu * nv * (nw + 1)
    }

    pub fn tet_count(&self) -> usize {
        5 * self.cells.iter().product::<usize>()
    }

    /// Index of point `(iu, iv, iw)` (angles wrapped).
    pub(super) fn index(&self, iu: usize, iv: usize, iw: usize) -> u32 {
        let [nu, nv, _] = self.cells;
        ((iu % nu) + nu * ((iv % nv) + nv * iw)) as u32
    }

    /// Position at `(u, v, rho)`, in f64.
    pub fn position(&self, u: f64, v: f64, rho: f64) -> DVec3 {
        let ring = self.major_radius + rho * v.cos();
        DVec3::new(ring * u.cos(), ring * u.sin(), rho * v.sin())
    }

    /// Every point, `iu` fastest, then `iv`, then `iw`.
    pub fn points(&self) -> Vec<Vec3> {
        let [nu, nv, nw] = self.cells;
        (0..self.point_count())
            .into_par_iter()
            .map(|p| {
                let (iu, iv, iw) = (p % nu, (p / nu) % nv, p / (nu * nv));
                let u = TAU * iu as f64 / nu as f64;
                let v = TAU * iv as f64 / nv as f64;
                let t = iw as f64 / nw as f64;
                let rho = self.inner_radius + (self.outer_radius - self.inner_radius) * t;
                self.position(u, v, rho).as_vec3()
            })
            .collect()
    }

    /// The fields [`FIELDS`] at `points`.
    pub fn fields(points: &[Vec3]) -> Vec<ScalarField> {
        TorusShell::fields_at(points, 0.0)
    }

    /// The fields [`FIELDS`] at `points` at time `t` of a series: the wave
    /// travels, `sin(3x + 2 pi t) cos 3y + sin(6z) / 2`, and the linear
    /// field grows, `(1 + t)(x + 2y + 3z)`; at `t = 0` they are [`wave`]
    /// and [`linear`].
    pub fn fields_at(points: &[Vec3], t: f64) -> Vec<ScalarField> {
        let field = |name: &str, f: &(dyn Fn(Vec3) -> f32 + Sync)| ScalarField {
            name: name.to_string(),
            values: points.par_iter().map(|&p| f(p)).collect(),
        };
        if t == 0.0 {
            return vec![field(FIELDS[0], &wave), field(FIELDS[1], &linear)];
        }
        let phase = std::f64::consts::TAU * t;
        let moving = move |p: Vec3| {
            let p = p.as_dvec3();
            ((3.0 * p.x + phase).sin() * (3.0 * p.y).cos() + 0.5 * (6.0 * p.z).sin()) as f32
        };
        let growing = move |p: Vec3| {
            let p = p.as_dvec3();
            ((1.0 + t) * (p.x + 2.0 * p.y + 3.0 * p.z)) as f32
        };
        vec![field(FIELDS[0], &moving), field(FIELDS[1], &growing)]
    }

    /// The 5 tetrahedra of hexahedron `h` (`iu` fastest).
    fn hex_tets(&self, t: &Templates, h: usize) -> [[u32; 4]; 5] {
        let [nu, nv, _] = self.cells;
        let corner = (h % nu, (h / nu) % nv, h / (nu * nv));
        cell_tets(t, corner, |iu, iv, iw| self.index(iu, iv, iw))
    }

    /// The whole mesh in memory (for tests and small sizes; large ones are
    /// streamed by [`TorusShell::write_vtu`]).
    pub fn mesh(&self) -> TetMesh {
        let t = templates();
        let points = self.points();
        TetMesh {
            fields: TorusShell::fields(&points),
            points,
            tets: (0..self.tet_count() / 5)
                .into_par_iter()
                .flat_map_iter(|h| self.hex_tets(&t, h))
                .collect(),
        }
    }

    /// Writes the mesh as a `.vtu` (appended raw data, Int32 indices when
    /// they fit), tetrahedra streamed. Returns the bytes written.
    ///
    /// # Errors
    /// [`GenerateError::Io`] naming the file.
    pub fn write_vtu(&self, path: &Path) -> Result<u64, GenerateError> {
        self.write_vtu_at(path, 0.0)
    }

    /// [`TorusShell::write_vtu`] with the fields at time `t` (see
    /// [`TorusShell::fields_at`]): the steps of a time series share the
    /// points and cells.
    ///
    /// # Errors
    /// [`GenerateError::Io`] naming the file.
    pub fn write_vtu_at(&self, path: &Path, t: f64) -> Result<u64, GenerateError> {
        let io_error = |source| GenerateError::Io {
            file: path.display().to_string(),
            source,
        };
        let points = self.points();
        let fields = TorusShell::fields_at(&points, t);
        let index = if 4 * self.tet_count() <= i32::MAX as usize {
            VtuIndex::Int32
        } else {
            VtuIndex::Int64
        };
        let options = VtuStreamOptions {
            index,
            header_u64: true,
            big_endian: false,
        };
        // The writer buffers.
        let mut file = File::create(path).map_err(io_error)?;
        write_vtu_streamed(&points, &fields, self, &mut file, &options).map_err(io_error)
    }
}

impl TetChunks for TorusShell {
    fn tet_count(&self) -> usize {
        TorusShell::tet_count(self)
    }

    fn for_each_chunk(
        &self,
        sink: &mut dyn FnMut(&[[u32; 4]]) -> io::Result<()>,
    ) -> io::Result<()> {
        let t = templates();
        let hexes = self.tet_count() / 5;
        let mut chunk = Vec::with_capacity(5 * CHUNK_HEXES);
        for start in (0..hexes).step_by(CHUNK_HEXES) {
            chunk.clear();
            for h in start..(start + CHUNK_HEXES).min(hexes) {
                chunk.extend(self.hex_tets(&t, h));
            }
            sink(&chunk)?;
        }
        Ok(())
    }
}
