//! The pair filter: what an overlapping pair of leaves must pass to become a candidate pair, and the dense
//! per-collider record ([`Candidate`]) it reads instead of looking colliders and bodies up in their arenas.

use crate::prediction::{ball_center, centres_clearly_apart, prediction_distance};
use crate::{Collider, ColliderHandle, ColliderSet, ColliderShape, CollisionGroups};
use rebound_dynamics::{BodyType, RigidBody};
use rebound_math::Vec3;
use rebound_world::BodyHandle;
use std::collections::BTreeSet;

/// Overlapping leaf pairs per run of the kept overlaps' filter (a task on the pool).
const PAIRS_PER_TASK: usize = 1024;

/// A body that moves and may push or be pushed this step: awake and not fixed.
pub(crate) fn is_active(body: &RigidBody) -> bool {
    !body.is_sleeping() && body.body_type() != BodyType::Fixed
}

/// A pair in ascending order.
pub(crate) fn ordered<T: Ord>(a: T, b: T) -> (T, T) {
    if a <= b { (a, b) } else { (b, a) }
}

/// Whether two colliders (on existing bodies) may touch: different bodies, both enabled, neither a sensor,
/// groups that accept each other, contacts not disabled by a joint, and at least one dynamic body.
fn can_collide(
    x: &Candidate,
    y: &Candidate,
    disabled_pairs: &BTreeSet<(BodyHandle, BodyHandle)>,
) -> bool {
    x.body != y.body
        && x.collides
        && y.collides
        && x.groups.interacts_with(y.groups)
        && (x.dynamic || y.dynamic)
        && !disabled_pairs.contains(&ordered(x.body, y.body))
}

/// What the pair filter reads of one collider and its body, gathered once a step in a dense array by collider
/// slot ([`BroadPhase::find_pairs`]): every overlapping pair reads two of these instead of looking both
/// colliders and both bodies up in their arenas.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidate {
    /// The collider (a pair of handles from an older traversal must still name it).
    pub(super) handle: ColliderHandle,
    pub(super) body: BodyHandle,
    /// Enabled and not a sensor.
    pub(super) collides: bool,
    /// Collides, and its body is awake and not fixed.
    pub(super) mover: bool,
    /// Its body is dynamic.
    pub(super) dynamic: bool,
    pub(super) groups: CollisionGroups,
    /// A ball's world centre and radius (m).
    pub(super) ball: Option<(Vec3, f32)>,
    /// The body's linear velocity (m/s) and the collider's rotation reach `|ω|·r` (m/s).
    pub(super) velocity: Vec3,
    pub(super) reach: f32,
}

impl Candidate {
    /// The record of `collider` (`handle`) on `body`, with its rotation reach (m/s).
    #[inline]
    pub(super) fn of(
        handle: ColliderHandle,
        collider: &Collider,
        body: &RigidBody,
        reach: f32,
    ) -> Self {
        let collides = collider.desc.enabled && !collider.desc.is_sensor;
        Self {
            handle,
            body: collider.body,
            collides,
            mover: collides && is_active(body),
            dynamic: body.is_dynamic(),
            groups: collider.desc.groups,
            ball: match collider.desc.shape {
                ColliderShape::Ball { radius } => Some((ball_center(collider, body), radius)),
                _ => None,
            },
            velocity: body.linear_velocity(),
            reach,
        }
    }
}

/// The filters a pair of overlapping leaves passes to become a candidate: at least one of the two colliders
/// moves, [`can_collide`], and two balls are not farther apart than the narrow phase's prediction distance (a
/// swinging chain's fat boxes overlap four times as many neighbours as can touch this step) — the narrow
/// phase's own test ([`centres_clearly_apart`]) on the same values.
pub(super) struct PairFilter<'a> {
    pub(super) candidates: &'a [Option<Candidate>],
    pub(super) disabled_pairs: &'a BTreeSet<(BodyHandle, BodyHandle)>,
    pub(super) speculative_margin: f32,
    pub(super) dt: f32,
}

impl PairFilter<'_> {
    /// Whether colliders `h1` < `h2` are a candidate pair.
    pub(super) fn keeps(&self, h1: ColliderHandle, h2: ColliderHandle) -> bool {
        let candidate = |h: ColliderHandle| {
            self.candidates
                .get(h.0.index as usize)
                .and_then(Option::as_ref)
                .filter(|c| c.handle == h)
        };
        let (Some(x), Some(y)) = (candidate(h1), candidate(h2)) else {
            return false;
        };
        self.keeps_candidates(x, y)
    }

    /// The candidate pair of two overlapping leaves (slots), lower handle first, if it passes: what
    /// [`leaf_pair`] then [`PairFilter::keeps`] give, with the handles read from this step's candidates (every
    /// collider on a live body has one, holding its current handle) instead of from the collider arena.
    pub(super) fn keeps_leaves(
        &self,
        slot1: u32,
        slot2: u32,
    ) -> Option<(ColliderHandle, ColliderHandle)> {
        if slot1 == slot2 {
            return None;
        }
        let candidate = |slot: u32| self.candidates.get(slot as usize).and_then(Option::as_ref);
        let (mut x, mut y) = (candidate(slot1)?, candidate(slot2)?);
        if y.handle < x.handle {
            core::mem::swap(&mut x, &mut y);
        }
        self.keeps_candidates(x, y).then_some((x.handle, y.handle))
    }

    /// The filters on the candidates of colliders `x` and `y` (`x` the lower handle).
    fn keeps_candidates(&self, x: &Candidate, y: &Candidate) -> bool {
        if !(x.mover || y.mover) {
            return false;
        }
        // The distance test of two balls before the pair filter's ordered-set lookup of disabled body pairs:
        // most overlapping boxes of a swinging chain fail it (the same answer in either order).
        if let (Some(ball1), Some(ball2)) = (x.ball, y.ball) {
            let prediction = prediction_distance(
                (x.velocity, y.velocity),
                (x.reach, y.reach),
                self.speculative_margin,
                self.dt,
            );
            if centres_clearly_apart(ball1, ball2, prediction) {
                return false;
            }
        }
        can_collide(x, y, self.disabled_pairs)
    }
}

/// The colliders of two overlapping leaves (slots), lower handle first; `None` for a leaf overlapping itself
/// or a slot without a collider.
#[inline]
pub(super) fn leaf_pair(
    colliders: &ColliderSet,
    slot1: u32,
    slot2: u32,
) -> Option<(ColliderHandle, ColliderHandle)> {
    if slot1 == slot2 {
        return None;
    }
    let (Some((h1, _)), Some((h2, _))) = (colliders.at_slot(slot1), colliders.at_slot(slot2))
    else {
        return None;
    };
    Some(ordered(h1, h2))
}

/// The kept overlaps that pass `filter`, in their order, into `pairs`: over the pool when it has more than
/// one thread, in runs of [`PAIRS_PER_TASK`], each filtered into its own buffer of `parts` (kept from step
/// to step).
pub(super) fn filter_kept(
    overlaps: &[(ColliderHandle, ColliderHandle)],
    filter: &PairFilter<'_>,
    parts: &mut Vec<Vec<(ColliderHandle, ColliderHandle)>>,
    pairs: &mut Vec<(ColliderHandle, ColliderHandle)>,
) {
    rebound_math::par::extend_in_parts(
        pairs,
        parts,
        overlaps.len().div_ceil(PAIRS_PER_TASK),
        |r, part| {
            let run = overlaps
                .get(r * PAIRS_PER_TASK..)
                .unwrap_or_default()
                .iter()
                .take(PAIRS_PER_TASK);
            part.extend(run.copied().filter(|&(h1, h2)| filter.keeps(h1, h2)));
        },
    );
}
