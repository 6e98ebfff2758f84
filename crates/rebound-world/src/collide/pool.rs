//! The *collide* stage's walk over the thread pool (the `parallel` feature, on a pool of more than one
//! thread): the manifolds cut into chunks, each chunk walked alone as the one-thread walk walks the whole
//! list — judged (bodies, quarantine, validity), matched with last step's manifolds by a forward walk from
//! where its first key falls, warm-started in place, its approach speeds written beside it — and its counts
//! (kept manifolds and their points, quarantined ones) returned. The cap on contact points and the list's
//! length then follow from the counts, chunk by chunk. Only when a manifold was dropped (a quarantined body,
//! an unusable manifold: a fault, not a step's common work) are the kept ones moved down over it, in order,
//! on one thread.
//!
//! Why the chunks match as the one walk does: the one walk asks last step's list for the keys of the kept
//! manifolds in increasing order, and the `j`-th kept manifold of a key gets the `j`-th old one of that key
//! (`walk_to` takes each match it returns). A chunk starts its walk at the first old manifold of its first
//! key, past as many of that key as kept manifolds of the key stand before the chunk — none unless a backend
//! repeats keys. Manifolds the cap drops are never read again, so warming them changes nothing.

use super::{Dropped, approach_speed, is_usable, moves, ordered, warm_start_points};
use crate::handles::BodyHandle;
use crate::manifold::ContactManifold;
use crate::sorted_walk::walk_to;
use crate::state::WorldState;
use rebound_dynamics::RigidBody;
use rebound_math::Mat3;
use rebound_math::par::{self, MIN_ITEMS_PER_TASK};

/// Manifolds per chunk of the walk: enough work per chunk to outweigh handing it to another thread.
pub(super) const MANIFOLDS_PER_CHUNK: usize = 256;

/// What one chunk's walk found.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct ChunkCounts {
    /// Usable manifolds between two bodies in the step (the cap on contact points may still drop some).
    kept: usize,
    /// Their contact points.
    points: usize,
    /// Manifolds with a quarantined body.
    quarantined: usize,
}

/// The pool's scratch, kept from step to step.
#[derive(Debug, Default)]
pub(super) struct Chunks {
    /// Per chunk, how many old manifolds of its first key kept manifolds before it have taken.
    taken: Vec<usize>,
    counts: Vec<ChunkCounts>,
    /// Per chunk, whether its manifolds are in order (scratch of [`is_sorted_on_pool`]).
    sorted: Vec<bool>,
}

/// Whether `manifolds` are sorted by order key, checked over the pool chunk by chunk (and at the chunks'
/// borders): a sorted list need not be sorted again (sorting it changes nothing).
pub(super) fn is_sorted_on_pool(manifolds: &mut [ContactManifold], scratch: &mut Chunks) -> bool {
    // Zero-sized partners: nothing is allocated.
    let mut none = vec![(); manifolds.len()];
    par::map_chunks_zip_mut(
        manifolds,
        &mut none,
        MANIFOLDS_PER_CHUNK,
        &mut scratch.sorted,
        |_, chunk, _| chunk.is_sorted_by_key(ContactManifold::order_key),
    );
    scratch.sorted.iter().all(|&sorted| sorted)
        && (MANIFOLDS_PER_CHUNK..manifolds.len())
            .step_by(MANIFOLDS_PER_CHUNK)
            .all(|start| manifolds[start - 1].order_key() <= manifolds[start].order_key())
}

/// How the walk treats a manifold, before the cap on contact points.
enum Judged<'a> {
    Kept(&'a RigidBody, &'a RigidBody),
    Quarantined,
    Rejected,
}

/// What the one-thread walk tests of a manifold before the cap, in its order.
#[inline(always)]
fn judge<'a>(state: &'a WorldState, m: &ContactManifold) -> Judged<'a> {
    let bodies = &state.bodies;
    let (Some(a), Some(b)) = (bodies.entry(m.body_a), bodies.entry(m.body_b)) else {
        return Judged::Rejected;
    };
    // A quarantined body is in no step (a backend may not know it); not a fault of the backend.
    if a.quarantined || b.quarantined {
        return Judged::Quarantined;
    }
    if !is_usable(m) {
        return Judged::Rejected;
    }
    Judged::Kept(&a.body, &b.body)
}

/// The walk of `collide` over the pool: `manifolds` (sorted by order key) judged, matched and warm-started
/// chunk by chunk, `speeds` and (with `carried` manifolds) `pushed` made to hold what the one-thread walk
/// gives them, the dropped manifolds counted in `counts`. Returns how many manifolds were kept (the first
/// ones of `manifolds`).
pub(super) fn walk_on_pool(
    state: &WorldState,
    manifolds: &mut [ContactManifold],
    speeds: &mut Vec<f32>,
    pushed: &mut Vec<bool>,
    carried: bool,
    scratch: &mut Chunks,
    counts: &mut Dropped,
) -> usize {
    let n = manifolds.len();
    let chunk_starts = (0..n).step_by(MANIFOLDS_PER_CHUNK);
    scratch.taken.clear();
    scratch
        .taken
        .extend(chunk_starts.map(|start| taken_before(state, manifolds, start)));
    speeds.clear();
    speeds.resize(n, 0.0);
    let taken = &scratch.taken;
    par::map_chunks_zip_mut(
        manifolds,
        speeds,
        MANIFOLDS_PER_CHUNK,
        &mut scratch.counts,
        |k, chunk, chunk_speeds| {
            walk_chunk(
                state,
                chunk,
                chunk_speeds,
                taken.get(k).copied().unwrap_or(0),
            )
        },
    );
    // The cap: whole manifolds in order, until the next would exceed it, then none.
    let max_points = state.settings.limits.max_contact_points as usize;
    let (mut kept, mut points, mut dropped) = (0, 0, 0);
    // The index of the first manifold the cap drops, if it drops any.
    let mut cut: Option<usize> = None;
    for (k, chunk) in scratch.counts.iter().enumerate() {
        counts.quarantined += chunk.quarantined;
        let start = k * MANIFOLDS_PER_CHUNK;
        dropped += (n - start).min(MANIFOLDS_PER_CHUNK) - chunk.kept;
        if cut.is_some() {
            counts.capped += chunk.kept;
        } else if points + chunk.points > max_points {
            // The manifold that would exceed it lies in this chunk: walked again, judged only.
            let (before, from) = cap_in_chunk(state, manifolds, start, max_points - points);
            kept += before;
            counts.capped += chunk.kept - before;
            cut = Some(from);
        } else {
            kept += chunk.kept;
            points += chunk.points;
        }
    }
    // Without a dropped manifold the kept ones are the first `kept` where they lie.
    if dropped > 0 {
        move_down(state, manifolds, speeds, cut.unwrap_or(n));
    }
    speeds.truncate(kept);
    pushed.clear();
    if carried {
        par::map_collect_in_order(&manifolds[..kept], pushed, MIN_ITEMS_PER_TASK, |_, m| {
            counts_as_pushed(state, m)
        });
    }
    kept
}

/// How many old manifolds of the key of `manifolds[start]` the kept manifolds before `start` take (see the
/// module docs): 0 unless the manifold before has the same key.
fn taken_before(state: &WorldState, manifolds: &[ContactManifold], start: usize) -> usize {
    let Some(key) = manifolds.get(start).map(ContactManifold::order_key) else {
        return 0;
    };
    manifolds[..start]
        .iter()
        .rev()
        .take_while(|m| m.order_key() == key)
        .filter(|m| matches!(judge(state, m), Judged::Kept(..)))
        .count()
}

/// One chunk's walk (see the module docs): `taken` old manifolds of its first key are passed over.
fn walk_chunk(
    state: &WorldState,
    chunk: &mut [ContactManifold],
    speeds: &mut [f32],
    taken: usize,
) -> ChunkCounts {
    let mut counts = ChunkCounts::default();
    let olds = &state.manifolds;
    let Some(first) = chunk.first().map(ContactManifold::order_key) else {
        return counts;
    };
    let at = olds.partition_point(|o| o.order_key() < first);
    let mut previous = olds.get(at..).unwrap_or_default().iter().peekable();
    for _ in 0..taken {
        if previous.next_if(|o| o.order_key() == first).is_none() {
            break;
        }
    }
    // Manifolds of one body A follow one another (the sort): its rotation matrix is computed once for them.
    let mut rotation_a: Option<(BodyHandle, Mat3)> = None;
    for (manifold, speed) in chunk.iter_mut().zip(speeds) {
        let (a, b) = match judge(state, manifold) {
            Judged::Kept(a, b) => (a, b),
            Judged::Quarantined => {
                counts.quarantined += 1;
                continue;
            }
            Judged::Rejected => continue,
        };
        counts.kept += 1;
        counts.points += manifold.point_count;
        let old = walk_to(
            &mut previous,
            &manifold.order_key(),
            ContactManifold::order_key,
        );
        let may_begin = old.is_none_or(|o| !o.is_touching());
        if may_begin || a.is_sleeping() || b.is_sleeping() {
            *speed = approach_speed(manifold, a, b);
        }
        let matrix_a = match rotation_a {
            Some((handle, matrix)) if handle == manifold.body_a => matrix,
            _ => {
                let matrix = Mat3::from_quat(a.rotation());
                rotation_a = Some((manifold.body_a, matrix));
                matrix
            }
        };
        let rotations = [matrix_a, Mat3::from_quat(b.rotation())];
        warm_start_points(manifold, (a, b), old, &rotations);
    }
    counts
}

/// In the chunk from `start` on, whose kept manifolds would exceed the `room` left for contact points: how
/// many kept manifolds fit before the first that does not, and that one's index.
fn cap_in_chunk(
    state: &WorldState,
    manifolds: &[ContactManifold],
    start: usize,
    room: usize,
) -> (usize, usize) {
    let (mut kept, mut points) = (0, 0);
    let end = (start + MANIFOLDS_PER_CHUNK).min(manifolds.len());
    for (index, m) in manifolds.iter().enumerate().take(end).skip(start) {
        if !matches!(judge(state, m), Judged::Kept(..)) {
            continue;
        }
        if points + m.point_count > room {
            return (kept, index);
        }
        points += m.point_count;
        kept += 1;
    }
    (kept, end)
}

/// The kept manifolds before `until` (where the cap begins) and their speeds moved down over the dropped
/// ones, in order, as the one-thread walk moves them: after a quarantine or an unusable manifold only.
fn move_down(
    state: &WorldState,
    manifolds: &mut [ContactManifold],
    speeds: &mut [f32],
    until: usize,
) {
    let mut kept = 0;
    for index in 0..until.min(manifolds.len()) {
        if !matches!(judge(state, &manifolds[index]), Judged::Kept(..)) {
            continue;
        }
        if kept != index {
            manifolds.swap(kept, index);
            speeds.swap(kept, index);
        }
        kept += 1;
    }
}

/// Whether a kept manifold counts as pushed before the solver runs: both bodies still, and touching last
/// step (see `collide`).
fn counts_as_pushed(state: &WorldState, m: &ContactManifold) -> bool {
    let (a, b) = (state.bodies.get(m.body_a), state.bodies.get(m.body_b));
    a.zip(b).is_some_and(|(a, b)| !moves(a) && !moves(b))
        && state
            .touching
            .binary_search(&ordered(m.body_a, m.body_b))
            .is_ok()
}
