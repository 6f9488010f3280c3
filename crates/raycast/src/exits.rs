//! The exits of the rays a thread keeps in flight, computed together: the
//! carried faces ([`Face`]) of all the rays held slot by slot and ray by
//! ray (one array per quantity and slot, a lane per ray), so that the
//! arithmetic of an exit (three edge functions, their signs, the exit
//! face's weights and barycentric interpolation, the new face) is one
//! vector operation for four rays instead of a chain per ray.
//!
//! Every lane computes what [`Face::exit`] computes, with the same
//! operations in the same order, so the bits are the same: the f32
//! quantities (distances, scalars) are held widened to f64, exactly, and
//! narrowed back exactly. A lane whose edge functions hold an exact zero
//! (the ray through a vertex or an edge), whose signs name no exit (a flat
//! cell) or whose exit face lies in the ray's plane is left to
//! [`Face::exit`] itself: all three are rare.

use crate::face::{FOLLOWING, Face, LEFT_OUT_SLOT, NONE, PRECEDING, Vertex};
use tetray_integrate::fastmath::{clamp_f32, max_f32, min_f32};
#[cfg(target_arch = "x86_64")]
use tetray_wide::avx2::F64x4;
use tetray_wide::{Wide, lanes};

/// The faces, the new vertices and the exits of `N` rays.
#[derive(Clone)]
pub(crate) struct Lanes<const N: usize> {
    /// Slot `j` of the face of lane `i` is `x[j][i]`, `y[j][i]`, ...; as
    /// in [`Face`], `edge[j]` is `E(v_j, v_{j+1})`.
    x: [[f64; N]; 3],
    y: [[f64; N]; 3],
    z: [[f64; N]; 3],
    s: [[f64; N]; 3],
    /// Slot 3 is unused: a slot masked to two bits indexes it without a
    /// bounds check. The vectors rank them as f64 (exact below 2^31, in
    /// order).
    id: [[u32; N]; 4],
    edge: [[f64; N]; 3],
    /// The vertex opposite each lane's face in its current cell. Its depth
    /// and scalar are kept as the f32 values the projection gives, widened
    /// to f64 as the exits read them (the same values, one conversion per
    /// four lanes); its position, which the exits' edge functions start
    /// from, is kept widened.
    apex_x: [f64; N],
    apex_y: [f64; N],
    apex_z: [f32; N],
    apex_s: [f32; N],
    apex_id: [u32; N],
    /// 1 where lane `i`'s ray is leaving its cell this round, else 0: a
    /// byte per lane, so that a lane's flag is one store, where a bit of a
    /// word took a load, a shift and a store.
    leaving: [u8; N],
    /// What [`Lanes::exits`] found: the rank of the vertex the exit face
    /// leaves out, the distance and the scalar; and 0 where lane `i` has
    /// them, 1 where it has not (it is resting, or left to [`Face::exit`]),
    /// so that a lane's exit is found by one test.
    rank: [u32; N],
    t: [f32; N],
    value: [f32; N],
    alone: [u8; N],
}

impl<const N: usize> Lanes<N> {
    pub fn new() -> Self {
        const { assert!(N <= 32) };
        Lanes {
            x: [[0.0; N]; 3],
            y: [[0.0; N]; 3],
            z: [[0.0; N]; 3],
            s: [[0.0; N]; 3],
            id: [[0; N]; 4],
            edge: [[0.0; N]; 3],
            apex_x: [0.0; N],
            apex_y: [0.0; N],
            apex_z: [0.0; N],
            apex_s: [0.0; N],
            apex_id: [0; N],
            leaving: [0; N],
            rank: [0; N],
            t: [0.0; N],
            value: [0.0; N],
            alone: [0; N],
        }
    }

    /// The face of `lane`.
    pub fn face(&self, lane: usize) -> Face {
        let mut face = Face::EMPTY;
        for j in 0..3 {
            face.x[j] = self.x[j][lane];
            face.y[j] = self.y[j][lane];
            face.z[j] = self.z[j][lane] as f32;
            face.s[j] = self.s[j][lane] as f32;
            face.id[j] = self.id[j][lane];
            face.edge[j] = self.edge[j][lane];
        }
        face
    }

    /// Makes `face` the face of `lane`.
    pub fn set_face(&mut self, lane: usize, face: &Face) {
        for j in 0..3 {
            self.x[j][lane] = face.x[j];
            self.y[j][lane] = face.y[j];
            self.z[j][lane] = f64::from(face.z[j]);
            self.s[j][lane] = f64::from(face.s[j]);
            self.id[j][lane] = face.id[j];
            self.edge[j][lane] = face.edge[j];
        }
    }

    /// The point index of the vertex opposite the face of `lane` in the
    /// tetrahedron whose point indices XOR to `vert_xor`.
    #[inline(always)]
    pub fn opposite(&self, lane: usize, vert_xor: u32) -> u32 {
        vert_xor ^ self.id[0][lane] ^ self.id[1][lane] ^ self.id[2][lane]
    }

    /// Makes `apex` the vertex `lane`'s ray leaves its cell against at the
    /// next [`Lanes::exits`].
    #[inline(always)]
    pub fn set_apex(&mut self, lane: usize, apex: Vertex) {
        self.apex_x[lane] = apex.x;
        self.apex_y[lane] = apex.y;
        self.apex_z[lane] = apex.z;
        self.apex_s[lane] = apex.s;
        self.apex_id[lane] = apex.id;
        self.leaving[lane] = 1;
    }

    /// Whether `lane` was given a vertex ([`Lanes::set_apex`]) since it
    /// last rested.
    #[inline(always)]
    pub fn is_leaving(&self, lane: usize) -> bool {
        self.leaving[lane] != 0
    }

    /// Marks `lane` as not leaving a cell at the next [`Lanes::exits`].
    #[inline(always)]
    pub fn rest(&mut self, lane: usize) {
        self.leaving[lane] = 0;
    }

    /// The exit [`Lanes::exits`] found for `lane` (the rank of the vertex
    /// the exit face leaves out, the distance and the scalar), if it found
    /// one: `None` for a resting lane and one left to [`Face::exit`] (see
    /// [`Lanes::exit`]).
    #[inline(always)]
    pub fn found(&self, lane: usize) -> Option<(usize, f32, f32)> {
        (self.alone[lane] == 0).then(|| (self.rank[lane] as usize, self.t[lane], self.value[lane]))
    }

    /// [`Face::exit`] of a lane given a vertex since it last rested,
    /// after [`Lanes::exits`], the lane's face now the exit face; `None`
    /// for a degenerate cell. The exit [`Lanes::found`], else the lane's
    /// own.
    #[inline(always)]
    pub fn exit(&mut self, lane: usize) -> Option<(usize, f32, f32)> {
        if let Some(exit) = self.found(lane) {
            return Some(exit);
        }
        let mut face = self.face(lane);
        let apex = Vertex {
            x: self.apex_x[lane],
            y: self.apex_y[lane],
            z: self.apex_z[lane],
            s: self.apex_s[lane],
            id: self.apex_id[lane],
        };
        let exit = face.exit(apex)?;
        self.set_face(lane, &face);
        Some(exit)
    }

    /// The exits of the live lanes, read by [`Lanes::exit`] (see the
    /// module's comment for the lanes left alone): four lanes to an AVX2
    /// vector where the caller holds the token, else lane by lane. The
    /// same bits either way.
    #[inline(always)]
    pub fn exits(&mut self, wide: Option<Wide>) {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = wide
            && N.is_multiple_of(4)
        {
            for quad in 0..N / 4 {
                self.exits_avx2(avx2, 4 * quad);
            }
            return;
        }
        let _ = wide;
        for lane in 0..N {
            self.exit_lane(lane);
        }
    }

    /// [`Lanes::exits`] of lane `i` alone, if it is leaving: the steps of
    /// [`Face::exit`] on the lane's slots.
    #[inline(always)]
    fn exit_lane(&mut self, i: usize) {
        if self.leaving[i] == 0 {
            self.alone[i] = 1;
            return;
        }
        let (dx, dy) = (self.apex_x[i], self.apex_y[i]);
        // E(d, v_j) of the three slots, as Face::exit.
        let e: [f64; 3] = std::array::from_fn(|j| dx * self.y[j][i] - dy * self.x[j][i]);
        let k = LEFT_OUT_SLOT[(lanes::positive_mask([e[0], e[1], e[2], 0.0]) & 7) as usize];
        if e[0] * e[1] * e[2] == 0.0 || k == NONE {
            self.alone[i] = 1;
            return;
        }
        let k = usize::from(k & 3);
        let (next, prev) = (FOLLOWING[k], PRECEDING[k]);
        let w = [self.edge[next][i], -e[prev], e[next]];
        let z = [
            self.apex_z[i],
            self.z[next][i] as f32,
            self.z[prev][i] as f32,
        ];
        let s = [f64::from(self.apex_s[i]), self.s[next][i], self.s[prev][i]];
        let sum = w[0] + w[1] + w[2];
        if sum == 0.0 {
            self.alone[i] = 1;
            return;
        }
        self.alone[i] = 0;
        let lo = min_f32(min_f32(z[0], z[1]), z[2]);
        let hi = max_f32(max_f32(z[0], z[1]), z[2]);
        let inv = 1.0 / sum;
        let t = (w[0] * f64::from(z[0]) + w[1] * f64::from(z[1]) + w[2] * f64::from(z[2])) * inv;
        self.t[i] = clamp_f32(t as f32, lo, hi);
        self.value[i] = ((w[0] * s[0] + w[1] * s[1] + w[2] * s[2]) * inv) as f32;
        // The rank of the left-out vertex among the cell's four, as
        // tetray_scene::vertex_rank.
        let ids = [self.id[0][i], self.id[1][i], self.id[2][i], self.apex_id[i]];
        self.rank[i] = tetray_scene::vertex_rank(ids, ids[k]) as u32;
        self.id[k][i] = self.apex_id[i];
        // The apex takes slot k, as Face::exit.
        self.x[k][i] = dx;
        self.y[k][i] = dy;
        self.z[k][i] = f64::from(self.apex_z[i]);
        self.s[k][i] = f64::from(self.apex_s[i]);
        self.edge[k][i] = e[next];
        self.edge[prev][i] = -e[prev];
    }
}

/// Bits 0 to 3 of `bits` as the bytes of the result, each 0 or 1 (bit `k`
/// in byte `k`, little-endian): one multiply, its copies of the four bits
/// at distinct positions (no carries), and a mask.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn spread_bits(bits: u32) -> u32 {
    (bits & 0xf).wrapping_mul(0x0020_4081) & 0x0101_0101
}

/// The inverse of [`spread_bits`]: bytes each 0 or 1 (little-endian) as
/// bits 0 to 3 of the result, by one multiply that adds the four bytes'
/// bits into bits 28 to 31 without carries.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn gather_bits(bytes: u32) -> u32 {
    bytes.wrapping_mul(0x1020_4080) >> 28
}

#[cfg(target_arch = "x86_64")]
impl<const N: usize> Lanes<N> {
    /// [`Lanes::exit_lane`] of lanes `i..i + 4` at once, in AVX2 vectors
    /// of f64, its branches as selects: the slot left out is three masks
    /// (one set unless the signs all agree), the point indices are ranked
    /// as f64 (exact below 2^31, in order). Every arithmetic operation is
    /// the scalar one, so the bits are the same.
    #[inline(always)]
    fn exits_avx2(&mut self, avx2: Wide, i: usize) {
        let zero = avx2.splat(0.0);
        let load = |a: &[f64; N]| avx2.load(a, i);
        let widen = |a: &[f32; N]| avx2.load_f32(a, i);
        let (dx, dy) = (load(&self.apex_x), load(&self.apex_y));
        let slots = |a: &[[f64; N]; 3]| [load(&a[0]), load(&a[1]), load(&a[2])];
        let (xs, ys) = (slots(&self.x), slots(&self.y));
        let e: [F64x4; 3] = std::array::from_fn(|j| dx * ys[j] - dy * xs[j]);
        let b = e.map(|e| e.gt(zero));
        // Slot k is left out when E(d, v_{k+1}) > 0 and E(d, v_{k+2}) is
        // not (LEFT_OUT_SLOT).
        let m = [b[2].and_not(b[1]), b[0].and_not(b[2]), b[1].and_not(b[0])];
        let next = |a: [_; 3]| m[0].select(a[1], m[1].select(a[2], a[0]));
        let prev = |a: [_; 3]| m[0].select(a[2], m[1].select(a[0], a[1]));
        let (e_next, e_prev) = (next(e), prev(e));
        let negated = e_prev.xor(avx2.splat(-0.0));
        let edge_next = next(slots(&self.edge));
        let w = [edge_next, negated, e_next];
        let (zs, ss) = (slots(&self.z), slots(&self.s));
        let z = [widen(&self.apex_z), next(zs), prev(zs)];
        let s = [widen(&self.apex_s), next(ss), prev(ss)];
        // min_f32(a, b) is `b < a ? b : a`: SSE's min(b, a).
        let lo = z[2].min(z[1].min(z[0]));
        let hi = z[2].max(z[1].max(z[0]));
        let sum = w[0] + w[1] + w[2];
        let one = avx2.splat(1.0);
        let inv = one / sum;
        let blend = |v: [F64x4; 3]| (w[0] * v[0] + w[1] * v[1] + w[2] * v[2]) * inv;
        let product = e[0] * e[1] * e[2];
        let some = m[0].or(m[1]).or(m[2]);
        let none = some.xor(avx2.splat(f64::from_bits(u64::MAX)));
        let alone = product.eq(zero).or(none).or(sum.eq(zero));
        // The rank of the left-out vertex, as Lanes::exit_lane.
        let ids: [F64x4; 3] = std::array::from_fn(|j| avx2.load_u32(&self.id[j], i));
        let apex_id = avx2.load_u32(&self.apex_id, i);
        // Slot k's: the slot following the one before k.
        let left_out = next([ids[2], ids[0], ids[1]]);
        let below = |id: F64x4| id.lt(left_out).and(one);
        let rank = below(ids[0]) + below(ids[1]) + below(ids[2]) + below(apex_id);
        rank.store_i32(&mut self.rank, i);
        // clamp_f32(t, lo, hi) is SSE's min(hi, max(lo, t)).
        hi.min(lo.max(blend(z).round_f32()))
            .store_f32(&mut self.t, i);
        blend(s).store_f32(&mut self.value, i);
        let leaving: [u8; 4] = self.leaving[i..i + 4].try_into().expect("four lanes");
        let leaving = gather_bits(u32::from_le_bytes(leaving));
        let live = avx2.lane_mask(leaving);
        // A resting lane has no exit either.
        let alone_bytes = spread_bits(alone.bits() | !leaving);
        self.alone[i..i + 4].copy_from_slice(&alone_bytes.to_le_bytes());
        let moves = alone.and_not(live);
        if moves.bits() == 0xf {
            // Every lane leaves: the exit face in the order (apex, next,
            // prev), all slots written. That is Face::exit's face (the apex
            // in slot k) turned cyclically: the same face, whose exits are
            // the same, as each is found relative to the slot left out.
            let new = [
                [dx, next(xs), prev(xs)],
                [dy, next(ys), prev(ys)],
                z,
                s,
                [e_next, edge_next, negated],
            ];
            let arrays = [
                &mut self.x,
                &mut self.y,
                &mut self.z,
                &mut self.s,
                &mut self.edge,
            ];
            for (array, new) in arrays.into_iter().zip(new) {
                for (slot, lanes) in array.iter_mut().zip(new) {
                    lanes.store(slot, i);
                }
            }
            let new_ids = [apex_id, next(ids), prev(ids)];
            for (slot, lanes) in self.id.iter_mut().zip(new_ids) {
                lanes.store_i32(slot, i);
            }
        } else {
            // The apex takes slot k of the lanes that leave; the exit
            // face's edges, as Face::exit.
            let apex = [dx, dy, z[0], s[0]];
            for j in 0..3 {
                let take = moves.and(m[j]);
                let before = moves.and(m[(j + 1) % 3]);
                // The indices as loaded above: a select and a store of
                // another type, which never becomes a masked store.
                take.select(apex_id, ids[j]).store_i32(&mut self.id[j], i);
                let arrays = [
                    &mut self.x[j],
                    &mut self.y[j],
                    &mut self.z[j],
                    &mut self.s[j],
                ];
                for (array, new) in arrays.into_iter().zip(apex) {
                    take.select(new, avx2.load_to_blend(array, i))
                        .store(array, i);
                }
                let kept = before.select(negated, avx2.load_to_blend(&self.edge[j], i));
                take.select(e_next, kept).store(&mut self.edge[j], i);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::face::tests::random_entries;

    /// Random faces and apices in lanes, some lanes resting and some
    /// through a face vertex (an exact zero left to Face::exit): every
    /// live lane's exit and new face have the bits of Face::exit's.
    #[test]
    fn lanes_give_the_single_face_bits() {
        const N: usize = 8;
        let wides: &[bool] = if tetray_wide::detected() {
            &[false, true]
        } else {
            &[false]
        };
        for &wide in wides {
            compare_lanes::<N>(wide);
        }
    }

    fn compare_lanes<const N: usize>(wide: bool) {
        let entries = random_entries(4000);
        let mut lanes = Lanes::<N>::new();
        let (mut compared, mut alone, mut whole) = (0, 0, 0);
        for (round, chunk) in entries.chunks(N).enumerate() {
            let mut expected = Vec::new();
            for (lane, entered) in chunk.iter().enumerate() {
                let (face, mut apex) = (&entered.face, entered.apex);
                if (round + lane) % 7 == 0 {
                    // On the line through the origin and vertex 0: an
                    // exact zero edge function.
                    apex.x = face.x[0] * 2.0;
                    apex.y = face.y[0] * 2.0;
                }
                lanes.set_face(lane, face);
                if (round + lane) % 5 == 3 {
                    lanes.rest(lane);
                    expected.push(None);
                } else {
                    lanes.set_apex(lane, apex);
                    let mut after = *face;
                    let exit = after.exit(apex);
                    expected.push(Some((exit, after)));
                }
            }
            tetray_wide::run(wide, || lanes.exits(tetray_wide::token(wide)));
            // Quads whose four lanes all leave (the whole faces written).
            whole += (0..N / 4)
                .filter(|q| {
                    (4 * q..4 * q + 4).all(|i| lanes.leaving[i] == 1 && lanes.alone[i] == 0)
                })
                .count();
            for (lane, expected) in expected.into_iter().enumerate() {
                let before = lanes.face(lane);
                let bits =
                    |e: Option<(usize, f32, f32)>| e.map(|(r, t, s)| (r, t.to_bits(), s.to_bits()));
                let Some((exit, after)) = expected else {
                    // A resting lane keeps its face and has no exit.
                    assert_same_face(&before, &chunk[lane].face);
                    assert_eq!(lanes.found(lane), None, "round {round} lane {lane}");
                    continue;
                };
                alone += usize::from(lanes.alone[lane]);
                // What the lanes found is the exit, where they found one.
                if let Some(found) = lanes.found(lane) {
                    assert_eq!(bits(Some(found)), bits(exit), "round {round} lane {lane}");
                }
                let got = lanes.exit(lane);
                assert_eq!(bits(got), bits(exit), "round {round} lane {lane}");
                if exit.is_some() {
                    assert_same_face_turned(&lanes.face(lane), &after);
                }
                compared += 1;
            }
        }
        assert!(
            compared > 2500 && alone > 300 && whole > 50,
            "{compared} compared, {alone} alone, {whole} whole quads"
        );
    }

    /// The bit-byte conversions of the vectors' masks, every pattern.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn bits_spread_to_bytes_and_back() {
        for bits in 0..16u32 {
            let bytes = spread_bits(bits);
            let expected: Vec<u8> = (0..4).map(|k| (bits >> k & 1) as u8).collect();
            assert_eq!(bytes.to_le_bytes().to_vec(), expected);
            assert_eq!(gather_bits(bytes), bits);
        }
    }

    /// `a` is `b` with its slots turned cyclically (the same face: the
    /// wide exits put the apex in slot 0 where Face::exit puts it in the
    /// slot left out).
    fn assert_same_face_turned(a: &Face, b: &Face) {
        let turned = |r: usize| {
            let mut t = Face::EMPTY;
            for j in 0..3 {
                let k = (j + r) % 3;
                (t.x[j], t.y[j], t.z[j]) = (b.x[k], b.y[k], b.z[k]);
                (t.s[j], t.id[j], t.edge[j]) = (b.s[k], b.id[k], b.edge[k]);
            }
            t
        };
        let same = |t: &Face| {
            (0..3).all(|j| {
                a.x[j].to_bits() == t.x[j].to_bits()
                    && a.y[j].to_bits() == t.y[j].to_bits()
                    && a.z[j].to_bits() == t.z[j].to_bits()
                    && a.s[j].to_bits() == t.s[j].to_bits()
                    && a.id[j] == t.id[j]
                    && a.edge[j].to_bits() == t.edge[j].to_bits()
            })
        };
        assert!((0..3).any(|r| same(&turned(r))), "not the same face turned");
    }

    fn assert_same_face(a: &Face, b: &Face) {
        for j in 0..3 {
            assert_eq!(a.x[j].to_bits(), b.x[j].to_bits());
            assert_eq!(a.y[j].to_bits(), b.y[j].to_bits());
            assert_eq!(a.z[j].to_bits(), b.z[j].to_bits());
            assert_eq!(a.s[j].to_bits(), b.s[j].to_bits());
            assert_eq!(a.id[j], b.id[j]);
            assert_eq!(a.edge[j].to_bits(), b.edge[j].to_bits());
        }
    }
}
