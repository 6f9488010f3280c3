//! One ray through the mesh: enter through the boundary (BVH), walk tet to
//! tet across exit faces, integrate each segment, composite front to back
//! (dissertation ch. 2: the ray integral is a product of segment
//! transmittances and a sum of attenuated segment emissions).

use glam::{Vec3, Vec3A};
use tetray_boundary_bvh::reentry_start;
use tetray_core::watertight::{Projector, RayFrame};
use tetray_integrate::SampledSegment;
use tetray_integrate::fastmath::max_f32;

use crate::entries::EntryList;
use crate::exits::Lanes;
use crate::face::{Face, Vertex};
use crate::holes::Holes;
use crate::segment::SegmentIntegrator;
use tetray_scene::{FINAL_EXIT, Scene, WalkTet};

/// The arrays a step of the walk reads, taken out of the scene once per
/// band: handed to each stage by value, their pointers and lengths stay in
/// registers or the stack frame instead of being loaded through the scene
/// at every step.
#[derive(Clone, Copy)]
pub(crate) struct Cells<'a> {
    pub records: &'a [WalkTet],
    pub points: &'a [[f32; 4]],
}

impl<'a> Cells<'a> {
    pub fn of(scene: &'a Scene) -> Self {
        Cells {
            records: scene.walk_records(),
            points: scene.point_records(),
        }
    }
}

/// Limits of one walk.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WalkLimits {
    /// Stop once the sum of the transmittance channels is at most this:
    /// `3 (1 - early_termination)`, so `1 - mean(T) >= early_termination`.
    pub stop_below_sum: f32,
    pub max_steps: u64,
}

/// What one ray did, summed into the frame's statistics.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct RayCounters {
    pub hit: bool,
    pub segments: u64,
    pub entries: u64,
    pub steps: u64,
    pub step_bound_hit: bool,
    pub walk_failure: bool,
    pub overlap_segments: u64,
    pub overlap_overflow: bool,
}

/// Light gathered along one ray: premultiplied colour and transmittance.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RayLight {
    pub color: Vec3A,
    pub transmittance: Vec3A,
}

impl RayLight {
    const CLEAR: RayLight = RayLight {
        color: Vec3A::ZERO,
        transmittance: Vec3A::ONE,
    };
}

/// The light of one contiguous interval of a ray inside the mesh (from an
/// entry through a boundary face to the next exit through one), composited
/// alone: what a split walk emits instead of compositing the whole ray.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Interval {
    /// Distance of the interval's entry along the ray, clipped at the ray
    /// origin (where its first segment starts).
    pub depth: f32,
    pub light: RayLight,
}

/// Where a [`Walker`] is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Between entries: the next step asks the BVH where the ray enters.
    Entering,
    /// Inside the mesh, in the cell `Walker::crossing` names until
    /// [`Walker::leave`] finds the exit; from [`Walker::leave`] to
    /// [`Walker::end`], half-way through a step: the exit is found, the
    /// segment is classified and integrated, and its light composited
    /// before the ray moves to `Walker::crossing` (a cell with no exit
    /// ends the walk instead, so a walking ray at [`Walker::end`] has
    /// its exit).
    Walking,
    Done,
}

/// One ray in flight, advanced one tetrahedron at a time, so that a thread
/// can keep several independent walks going and overlap their memory
/// latencies (each step is a chain of dependent loads: neighbour index,
/// vertex indices, vertex positions; see [`Walker::advance`]).
pub(crate) struct Walker<S> {
    ray: RayFrame,
    /// `ray`'s projection, for the walk's vertices.
    projector: Projector,
    phase: Phase,
    pub light: RayLight,
    pub counters: RayCounters,
    /// Distance reached so far; never decreases.
    t_cursor: f32,
    /// Boundary faces entered at distance `skip_t` with no segment of
    /// positive length since: a re-entry query must not return them again
    /// (a ray grazing a pinch point would otherwise loop).
    skip: Vec<u32>,
    skip_t: f32,
    /// `t_in` at the last entry: a segment of positive length since has
    /// moved `t_in` past it, which ends the faces to skip (checked at the
    /// next entry, so that the walk's steps do not clear the list).
    entry_t: f32,
    /// The ray's entries, where the frame found them all beforehand
    /// ([`crate::entries`]); otherwise the BVH is asked.
    entries: Option<EntryList>,
    /// The neighbours of the ray's cell by rank (its record's `next`),
    /// copied when its vertex is loaded: the exit reads its neighbour here
    /// instead of indexing the records again.
    next: [u32; 4],
    /// The cell the ray is in, from its entry or crossing until the step
    /// finds its exit; from then on the record's entry across the exit
    /// face (the next cell, or a boundary marker), which the ray crosses
    /// into at [`Walker::end`].
    crossing: u32,
    t_in: f32,
    s_in: f32,
    /// The classified `s_in` (set on entry).
    sample_in: S,
    /// Whether the ray's light is kept per interval ([`Walker::intervals`])
    /// instead of composited along the whole ray.
    split: bool,
    /// The finished intervals of a split walk, front to back.
    pub intervals: Vec<Interval>,
    interval_depth: f32,
    /// `counters.segments` where the current interval began.
    interval_start: u64,
    /// The left-out cells the ray crosses ([`crate::holes`]), found at its
    /// first entry query.
    holes: Holes,
}

impl<S: Copy + Default> Walker<S> {
    pub fn new() -> Self {
        let ray = RayFrame::new(Vec3::ZERO, Vec3::Z);
        Walker {
            ray,
            projector: Projector::new(&ray),
            phase: Phase::Done,
            light: RayLight::CLEAR,
            counters: RayCounters::default(),
            t_cursor: 0.0,
            skip: Vec::new(),
            skip_t: f32::NAN,
            entry_t: f32::NAN,
            entries: None,
            next: [FINAL_EXIT; 4],
            crossing: FINAL_EXIT,
            t_in: 0.0,
            s_in: 0.0,
            sample_in: S::default(),
            split: false,
            intervals: Vec::new(),
            interval_depth: 0.0,
            interval_start: 0,
            holes: Holes::default(),
        }
    }

    /// A walker that keeps each interval's light apart (see [`Interval`]):
    /// never merged across a gap, so intervals of other meshes can be
    /// composited in between.
    pub fn split() -> Self {
        Walker {
            split: true,
            ..Walker::new()
        }
    }

    /// Ends the current interval of a split walk: keeps its light if a
    /// segment was integrated in it, and starts the next from clear.
    pub fn close_interval(&mut self) {
        self.close_interval_lit(self.counters.segments > self.interval_start);
    }

    /// [`Walker::close_interval`], told whether the interval has light.
    fn close_interval_lit(&mut self, lit: bool) {
        if lit {
            self.intervals.push(Interval {
                depth: self.interval_depth,
                light: self.light,
            });
        }
        self.light = RayLight::CLEAR;
        self.interval_start = self.counters.segments;
    }

    /// Starts a ray from distance `t_start` on (`-inf` when its origin may
    /// lie inside the mesh: the walk then starts at the line's first entry
    /// and integrates only from distance 0).
    pub fn start(&mut self, ray: RayFrame, t_start: f32) {
        self.ray = ray;
        self.projector = Projector::new(&ray);
        self.phase = Phase::Entering;
        self.light = RayLight::CLEAR;
        self.counters = RayCounters::default();
        self.t_cursor = t_start;
        self.skip.clear();
        self.skip_t = f32::NAN;
        self.entry_t = f32::NAN;
        self.entries = None;
        self.intervals.clear();
        self.interval_start = 0;
        self.holes.clear();
    }

    /// Answers the started ray's entry queries from `list` (its pixel's
    /// entries, see [`crate::entries`]) when it holds them all.
    pub fn use_entries(&mut self, list: &EntryList) {
        if list.is_complete() {
            self.entries = Some(*list);
        }
    }

    /// One tetrahedron (after a BVH query where the ray is between
    /// entries; none where the query finds none), its segment integrated
    /// alone; returns whether the ray goes on. `lanes` holds the ray's face
    /// between calls.
    #[inline(always)]
    pub fn advance<const PREFETCH: bool, I: SegmentIntegrator<Sample = S> + ?Sized>(
        &mut self,
        scene: &Scene,
        integrator: &I,
        limits: WalkLimits,
        lanes: &mut Lanes<1>,
    ) -> bool {
        let cells = Cells::of(scene);
        self.begin::<PREFETCH, 1, I>(scene, cells, integrator, limits, lanes, 0);
        lanes.exits(None);
        let mut segment = SampledSegment::default();
        let light = self
            .leave(lanes, 0, integrator, &mut segment)
            .then(|| integrator.segment(&segment.front, &segment.back, segment.length));
        self.end(light, limits)
    }

    /// The first stage of [`Walker::advance`]: the vertex of the ray's
    /// tetrahedron that its exit is found against, given to the ray's lane
    /// of `lanes` (where the face it entered through is); a ray between
    /// entries first asks the BVH, and takes the vertex of the tetrahedron
    /// it enters. [`Lanes::exits`] then finds the exits of all lanes at
    /// once, [`Walker::leave`] takes the ray's and finds the step's
    /// segment, and [`Walker::end`] composites its light.
    /// A thread with many rays in flight takes each stage for all of them
    /// in turn and integrates their segments together: the stages of
    /// different rays are independent, and the processor overlaps them,
    /// where one ray's step is a single chain of dependent operations.
    ///
    /// With `PREFETCH`, each step first prefetches the records of the three
    /// cells the ray may enter next, so that a mesh too large for the
    /// caches costs less than a miss per step: the record arrives while the
    /// step computes its exit and integrates.
    #[inline(always)]
    pub fn begin<
        const PREFETCH: bool,
        const N: usize,
        I: SegmentIntegrator<Sample = S> + ?Sized,
    >(
        &mut self,
        scene: &Scene,
        cells: Cells<'_>,
        integrator: &I,
        limits: WalkLimits,
        lanes: &mut Lanes<N>,
        lane: usize,
    ) {
        // The lane leaves its cell at the next exits if it is given a
        // vertex ([`Walker::apex`]), and rests otherwise.
        match self.phase {
            Phase::Walking => self.apex::<PREFETCH, N>(cells, limits, lanes, lane),
            Phase::Entering => {
                lanes.rest(lane);
                // The entered cell's vertex in the same stage: the ray's
                // lane leaves it at the next exits, where it would
                // otherwise rest a round.
                self.enter(scene, integrator, limits, lanes, lane);
                if self.phase == Phase::Walking {
                    self.apex::<PREFETCH, N>(cells, limits, lanes, lane);
                }
            }
            Phase::Done => lanes.rest(lane),
        }
    }

    /// The last stage of [`Walker::advance`]: composites the light of the
    /// step's segment (`None` when [`Walker::leave`] found none), stops
    /// the ray once it is opaque enough, and moves it across the exit face.
    /// Returns whether the ray goes on.
    #[inline(always)]
    pub fn end(&mut self, light: Option<(Vec3A, Vec3A)>, limits: WalkLimits) -> bool {
        // Only a walking ray has a segment (see `Walker::leave`), so a
        // lit step needs no test of the phase.
        let crosses = match light {
            Some(light) => self.composite(light, limits),
            None => self.phase == Phase::Walking,
        };
        if crosses {
            self.cross();
        }
        self.phase != Phase::Done
    }

    #[inline(always)]
    fn enter<const N: usize, I: SegmentIntegrator<Sample = S> + ?Sized>(
        &mut self,
        scene: &Scene,
        integrator: &I,
        limits: WalkLimits,
        lanes: &mut Lanes<N>,
        lane: usize,
    ) {
        // Re-entries start a little before the exit (see REENTRY_REL).
        let t_query = if self.counters.entries > 0 {
            reentry_start(&self.ray, self.t_cursor, scene.bvh.scene_abs_max())
        } else {
            self.t_cursor
        };
        if self.t_in > self.entry_t {
            self.skip.clear();
            self.skip_t = f32::NAN;
        }
        let found = match &self.entries {
            Some(list) => list.first_entry(t_query, f32::INFINITY, &self.skip),
            None => scene
                .bvh
                .first_entry(&self.ray, t_query, f32::INFINITY, &self.skip),
        };
        if !self.holes.found && self.holes.find(scene, &self.ray, &self.projector) {
            self.counters.overlap_overflow = true;
        }
        if !self.holes.is_empty() {
            // The gap before this entry (or after the last exit).
            let gap_end = found.map_or(f32::INFINITY, |hit| hit.t);
            let light = &mut self.light;
            let filled = self.holes.fill(
                self.t_cursor,
                gap_end,
                limits.stop_below_sum,
                &mut light.color,
                &mut light.transmittance,
                |front, back, length| {
                    integrator.segment(&integrator.sample(front), &integrator.sample(back), length)
                },
            );
            self.counters.overlap_segments += filled.segments;
            if self.split && filled.segments > 0 {
                // The gap's light is an interval of its own.
                self.interval_depth = filled.depth;
                self.close_interval_lit(true);
            }
            if filled.opaque {
                self.phase = Phase::Done;
                return;
            }
        }
        let Some(hit) = found else {
            self.phase = Phase::Done;
            return;
        };
        self.counters.entries += 1;
        self.counters.hit = true;
        if hit.t != self.skip_t {
            self.skip.clear();
            self.skip_t = hit.t;
        }
        self.skip.push(hit.face);
        let Some(bf) = scene.topology.boundary_faces.get(hit.face as usize) else {
            self.counters.walk_failure = true;
            self.phase = Phase::Done;
            return;
        };
        self.crossing = bf.tet;
        let (face, s_in) = Face::enter(scene.point_records(), &self.projector, bf.vertices);
        lanes.set_face(lane, &face);
        self.s_in = s_in;
        self.t_in = hit.t.max(self.t_cursor);
        self.entry_t = self.t_in;
        self.sample_in = integrator.sample(self.s_in);
        self.interval_depth = self.t_in.max(0.0);
        self.phase = Phase::Walking;
    }

    /// Loads the vertex of the current cell opposite the face the ray
    /// entered through, against which [`Lanes::exits`] finds the exit.
    #[inline(always)]
    fn apex<const PREFETCH: bool, const N: usize>(
        &mut self,
        cells: Cells<'_>,
        limits: WalkLimits,
        lanes: &mut Lanes<N>,
        lane: usize,
    ) {
        let record = &cells.records[self.crossing as usize];
        if PREFETCH {
            // The next tetrahedron is one of the neighbours across the three
            // other faces: their records start loading now, while this step
            // computes its exit and integrates. All four are asked for (the
            // one the ray came from is cached already), and a boundary
            // marker asks for the last record: no branch on which face is
            // which, whose outcome is as good as random. A record's first
            // and last bytes are asked for: a quarter of the 20-byte
            // records cross a cache line, whose second line was a miss of
            // its own at the next step (where the record does not cross,
            // the second request finds the line on its way).
            let last = cells.records.len() - 1;
            for &next in &record.next {
                let index = (next as usize).min(last);
                let candidate = &cells.records[index];
                tetray_memory::prefetch(&candidate.vert_xor);
                tetray_memory::prefetch(&candidate.next[3]);
            }
        }
        let counters = &mut self.counters;
        counters.steps += 1;
        if counters.steps > limits.max_steps {
            counters.step_bound_hit = true;
            self.phase = Phase::Done;
            lanes.rest(lane);
            return;
        }
        // Of this cell only the vertex opposite the entry face is new: the
        // XOR of the record's and the face's point indices.
        self.next = record.next;
        let apex = lanes.opposite(lane, record.vert_xor);
        lanes.set_apex(lane, Vertex::load(cells.points, &self.projector, apex));
    }

    /// The second stage of [`Walker::advance`]: takes the exit
    /// [`Lanes::exits`] found for the ray (if it was given a vertex this
    /// round), where it leaves the current cell and the cell it enters,
    /// classifies the scalar there and writes the step's segment, if it
    /// has positive length in front of the eye; returns whether it has.
    #[inline(always)]
    pub fn leave<const N: usize, I: SegmentIntegrator<Sample = S> + ?Sized>(
        &mut self,
        lanes: &mut Lanes<N>,
        lane: usize,
        integrator: &I,
        segment: &mut SampledSegment<S>,
    ) -> bool {
        // The exit the lanes found, else (rarely) none for a resting lane or
        // the lane's own.
        let exit = match lanes.found(lane) {
            Some(exit) => Some(exit),
            None if !lanes.is_leaving(lane) => return false,
            None => lanes.exit(lane),
        };
        let Some((rank, t_exit, s_out)) = exit else {
            // Only a degenerate (flat) tetrahedron has no exit face.
            self.counters.walk_failure = true;
            self.phase = Phase::Done;
            return false;
        };
        // The exit face is the one opposite the entry face's vertex it
        // leaves out, whose rank among the cell's four names the neighbour.
        self.crossing = self.next[rank & 3];
        self.classify(integrator, t_exit, s_out, segment)
    }

    /// Starts loading the point the ray's next step projects first: the
    /// apex of the cell across the exit face, whose record the exit
    /// prefetched one stage earlier. Called between [`Walker::begin`] and
    /// [`Walker::end`] when many rays are in flight, so that the point
    /// arrives while the other rays integrate, instead of being a second
    /// miss in the chain of the next step (record, then point). Costs a
    /// few instructions; a ray not crossing prefetches some point of the
    /// mesh (a stale crossing), which is harmless, and one leaving the
    /// mesh (a boundary marker past the records) none.
    #[inline(always)]
    pub fn prefetch_next_apex<const N: usize>(
        &self,
        cells: Cells<'_>,
        lanes: &Lanes<N>,
        lane: usize,
    ) {
        if let Some(record) = cells.records.get(self.crossing as usize)
            && let Some(apex) = cells
                .points
                .get(lanes.opposite(lane, record.vert_xor) as usize)
        {
            tetray_memory::prefetch(apex);
        }
    }

    /// Classifies the scalar `s_out` at the step's exit, at distance
    /// `t_exit`, and writes the step's segment (see [`Walker::leave`]).
    #[inline(always)]
    fn classify<I: SegmentIntegrator<Sample = S> + ?Sized>(
        &mut self,
        integrator: &I,
        t_exit: f32,
        s_out: f32,
        segment: &mut SampledSegment<S>,
    ) -> bool {
        let (t_in, s_in) = (self.t_in, self.s_in);
        let sample_in = self.sample_in;
        let t_out = max_f32(t_exit, t_in);
        let sample_out = integrator.sample_near(s_out, &sample_in);
        // `t_out > t_in && t_out > 0` in one comparison (both false for a
        // NaN).
        let near = max_f32(t_in, 0.0);
        let integrate = t_out > near;
        // Clip at the ray origin; the scalar is linear along the segment,
        // so interpolating it there is exact.
        let front = if t_in < 0.0 && integrate {
            integrator.sample(s_in + (s_out - s_in) * (-t_in / (t_out - t_in)))
        } else {
            sample_in
        };
        // Written whether integrated or not: the caller reads it only if
        // it is, and the write takes no branch.
        *segment = SampledSegment {
            front,
            back: sample_out,
            length: t_out - near,
        };
        self.t_in = t_out;
        self.s_in = s_out;
        self.sample_in = sample_out;
        integrate
    }

    /// Composites the light of the step's segment; returns whether the
    /// ray goes on (it stops once it is opaque enough).
    #[inline(always)]
    fn composite(&mut self, (emitted, transmittance): (Vec3A, Vec3A), limits: WalkLimits) -> bool {
        let ray = &mut self.light;
        ray.color += ray.transmittance * emitted;
        ray.transmittance *= transmittance;
        self.counters.segments += 1;
        // 1 - mean(T) >= threshold, without a division.
        if ray.transmittance.element_sum() <= limits.stop_below_sum {
            self.phase = Phase::Done;
            return false;
        }
        true
    }

    /// Crosses the exit face of the step.
    #[inline(always)]
    fn cross(&mut self) {
        let next = self.crossing;
        if next >= FINAL_EXIT {
            // Left through the convex hull: nothing more to meet; otherwise
            // ask the BVH where the ray comes back.
            // A left-out cell beyond the hull's exit still has its gap.
            self.phase = if next == FINAL_EXIT && !self.holes.beyond(self.t_in) {
                Phase::Done
            } else {
                Phase::Entering
            };
            self.t_cursor = self.t_in;
            if self.split {
                self.close_interval();
            }
            return;
        }
        // `crossing` is the ray's cell now. The ray is walking already.
        // The store is kept: without it the compiler lays the walk out in
        // more instructions (Blunt Fin PPI, `tools/cpu-instructions`: 284.0
        // per segment against 277.6).
        self.phase = Phase::Walking;
    }
}
