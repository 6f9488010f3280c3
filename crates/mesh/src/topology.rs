//! Face-neighbour graph: which tetrahedron lies across each face, and the
//! boundary faces.
//!
//! Faces are matched by bucketing, not hashing: every face of every
//! tetrahedron, its three point indices sorted, goes to the bucket of its
//! smallest point (a counting sort over the points, 4 bytes per face, by
//! chunks of tetrahedra in parallel),
//! then each bucket (in parallel; buckets hold a few dozen faces) is
//! sorted by the other two points, read back from the tetrahedra, and the
//! two faces of each run of equal points are each other's neighbour (each
//! face written once).

use std::sync::atomic::{AtomicU32, Ordering};

use rayon::prelude::*;

use crate::{BoundaryFace, FACE_VERTICES, MeshError, NO_NEIGHBOR, TetMesh, Topology};

/// Largest number of tetrahedra: `4 * tet + face` must fit in 32 bits, and
/// `u32::MAX` is [`NO_NEIGHBOR`].
pub const MAX_TETS: usize = (u32::MAX / 4) as usize;

/// Buckets sorted by one rayon task.
const BUCKETS_PER_TASK: usize = 4096;

/// At most this many chunks fill the buckets in parallel: each holds a
/// count per point while it does.
const MAX_CHUNKS: usize = 8;

/// The point indices of local face `f` of `tet`, sorted.
fn sorted_face(tet: &[u32; 4], f: usize) -> [u32; 3] {
    let [a, b, c] = FACE_VERTICES[f];
    let mut v = [tet[a], tet[b], tet[c]];
    v.sort_unstable();
    v
}

/// The smallest point index of local face `f` of `tet` (its bucket).
fn smallest_point(tet: &[u32; 4], f: usize) -> usize {
    let [a, b, c] = FACE_VERTICES[f];
    tet[a].min(tet[b]).min(tet[c]) as usize
}

/// A face shared by more than two tetrahedra: its points and theirs.
type SharedFace = ([u32; 3], Vec<u32>);

/// Every face of every tetrahedron, in buckets by smallest point: bucket
/// `p` is `entries[offsets[p]..offsets[p + 1]]`, each entry a face id
/// `4 * tet + local_face` (4 bytes per face: the other two points are read
/// back from the tetrahedra when a bucket is matched).
struct FaceBuckets<'t> {
    tets: &'t [[u32; 4]],
    offsets: Vec<u32>,
    entries: Vec<u32>,
}

/// One face of a bucket while it is matched: its other two points (the
/// larger in the low half) over its face id.
type FaceKey = (u64, u32);

impl<'t> FaceBuckets<'t> {
    fn new(tets: &'t [[u32; 4]]) -> FaceBuckets<'t> {
        let points = tets
            .par_iter()
            .map(|t| t.iter().copied().max().unwrap_or(0) as usize + 1)
            .max()
            .unwrap_or(0);
        // A counting sort in parallel: each chunk of tetrahedra counts its
        // faces per bucket, then writes them at its own cursors, after the
        // earlier chunks' faces of the same bucket (so the entries are the
        // same whatever the thread count).
        let chunks = rayon::current_num_threads().clamp(1, MAX_CHUNKS);
        let chunk_len = tets.len().div_ceil(chunks).max(1);
        let mut cursors: Vec<Vec<u32>> = tets
            .par_chunks(chunk_len)
            .map(|chunk| {
                let mut counts = vec![0u32; points];
                for tet in chunk {
                    for f in 0..4 {
                        counts[smallest_point(tet, f)] += 1;
                    }
                }
                counts
            })
            .collect();
        let mut offsets = vec![0u32; points + 1];
        let mut total = 0u32;
        for p in 0..points {
            offsets[p] = total;
            for counts in &mut cursors {
                // The chunk's first slot in bucket p; at most 4 * MAX_TETS.
                let n = counts[p];
                counts[p] = total;
                total += n;
            }
        }
        offsets[points] = total;
        let entries: Vec<AtomicU32> = (0..4 * tets.len())
            .into_par_iter()
            .map(|_| AtomicU32::new(0))
            .collect();
        tets.par_chunks(chunk_len)
            .zip(cursors.par_iter_mut())
            .enumerate()
            .for_each(|(c, (chunk, cursor))| {
                for (i, tet) in chunk.iter().enumerate() {
                    // t < MAX_TETS, so 4 t + 3 fits in u32.
                    let t = (c * chunk_len + i) as u32;
                    for f in 0..4 {
                        let slot = &mut cursor[smallest_point(tet, f)];
                        // Every slot is written once, by its chunk.
                        entries[*slot as usize].store(4 * t + f as u32, Ordering::Relaxed);
                        *slot += 1;
                    }
                }
            });
        FaceBuckets {
            tets,
            offsets,
            entries: entries.into_iter().map(AtomicU32::into_inner).collect(),
        }
    }

    /// Bucket `p` in `keys`, sorted by the faces' other two points.
    fn sorted_bucket(&self, p: usize, keys: &mut Vec<FaceKey>) {
        keys.clear();
        let ids = &self.entries[self.offsets[p] as usize..self.offsets[p + 1] as usize];
        keys.extend(ids.iter().map(|&id| {
            let [_, b, c] = sorted_face(&self.tets[id as usize / 4], id as usize % 4);
            ((b as u64) << 32 | c as u64, id)
        }));
        keys.sort_unstable();
    }

    /// The neighbour across every face (by face id `4 * tet + local_face`),
    /// bucket by bucket (in parallel): the two faces of a run of equal
    /// points are each other's other side. Each face id is written by its
    /// own run only, so relaxed stores suffice. On a run of more than two
    /// faces: the non-manifold face with the smallest points and its
    /// tetrahedra.
    fn neighbors(&self) -> Result<Vec<AtomicU32>, SharedFace> {
        let slots: Vec<AtomicU32> = (0..4 * self.tets.len())
            .into_par_iter()
            .map(|_| AtomicU32::new(NO_NEIGHBOR))
            .collect();
        let points = self.offsets.len().saturating_sub(1);
        let shared_by_more = (0..points)
            .into_par_iter()
            .with_min_len(BUCKETS_PER_TASK)
            .map_init(Vec::new, |keys, p| {
                self.sorted_bucket(p, keys);
                for run in keys.chunk_by(|x, y| x.0 == y.0) {
                    match *run {
                        [_] => {}
                        [(_, x), (_, y)] => {
                            slots[x as usize].store(y / 4, Ordering::Relaxed);
                            slots[y as usize].store(x / 4, Ordering::Relaxed);
                        }
                        _ => return Some(shared_face(p, run)),
                    }
                }
                None
            })
            .find_map_any(|found| found);
        if let Some(found) = shared_by_more {
            // The same face whatever the thread count: the smallest points.
            return Err(self.first_non_manifold().unwrap_or(found));
        }
        Ok(slots)
    }

    /// The non-manifold face with the smallest points (the same one
    /// whatever the thread count): its points and tetrahedra.
    fn first_non_manifold(&self) -> Option<SharedFace> {
        let mut keys = Vec::new();
        (0..self.offsets.len().saturating_sub(1)).find_map(|p| {
            self.sorted_bucket(p, &mut keys);
            keys.chunk_by(|x, y| x.0 == y.0)
                .find(|run| run.len() > 2)
                .map(|run| shared_face(p, run))
        })
    }
}

/// The face of bucket `p` that `run` (more than two faces) shares.
fn shared_face(p: usize, run: &[FaceKey]) -> SharedFace {
    let key = run[0].0;
    let tets = run.iter().map(|&(_, id)| id / 4).collect();
    ([p as u32, (key >> 32) as u32, key as u32], tets)
}

/// [`MeshError::TooLarge`] beyond [`MAX_TETS`] tetrahedra (face ids
/// `4 * tet + local_face` are u32).
pub(crate) fn check_tet_count(n: usize) -> Result<(), MeshError> {
    if n > MAX_TETS {
        return Err(MeshError::TooLarge {
            what: "tetrahedra",
            count: n,
            max: MAX_TETS,
        });
    }
    Ok(())
}

/// The faces of `tets` with no neighbour in `neighbors`, outward oriented
/// when the tetrahedra are positively oriented, listed by tetrahedron, then
/// local face.
pub fn boundary_faces_of(neighbors: &[[u32; 4]], tets: &[[u32; 4]]) -> Vec<BoundaryFace> {
    let mut faces = Vec::new();
    for (t, (nb, tet)) in neighbors.iter().zip(tets).enumerate() {
        for (f, &n) in nb.iter().enumerate() {
            if n == NO_NEIGHBOR {
                faces.push(BoundaryFace {
                    tet: t as u32,
                    local_face: f as u8,
                    vertices: FACE_VERTICES[f].map(|v| tet[v]),
                });
            }
        }
    }
    faces
}

impl Topology {
    /// Matches the faces of `mesh`'s tetrahedra.
    ///
    /// Only point indices are used (no coordinates), so this works on any
    /// mesh; the boundary faces are outward oriented when the tetrahedra
    /// are positively oriented. Boundary faces are listed by tetrahedron,
    /// then local face.
    ///
    /// # Errors
    /// [`MeshError::NonManifoldFace`] when a face belongs to more than two
    /// tetrahedra (naming them); [`MeshError::TooLarge`] beyond 2^30 - 1
    /// tetrahedra.
    pub fn build(mesh: &TetMesh) -> Result<Topology, MeshError> {
        let n = mesh.tets.len();
        check_tet_count(n)?;
        let faces = FaceBuckets::new(&mesh.tets);
        let slots = faces
            .neighbors()
            .map_err(|(vertices, tets)| MeshError::NonManifoldFace { vertices, tets })?;
        // The buckets go before the rows are made: not both in memory.
        drop(faces);
        let neighbors: Vec<[u32; 4]> = slots
            .par_chunks(4)
            .map(|c| std::array::from_fn(|f| c[f].load(Ordering::Relaxed)))
            .collect();
        drop(slots);

        let boundary_faces = boundary_faces_of(&neighbors, &mesh.tets);
        Ok(Topology {
            neighbors,
            boundary_faces,
        })
    }

    /// The index in `boundary_faces` of local face `f` of `tet`, when that
    /// face is on the boundary (a binary search: the list is ordered by
    /// tetrahedron, then local face).
    pub fn boundary_face_index(&self, tet: u32, f: usize) -> Option<usize> {
        let key = (tet, u8::try_from(f).ok()?);
        self.boundary_faces
            .binary_search_by_key(&key, |b| (b.tet, b.local_face))
            .ok()
    }

    /// The local face of `neighbor` that is shared with `tet`, if they are
    /// face neighbours.
    pub fn shared_face(&self, tet: u32, neighbor: u32) -> Option<usize> {
        self.neighbors
            .get(neighbor as usize)?
            .iter()
            .position(|&t| t == tet)
    }

    /// Connected components through shared faces: `(count, label per
    /// tetrahedron)`, labels numbered from 0 in order of first tetrahedron.
    ///
    /// A concurrent union-find over the face pairs, tetrahedra in parallel:
    /// each root links to the smaller of the two roots (so a component's
    /// root is its first tetrahedron, and parents only point down), paths
    /// are halved as they are read. Tetrahedra are visited in index order,
    /// so neighbours numbered close together stay in cache, unlike a
    /// depth-first search.
    pub fn components(&self) -> (usize, Vec<u32>) {
        let n = self.neighbors.len();
        let parent: Vec<AtomicU32> = (0..n as u32).into_par_iter().map(AtomicU32::new).collect();
        self.neighbors
            .par_iter()
            .enumerate()
            .with_min_len(COMPONENT_CHUNK)
            .for_each(|(t, row)| {
                for &nb in row {
                    // Each pair once, from its larger tetrahedron.
                    if nb < t as u32 {
                        union(&parent, t as u32, nb);
                    }
                }
            });
        // Roots are the first tetrahedra of their components: a component's
        // label is the number of roots before its root.
        let root: Vec<u32> = (0..n as u32)
            .into_par_iter()
            .with_min_len(COMPONENT_CHUNK)
            .map(|t| find(&parent, t))
            .collect();
        drop(parent);
        let mut rank = vec![0u32; n];
        let mut count = 0u32;
        for (t, r) in rank.iter_mut().enumerate() {
            *r = count;
            count += u32::from(root[t] == t as u32);
        }
        let label = root
            .par_iter()
            .with_min_len(COMPONENT_CHUNK)
            .map(|&r| rank[r as usize])
            .collect();
        (count as usize, label)
    }
}

/// Tetrahedra per rayon task in [`Topology::components`].
const COMPONENT_CHUNK: usize = 1 << 14;

/// The root of `x`'s set, halving the path on the way (each node read is
/// pointed at its grandparent, which is still one of its ancestors).
fn find(parent: &[AtomicU32], mut x: u32) -> u32 {
    loop {
        let p = parent[x as usize].load(Ordering::Relaxed);
        if p == x {
            return x;
        }
        let gp = parent[p as usize].load(Ordering::Relaxed);
        if gp != p {
            // A lost race only leaves the longer path.
            let _ = parent[x as usize].compare_exchange_weak(
                p,
                gp,
                Ordering::Relaxed,
                Ordering::Relaxed,
            );
        }
        x = gp;
    }
}

/// Joins the sets of `a` and `b`: the larger root is linked to the smaller,
/// by a compare-and-swap that only succeeds while it is still a root.
fn union(parent: &[AtomicU32], a: u32, b: u32) {
    let (mut a, mut b) = (a, b);
    loop {
        a = find(parent, a);
        b = find(parent, b);
        if a == b {
            return;
        }
        let (hi, lo) = if a > b { (a, b) } else { (b, a) };
        if parent[hi as usize]
            .compare_exchange(hi, lo, Ordering::AcqRel, Ordering::Relaxed)
            .is_ok()
        {
            return;
        }
    }
}
