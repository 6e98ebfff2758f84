//! The *collide* stage's walk over the thread pool (the `parallel` feature, on a pool of more than one
//! thread): each manifold judged alone (its bodies, the quarantine, its validity, last step's manifold of
//! its key), then warm-started where it lies with its approach speed, each over the pool. The walk of
//! `collide` then only keeps, caps and moves the manifolds, in order, as on one thread: the same results.

use super::{Dropped, approach_speed, is_usable, moves, ordered, warm_start_points};
use crate::manifold::ContactManifold;
use crate::state::WorldState;
use core::sync::atomic::{AtomicBool, Ordering};
use rebound_math::Mat3;
use rebound_math::par::{self, MIN_ITEMS_PER_TASK};

/// What the walk does with a manifold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// Usable, between two bodies in the step (it may still fall to the cap on contact points).
    Kept,
    /// With a quarantined body.
    Quarantined,
    /// Unusable, or with a stale handle.
    Rejected,
}

/// What the pool found of one manifold of the backend.
#[derive(Debug, Clone, Copy)]
pub(super) struct Verdict {
    pub(super) kind: Kind,
    /// Index into last step's manifolds of the one with the same order key.
    old: Option<u32>,
    /// The approach speed (m/s, ≥ 0), 0 where nothing needs it (see `collide`).
    pub(super) speed: f32,
}

/// Judges and warm-starts every manifold of `manifolds` (sorted by order key) over the pool, each alone,
/// with `verdicts[i]` what the walk needs of manifold `i`. Returns `false`, having changed nothing, when two
/// manifolds share an order key (a faulty backend): the one-thread walk then matches them to last step's in
/// its own way, which a search per manifold would not reproduce.
pub(super) fn judge_on_pool(
    state: &WorldState,
    manifolds: &mut [ContactManifold],
    verdicts: &mut Vec<Verdict>,
) -> bool {
    let unique = AtomicBool::new(true);
    let shared = &*manifolds;
    par::map_collect_in_order(shared, verdicts, MIN_ITEMS_PER_TASK, |i, m| {
        let key = m.order_key();
        if shared
            .get(i + 1)
            .is_some_and(|next| next.order_key() == key)
        {
            unique.store(false, Ordering::Relaxed);
        }
        judge(state, m)
    });
    if !unique.into_inner() {
        return false;
    }
    par::for_each_zip_both_mut(manifolds, verdicts, MIN_ITEMS_PER_TASK, |m, v| {
        warm_start(state, m, v);
    });
    true
}

/// A manifold's verdict: what the one-thread walk tests, in its order, and last step's manifold of its key.
/// The first of last step's with a key not below it is the one the walk's forward search finds, as long as
/// this step's keys are distinct.
fn judge(state: &WorldState, m: &ContactManifold) -> Verdict {
    let verdict = |kind| Verdict {
        kind,
        old: None,
        speed: 0.0,
    };
    let bodies = &state.bodies;
    let (Some(a), Some(b)) = (bodies.entry(m.body_a), bodies.entry(m.body_b)) else {
        return verdict(Kind::Rejected);
    };
    if a.quarantined || b.quarantined {
        return verdict(Kind::Quarantined);
    }
    if !is_usable(m) {
        return verdict(Kind::Rejected);
    }
    let key = m.order_key();
    let olds = &state.manifolds;
    let at = olds.partition_point(|o| o.order_key() < key);
    Verdict {
        kind: Kind::Kept,
        old: olds
            .get(at)
            .filter(|o| o.order_key() == key)
            .map(|_| at as u32),
        speed: 0.0,
    }
}

/// A kept manifold's approach speed, if needed, and its warm start, as the one-thread walk computes them
/// (the rotation matrices computed here, per manifold, are the walk's per body: the same bits).
fn warm_start(state: &WorldState, m: &mut ContactManifold, v: &mut Verdict) {
    if v.kind != Kind::Kept {
        return;
    }
    let (Some(a), Some(b)) = (state.bodies.get(m.body_a), state.bodies.get(m.body_b)) else {
        return;
    };
    let old = v.old.and_then(|i| state.manifolds.get(i as usize));
    let may_begin = old.is_none_or(|o| !o.is_touching());
    if may_begin || a.is_sleeping() || b.is_sleeping() {
        v.speed = approach_speed(m, a, b);
    }
    let rotations = [Mat3::from_quat(a.rotation()), Mat3::from_quat(b.rotation())];
    warm_start_points(m, (a, b), old, &rotations);
}

/// What [`keep_judged`] fills: the kept manifolds' approach speeds and, with `carried` manifolds, whether
/// each counts as pushed before the solver runs; and the dropped manifolds' counts.
pub(super) struct Kept<'a> {
    pub(super) speeds: &'a mut Vec<f32>,
    pub(super) pushed: &'a mut Vec<bool>,
    pub(super) carried: bool,
    pub(super) counts: &'a mut Dropped,
}

/// The one-thread part of the walk after [`judge_on_pool`]: the kept manifolds moved down over the dropped
/// ones in order, up to the cap on contact points, as the one-thread walk keeps them. Returns how many were
/// kept.
pub(super) fn keep_judged(
    state: &WorldState,
    manifolds: &mut [ContactManifold],
    verdicts: &[Verdict],
    out: &mut Kept<'_>,
) -> usize {
    let (mut kept, mut points) = (0, 0);
    let max_points = state.settings.limits.max_contact_points as usize;
    for (index, verdict) in verdicts.iter().enumerate().take(manifolds.len()) {
        match verdict.kind {
            Kind::Kept => {}
            Kind::Quarantined => {
                out.counts.quarantined += 1;
                continue;
            }
            Kind::Rejected => continue,
        }
        let point_count = manifolds[index].point_count;
        if out.counts.capped > 0 || points + point_count > max_points {
            out.counts.capped += 1;
            continue;
        }
        points += point_count;
        if kept != index {
            manifolds.swap(kept, index);
        }
        let manifold = &manifolds[kept];
        kept += 1;
        out.speeds.push(verdict.speed);
        if out.carried {
            let (a, b) = (
                state.bodies.get(manifold.body_a),
                state.bodies.get(manifold.body_b),
            );
            out.pushed.push(
                a.zip(b).is_some_and(|(a, b)| !moves(a) && !moves(b))
                    && state
                        .touching
                        .binary_search(&ordered(manifold.body_a, manifold.body_b))
                        .is_ok(),
            );
        }
    }
    kept
}
