//! One frame: the factorization of the view, compositing of the sheared
//! slabs into the intermediate image (one scanline per rayon task), and the
//! 2-D warp to the final image.
//!
//! Coordinates: in "traversal" index space `(x, y, t)`, `x` and `y` index
//! the slice axes `a` and `b`, `t` counts slices from the one nearest the
//! eye (`t = 0`). The rays of the intermediate image pass through the
//! points `(x0, y0, 0)` of the front slice, `x0 = u - ou`, and reach slice
//! `t` at `x = x0 g(t) + ex(t)`: `g = 1` and `ex = sa t` for a parallel
//! projection (a shear), `g = 1 + t / -Et` and `ex = Ex t / Et` from the eye
//! `E` for perspective (a shear and a scale).

use std::time::{Duration, Instant};

use glam::{DVec3, Vec3A};
use rayon::prelude::*;
use tetray_core::{Camera, Image};

use crate::classify::SlabLight;
use crate::stack::{Stack, axes_of};
use crate::{Classification, ShearWarp, ShearWarpError};
use tetray_integrate::SegmentLight;

/// What to render and how.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearWarpOptions {
    pub width: u32,
    pub height: u32,
    /// Stop a ray once its opacity `1 - mean(T)` reaches this; 1 disables.
    pub early_termination: f32,
    /// Skip runs of empty cells (never changes the image).
    pub skip_empty: bool,
}

impl Default for ShearWarpOptions {
    fn default() -> Self {
        ShearWarpOptions {
            width: 512,
            height: 512,
            early_termination: 1.0,
            skip_empty: true,
        }
    }
}

/// Counters of one frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearWarpStats {
    /// Principal viewing axis (0 = x).
    pub principal_axis: usize,
    pub intermediate_width: usize,
    pub intermediate_height: usize,
    /// Slab length of a parallel projection (world units).
    pub slab_length: Option<f32>,
    pub slabs_composited: u64,
    /// Slabs inside the grid skipped as empty.
    pub slabs_skipped: u64,
    /// Rays stopped by early termination.
    pub rays_terminated: u64,
    pub composite_time: Duration,
    pub warp_time: Duration,
    pub elapsed: Duration,
}

/// A rendered frame.
#[derive(Debug, Clone)]
pub struct ShearWarpOutput {
    pub image: Image,
    pub stats: ShearWarpStats,
}

/// The factorized view.
#[derive(Debug, Clone, Copy)]
struct View {
    axes: [usize; 3],
    flip: bool,
    na: usize,
    nb: usize,
    nc: usize,
    /// Parallel: `(sa, sb)` per slice; perspective: the eye `(Ex, Ey, Et)`.
    shear: (f64, f64),
    eye: Option<DVec3>,
    ou: f64,
    ov: f64,
    nu: usize,
    nv: usize,
    spacing: DVec3,
    origin: DVec3,
}

impl View {
    #[inline]
    fn g(&self, t: f64) -> f64 {
        match self.eye {
            None => 1.0,
            Some(e) => 1.0 - t / e.z,
        }
    }

    /// `(ex, ey)` at slice `t`.
    #[inline]
    fn offset(&self, t: f64) -> (f64, f64) {
        match self.eye {
            None => (self.shear.0 * t, self.shear.1 * t),
            Some(e) => (e.x * t / e.z, e.y * t / e.z),
        }
    }

    /// Traversal coordinates of a world point.
    fn traversal(&self, p: DVec3) -> DVec3 {
        let idx = (p - self.origin) / self.spacing;
        let [a, b, c] = self.axes;
        let t = if self.flip {
            (self.nc - 1) as f64 - idx[c]
        } else {
            idx[c]
        };
        DVec3::new(idx[a], idx[b], t)
    }

    /// Traversal components of a world direction.
    fn traversal_dir(&self, d: DVec3) -> DVec3 {
        let idx = d / self.spacing;
        let [a, b, c] = self.axes;
        DVec3::new(idx[a], idx[b], if self.flip { -idx[c] } else { idx[c] })
    }

    /// World length of a step of one slice with in-slice step `(dx, dy)`.
    fn step_length(&self, dx: f64, dy: f64) -> f64 {
        let [a, b, c] = self.axes;
        DVec3::new(dx * self.spacing[a], dy * self.spacing[b], self.spacing[c]).length()
    }
}

impl ShearWarp {
    /// Renders the grid seen by `camera`.
    pub fn render(
        &self,
        camera: &Camera,
        opts: &ShearWarpOptions,
    ) -> Result<ShearWarpOutput, ShearWarpError> {
        let start = Instant::now();
        let thr = opts.early_termination;
        if thr.is_nan() || thr <= 0.0 {
            return Err(ShearWarpError::BadEarlyTermination(thr));
        }
        let rays = camera.pixel_rays(opts.width, opts.height)?;
        let mut image = Image::new(opts.width, opts.height)?;
        let view = self.factorize(camera)?;
        let stack = self.stack(view.axes[2]);
        let slab_length = view
            .eye
            .is_none()
            .then(|| view.step_length(view.shear.0, view.shear.1) as f32);
        let light = SlabLight::new(&self.classifier, slab_length);
        let pre = self.classification == Classification::PreIntegrated;

        // Composite: one intermediate scanline per task.
        let composite_start = Instant::now();
        let mut inter = vec![(Vec3A::ZERO, Vec3A::ONE); view.nu * view.nv];
        let counters = inter
            .par_chunks_mut(view.nu)
            .enumerate()
            .map(|(v, row)| {
                let mut line = Scanline {
                    view: &view,
                    stack,
                    light: &light,
                    slab_length,
                    pre,
                    skip: opts.skip_empty,
                    threshold: thr,
                    y0: v as f64 - view.ov,
                    row,
                    next: (0..=view.nu as u32).collect(),
                    buf_t: vec![u32::MAX; view.nu],
                    buf_s: vec![0.0; view.nu],
                    counts: [0; 3],
                };
                line.composite();
                line.counts
            })
            .reduce(|| [0; 3], |a, b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
        let composite_time = composite_start.elapsed();

        // Warp: every final pixel's ray meets the front slice at (u, v).
        let warp_start = Instant::now();
        let width = opts.width as usize;
        image
            .rgba
            .par_chunks_mut(width)
            .enumerate()
            .for_each(|(py, out)| {
                for (px, pixel) in out.iter_mut().enumerate() {
                    let ray = rays.ray(px as u32, py as u32);
                    let o = view.traversal(ray.origin.as_dvec3());
                    let d = view.traversal_dir(ray.dir.as_dvec3());
                    if d.z <= 0.0 {
                        continue;
                    }
                    let s = -o.z / d.z;
                    let u = o.x + s * d.x + view.ou;
                    let v = o.y + s * d.y + view.ov;
                    let (c, t) = bilinear(&inter, view.nu, view.nv, u, v);
                    *pixel = [c.x, c.y, c.z, 1.0 - (t.x + t.y + t.z) / 3.0];
                }
            });
        let stats = ShearWarpStats {
            principal_axis: view.axes[2],
            intermediate_width: view.nu,
            intermediate_height: view.nv,
            slab_length,
            slabs_composited: counters[0],
            slabs_skipped: counters[1],
            rays_terminated: counters[2],
            composite_time,
            warp_time: warp_start.elapsed(),
            elapsed: start.elapsed(),
        };
        Ok(ShearWarpOutput { image, stats })
    }

    /// The principal axis, the traversal order, the shear (or the eye) and
    /// the intermediate image's extent.
    fn factorize(&self, camera: &Camera) -> Result<View, ShearWarpError> {
        let basis = camera.basis()?;
        let spacing = self.grid.spacing().as_dvec3();
        let origin = self.grid.origin().as_dvec3();
        let dims = self.grid.dims();
        let dv = basis.direction.as_dvec3() / spacing;
        let c = (0..3)
            .max_by(|&i, &j| dv[i].abs().total_cmp(&dv[j].abs()))
            .unwrap_or(2);
        let axes = axes_of(c);
        let [na, nb, nc] = axes.map(|a| dims[a]);
        let mut view = View {
            axes,
            flip: dv[c] < 0.0,
            na,
            nb,
            nc,
            shear: (0.0, 0.0),
            eye: None,
            ou: 0.0,
            ov: 0.0,
            nu: 0,
            nv: 0,
            spacing,
            origin,
        };
        if camera.parallel_scale.is_none() {
            let idx = (camera.position.as_dvec3() - origin) / spacing;
            let last = (nc - 1) as f64;
            view.flip = if idx[c] < 0.0 {
                false
            } else if idx[c] > last {
                true
            } else {
                return Err(ShearWarpError::EyeInsideSlab {
                    axis: ['x', 'y', 'z'][c],
                    index: idx[c],
                    last: nc - 1,
                });
            };
            view.eye = Some(view.traversal(camera.position.as_dvec3()));
        } else {
            let d = view.traversal_dir(basis.direction.as_dvec3());
            view.shear = (d.x / d.z, d.y / d.z);
        }
        // The front-slice coordinates of every slice's corners.
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for t in [0.0, (nc - 1) as f64] {
            let (g, (ex, ey)) = (view.g(t), view.offset(t));
            for (x, y) in [(0.0, 0.0), ((na - 1) as f64, (nb - 1) as f64)] {
                let p = DVec3::new((x - ex) / g, (y - ey) / g, 0.0);
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        view.ou = -lo.x.floor();
        view.ov = -lo.y.floor();
        view.nu = (hi.x.ceil() - lo.x.floor()) as usize + 1;
        view.nv = (hi.y.ceil() - lo.y.floor()) as usize + 1;
        Ok(view)
    }
}

/// The intermediate image at real pixel `(u, v)`, clear outside.
fn bilinear(inter: &[(Vec3A, Vec3A)], nu: usize, nv: usize, u: f64, v: f64) -> (Vec3A, Vec3A) {
    if !(u > -1.0 && v > -1.0 && u < nu as f64 && v < nv as f64) {
        return (Vec3A::ZERO, Vec3A::ONE);
    }
    let (i, j) = (u.floor(), v.floor());
    let (fu, fv) = ((u - i) as f32, (v - j) as f32);
    let (i, j) = (i as i64, j as i64);
    let at = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= nu as i64 || y >= nv as i64 {
            (Vec3A::ZERO, Vec3A::ONE)
        } else {
            inter[y as usize * nu + x as usize]
        }
    };
    let (p00, p10, p01, p11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
    let mix = |a: Vec3A, b: Vec3A, c: Vec3A, d: Vec3A| a.lerp(b, fu).lerp(c.lerp(d, fu), fv);
    (
        mix(p00.0, p10.0, p01.0, p11.0),
        mix(p00.1, p10.1, p01.1, p11.1),
    )
}

/// One intermediate scanline being composited.
struct Scanline<'a> {
    view: &'a View,
    stack: &'a Stack,
    light: &'a SlabLight<'a>,
    slab_length: Option<f32>,
    pre: bool,
    skip: bool,
    threshold: f32,
    y0: f64,
    /// Accumulated (emitted, transmittance) per pixel.
    row: &'a mut [(Vec3A, Vec3A)],
    /// Opaque-pixel links: `next[u]` leads to the first pixel at or after
    /// `u` still compositing (Lacroute's early ray termination).
    next: Vec<u32>,
    /// Buffer slice: the sample of slice `buf_t[u]` at pixel `u`.
    buf_t: Vec<u32>,
    buf_s: Vec<f32>,
    /// Slabs composited, slabs skipped, rays terminated.
    counts: [u64; 3],
}

impl Scanline<'_> {
    fn find(&mut self, mut u: usize) -> usize {
        while self.next[u] as usize != u {
            let n = self.next[u] as usize;
            self.next[u] = self.next[n];
            u = n;
        }
        u
    }

    fn composite(&mut self) {
        let view = *self.view;
        let (na, nb) = (view.na, view.nb);
        let (xmax, ymax) = ((na - 1) as f64, (nb - 1) as f64);
        for t in 0..view.nc - 1 {
            if self.find(0) >= view.nu {
                break;
            }
            let (tf, tb) = (t as f64, (t + 1) as f64);
            let (gf, gb) = (view.g(tf), view.g(tb));
            let ((exf, eyf), (exb, eyb)) = (view.offset(tf), view.offset(tb));
            let (yf, yb) = (self.y0 * gf + eyf, self.y0 * gb + eyb);
            // The part of the slab this scanline's rays spend between the
            // grid's first and last rows.
            let Some((sy0, sy1)) = clip(yf, yb, ymax) else {
                continue;
            };
            let slab = Slab {
                t,
                gf,
                gb,
                exf,
                exb,
                yf,
                yb,
            };
            // Pixels whose ray meets the grid in this slab at all.
            let (mut any_lo, mut any_hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for s in [sy0, sy1] {
                let (g, ex) = (gf + s * (gb - gf), exf + s * (exb - exf));
                any_lo = any_lo.min(-ex / g + view.ou);
                any_hi = any_hi.max((xmax - ex) / g + view.ou);
            }
            let any_lo = any_lo.ceil().max(0.0) as usize;
            let any_hi = any_hi.floor().min((view.nu - 1) as f64);
            if any_hi < any_lo as f64 {
                continue;
            }
            let any_hi = any_hi as usize;
            // Pixels whose ray is inside both slices.
            let lo = ((0.0 - exf) / gf).max((0.0 - exb) / gb) + view.ou;
            let hi = ((xmax - exf) / gf).min((xmax - exb) / gb) + view.ou;
            let u_lo = lo.ceil().max(any_lo as f64) as usize;
            let u_hi = hi.floor().min(any_hi as f64);
            if sy0 > 0.0 || sy1 < 1.0 || hi < lo || u_hi < u_lo as f64 {
                // The rays cross a side of the grid in this slab.
                self.partial(&slab, any_lo, any_hi, (sy0, sy1));
                continue;
            }
            let u_hi = u_hi as usize;
            if any_lo < u_lo {
                self.partial(&slab, any_lo, u_lo - 1, (sy0, sy1));
            }
            if u_hi < any_hi {
                self.partial(&slab, u_hi + 1, any_hi, (sy0, sy1));
            }
            if !self.skip {
                self.stretch(&slab, u_lo, u_hi);
                continue;
            }
            // Merge the runs of the front and back cell rows.
            let (kf, kb) = (self.slice(t), self.slice(t + 1));
            let (jf, jb) = (yf as usize, yb as usize);
            let cell = |u: usize, g: f64, ex: f64| {
                (((u as f64 - view.ou) * g + ex).floor().clamp(0.0, xmax)) as usize
            };
            let mut u = u_lo;
            while u <= u_hi {
                let rf = self.stack.run(kf, jf, cell(u, gf, exf));
                let rb = self.stack.run(kb, jb, cell(u, gb, exb));
                let last = |end: u32, g: f64, ex: f64| {
                    let mut w = ((end as f64 - ex) / g + view.ou).floor().max(u as f64) as usize;
                    w = w.min(u_hi);
                    while w > u && cell(w, g, ex) >= end as usize {
                        w -= 1;
                    }
                    while w < u_hi && cell(w + 1, g, ex) < end as usize {
                        w += 1;
                    }
                    w
                };
                let end = last(rf.end, gf, exf).min(last(rb.end, gb, exb));
                let empty = if self.pre {
                    rf.class != 0 && rf.class == rb.class
                } else {
                    rf.class != 0
                };
                if empty {
                    self.counts[1] += (end - u + 1) as u64;
                } else {
                    self.stretch(&slab, u, end);
                }
                u = end + 1;
            }
        }
    }

    /// The grid slice of traversal slice `t`.
    #[inline]
    fn slice(&self, t: usize) -> usize {
        if self.view.flip {
            self.view.nc - 1 - t
        } else {
            t
        }
    }

    /// Bilinear sample of traversal slice `t` at `(x, y)` (inside it).
    #[inline]
    fn sample(&self, t: usize, x: f64, y: f64) -> f32 {
        let s = self.stack;
        let (na, nb) = (s.na, s.nb);
        let i = (x as usize).min(na - 2);
        let j = (y as usize).min(nb - 2);
        let (wx, wy) = ((x - i as f64) as f32, (y - j as f64) as f32);
        let base = (self.slice(t) * nb + j) * na + i;
        let d = &s.data;
        let near = d[base] * (1.0 - wx) + d[base + 1] * wx;
        let far = d[base + na] * (1.0 - wx) + d[base + na + 1] * wx;
        near * (1.0 - wy) + far * wy
    }

    /// Composites slab `slab` at the pixels `u0..=u1` still compositing.
    fn stretch(&mut self, slab: &Slab, u0: usize, u1: usize) {
        let view = *self.view;
        let xmax = (view.na - 1) as f64;
        let mut u = self.find(u0);
        while u <= u1 {
            let x0 = u as f64 - view.ou;
            let (xf, xb) = (x0 * slab.gf + slab.exf, x0 * slab.gb + slab.exb);
            if (0.0..=xmax).contains(&xf) && (0.0..=xmax).contains(&xb) {
                let s_f = if self.buf_t[u] == slab.t as u32 {
                    self.buf_s[u]
                } else {
                    self.sample(slab.t, xf, slab.yf)
                };
                let s_b = self.sample(slab.t + 1, xb, slab.yb);
                self.buf_t[u] = slab.t as u32 + 1;
                self.buf_s[u] = s_b;
                let length = self.full_length(x0);
                let light = self.light.light(s_f, s_b, length);
                self.blend(u, &light);
            }
            u = self.find(u + 1);
        }
    }
}

impl Scanline<'_> {
    /// The world length of the whole slab along the ray of pixel `x0`.
    fn full_length(&self, x0: f64) -> f32 {
        match self.slab_length {
            Some(l) => l,
            None => {
                let e = self.view.eye.unwrap_or_default();
                let d = -e.z;
                self.view.step_length((x0 - e.x) / d, (self.y0 - e.y) / d) as f32
            }
        }
    }

    /// Adds a slab's light to pixel `u`; marks the pixel opaque when it
    /// reaches the early-termination threshold.
    fn blend(&mut self, u: usize, light: &SegmentLight) {
        let px = &mut self.row[u];
        px.0 += px.1 * light.emitted;
        px.1 *= light.transmittance;
        self.counts[0] += 1;
        if self.threshold < 1.0 && 1.0 - (px.1.x + px.1.y + px.1.z) / 3.0 >= self.threshold {
            self.next[u] = u as u32 + 1;
            self.counts[2] += 1;
        }
    }

    /// Composites the part of slab `slab` inside the grid at the pixels
    /// `u0..=u1` still compositing, whose rays cross a side face of the
    /// grid between the slab's two slices: the ray's parameter `s` (0 at
    /// the front slice, 1 at the back one) is clipped to the grid's box
    /// (`sy`: the scanline's clip to the rows), the scalar taken
    /// trilinearly at the clipped ends, and the light scaled to the
    /// clipped length (`1 - (1 - a)^(l / d)` and the colour with it).
    fn partial(&mut self, slab: &Slab, u0: usize, u1: usize, sy: (f64, f64)) {
        let view = *self.view;
        let xmax = (view.na - 1) as f64;
        let ymax = (view.nb - 1) as f64;
        let mut u = self.find(u0);
        while u <= u1 {
            let x0 = u as f64 - view.ou;
            let (xf, xb) = (x0 * slab.gf + slab.exf, x0 * slab.gb + slab.exb);
            if let Some((sx0, sx1)) = clip(xf, xb, xmax) {
                let (s0, s1) = (sx0.max(sy.0), sx1.min(sy.1));
                if s1 > s0 {
                    let at = |s: f64| {
                        let x = (xf + s * (xb - xf)).clamp(0.0, xmax);
                        let y = (slab.yf + s * (slab.yb - slab.yf)).clamp(0.0, ymax);
                        let w = s as f32;
                        self.sample(slab.t, x, y) * (1.0 - w) + self.sample(slab.t + 1, x, y) * w
                    };
                    let (a, b) = (at(s0), at(s1));
                    let light = self
                        .light
                        .part(a, b, self.full_length(x0), (s1 - s0) as f32);
                    // The back sample is not the slice's at this pixel.
                    self.buf_t[u] = u32::MAX;
                    self.blend(u, &light);
                }
            }
            u = self.find(u + 1);
        }
    }
}

/// The parameters `s` in 0..=1 where `a + s (b - a)` lies in `0..=max`,
/// when there are any (an interval of positive length, or all of 0..=1).
fn clip(a: f64, b: f64, max: f64) -> Option<(f64, f64)> {
    if a == b {
        return (0.0..=max).contains(&a).then_some((0.0, 1.0));
    }
    let (p, q) = ((0.0 - a) / (b - a), (max - a) / (b - a));
    let (lo, hi) = (p.min(q).max(0.0), p.max(q).min(1.0));
    (hi > lo).then_some((lo, hi))
}

/// The geometry of the slab between traversal slices `t` and `t + 1` on
/// one scanline.
struct Slab {
    t: usize,
    gf: f64,
    gb: f64,
    exf: f64,
    exb: f64,
    yf: f64,
    yb: f64,
}
