//! Moving the bytes with MPI (rsmpi): the all-to-all exchange of fragments
//! to the ranks owning their pixels, the gather of composited tiles on
//! rank 0, and the reductions the ranks agree through. Everything else is
//! in the modules that know nothing of MPI.

use std::time::{Duration, Instant};

use glam::DVec3;
use mpi::Count;
use mpi::collective::SystemOperation;
use mpi::datatype::{Partition, PartitionMut};
use mpi::traits::*;
use tetray_core::Image;
use tetray_raycast::Fragment;

use crate::DistributedError;
use crate::composite::{assemble, bucket_by_owner, composite_owned, prefix_sums};
use crate::layout::TileLayout;
use crate::summary::{MeshSummary, Reduce};

/// 32-bit words per fragment on the wire.
const WORDS: usize = std::mem::size_of::<Fragment>() / 4;

/// What compositing one frame cost this rank.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CompositeCost {
    /// Fragments this rank made, and those it received to composite.
    pub fragments_sent: u64,
    pub fragments_received: u64,
    /// Bytes sent to other ranks in the exchange (its own stay in place).
    pub bytes_exchanged: u64,
    /// Bytes of composited pixels sent to rank 0 (0 for rank 0).
    pub bytes_gathered: u64,
    /// Waiting for the other ranks to finish tracing (a barrier): load
    /// imbalance, kept out of the exchange time.
    pub wait: Duration,
    pub exchange: Duration,
    pub sort: Duration,
    pub blend: Duration,
    pub gather: Duration,
}

fn count(n: usize) -> Result<Count, DistributedError> {
    Count::try_from(n).map_err(|_| DistributedError::TooLarge(n))
}

fn counts(values: &[usize]) -> Result<Vec<Count>, DistributedError> {
    values.iter().map(|&n| count(n)).collect()
}

/// Sends every fragment to the rank owning its pixel (`MPI_Alltoallv`),
/// composites the fragments of the pixels this rank owns and gathers the
/// image on rank 0: `Some(image)` there, `None` elsewhere.
pub fn composite<C: Communicator>(
    comm: &C,
    fragments: &[Fragment],
    layout: &TileLayout,
) -> Result<(Option<Image>, CompositeCost), DistributedError> {
    let rank = comm.rank() as usize;
    let mut cost = CompositeCost {
        fragments_sent: fragments.len() as u64,
        ..CompositeCost::default()
    };
    let start = Instant::now();
    comm.barrier();
    cost.wait = start.elapsed();
    let start = Instant::now();
    let buckets = bucket_by_owner(fragments, layout);
    let send_words: Vec<usize> = buckets.counts.iter().map(|&n| n * WORDS).collect();
    let send_counts = counts(&send_words)?;
    let mut recv_counts = vec![0 as Count; layout.ranks];
    comm.all_to_all_into(&send_counts[..], &mut recv_counts[..]);
    let recv_words: Vec<usize> = recv_counts.iter().map(|&n| n as usize).collect();
    let total: usize = recv_words.iter().sum();
    let send: &[u32] = bytemuck::cast_slice(&buckets.fragments);
    let mut recv = vec![0u32; total];
    {
        let send_displs = counts(&prefix_sums(&send_words))?;
        let recv_displs = counts(&prefix_sums(&recv_words))?;
        let partition = Partition::new(send, &send_counts[..], &send_displs[..]);
        let mut into = PartitionMut::new(&mut recv[..], &recv_counts[..], &recv_displs[..]);
        comm.all_to_all_varcount_into(&partition, &mut into);
    }
    let received: Vec<Fragment> = bytemuck::pod_collect_to_vec(&recv);
    cost.exchange = start.elapsed();
    cost.fragments_received = received.len() as u64;
    cost.bytes_exchanged = ((send.len() - send_words[rank]) * 4) as u64;

    let owned = composite_owned(&received, layout, rank);
    cost.sort = owned.sort_time;
    cost.blend = owned.blend_time;

    let start = Instant::now();
    let flat: &[f32] = bytemuck::cast_slice(&owned.rgba);
    let root = comm.process_at_rank(0);
    let image = if rank == 0 {
        let per_rank: Vec<usize> = (0..layout.ranks)
            .map(|r| layout.owned_count(r) * 4)
            .collect();
        let mut all = vec![0f32; per_rank.iter().sum()];
        {
            let gather_counts = counts(&per_rank)?;
            let displs = counts(&prefix_sums(&per_rank))?;
            let mut into = PartitionMut::new(&mut all[..], &gather_counts[..], &displs[..]);
            root.gather_varcount_into_root(flat, &mut into);
        }
        let pixels: &[[f32; 4]] = bytemuck::cast_slice(&all);
        let mut slices = Vec::with_capacity(layout.ranks);
        let mut at = 0;
        for n in &per_rank {
            slices.push(&pixels[at..at + n / 4]);
            at += n / 4;
        }
        let mut image = Image::new(layout.width, layout.height)?;
        image.rgba = assemble(&slices, layout);
        Some(image)
    } else {
        root.gather_varcount_into(flat);
        cost.bytes_gathered = std::mem::size_of_val(flat) as u64;
        None
    };
    cost.gather = start.elapsed();
    Ok((image, cost))
}

/// The whole mesh's summary from every rank's (min, max and sum
/// allreduces).
pub fn reduce_summary<C: Communicator>(comm: &C, local: &MeshSummary) -> MeshSummary {
    let mine = local.to_reduce();
    let mut all = Reduce {
        min: vec![0.0; mine.min.len()],
        max: vec![0.0; mine.max.len()],
        sum: vec![0.0; mine.sum.len()],
    };
    comm.all_reduce_into(&mine.min[..], &mut all.min[..], SystemOperation::min());
    comm.all_reduce_into(&mine.max[..], &mut all.max[..], SystemOperation::max());
    comm.all_reduce_into(&mine.sum[..], &mut all.sum[..], SystemOperation::sum());
    MeshSummary::from_reduced(&all)
}

/// The bounds of every rank's points (f64, as read); `None` when no rank
/// has any.
pub fn reduce_bounds<C: Communicator>(
    comm: &C,
    local: Option<(DVec3, DVec3)>,
) -> Option<(DVec3, DVec3)> {
    let (lo, hi) = local.unwrap_or((DVec3::INFINITY, DVec3::NEG_INFINITY));
    let (mut glo, mut ghi) = ([0.0f64; 3], [0.0f64; 3]);
    comm.all_reduce_into(&lo.to_array()[..], &mut glo[..], SystemOperation::min());
    comm.all_reduce_into(&hi.to_array()[..], &mut ghi[..], SystemOperation::max());
    let (lo, hi) = (DVec3::from_array(glo), DVec3::from_array(ghi));
    (lo.cmple(hi).all()).then_some((lo, hi))
}

/// Whether every rank says yes (a logical-and allreduce).
pub fn all_agree<C: Communicator>(comm: &C, yes: &[bool]) -> Vec<bool> {
    let mine: Vec<i32> = yes.iter().map(|&y| i32::from(y)).collect();
    let mut all = vec![0i32; mine.len()];
    comm.all_reduce_into(&mine[..], &mut all[..], SystemOperation::min());
    all.iter().map(|&v| v == 1).collect()
}

/// The names of the lowest rank with `has_part`, on every rank (rank 0's
/// when none has).
pub fn broadcast_names<C: Communicator>(comm: &C, names: &[String], has_part: bool) -> Vec<String> {
    let size = comm.size();
    let mine = if has_part { comm.rank() } else { size };
    let mut first = 0;
    comm.all_reduce_into(&mine, &mut first, SystemOperation::min());
    let root = comm.process_at_rank(if first < size { first } else { 0 });
    let mut text = names.join("\n").into_bytes();
    let mut len = text.len() as u64;
    root.broadcast_into(&mut len);
    text.resize(len as usize, 0);
    root.broadcast_into(&mut text[..]);
    let text = String::from_utf8_lossy(&text).into_owned();
    if text.is_empty() {
        Vec::new()
    } else {
        text.split('\n').map(str::to_string).collect()
    }
}

/// Every rank's `values` on rank 0 (`Some` there, one row per rank).
pub fn gather_rows<C: Communicator>(comm: &C, values: &[f64]) -> Option<Vec<Vec<f64>>> {
    let root = comm.process_at_rank(0);
    let n = values.len();
    if comm.rank() == 0 {
        let mut all = vec![0.0f64; n * comm.size() as usize];
        root.gather_into_root(values, &mut all[..]);
        Some(all.chunks(n.max(1)).map(<[f64]>::to_vec).collect())
    } else {
        root.gather_into(values);
        None
    }
}
