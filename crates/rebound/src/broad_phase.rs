//! The broad phase (first half of the collide stage) and the spatial index queries use: parry3d's incremental
//! [`Bvh`] over every collider's bounding box.
//!
//! **At the start of a step** every collider's box at the current pose is fattened by the speculative margin
//! of its body:
//!
//! ```text
//! margin = settings.speculative_margin + (|v| + |ω|·r)·dt      (awake, non-fixed bodies; 0 otherwise)
//! ```
//!
//! where `r` bounds the distance from the centre of mass to the box, so the box covers everything the body can
//! reach during the step (rotation included). A leaf that already contains its collider's fat box is kept;
//! the others get the fat box — loosened by half the speculative margin for a slow body, so that a resting
//! body's jitter does not change its leaf every step. If any leaf changed, the tree is refitted and traversed
//! against itself once (every pair of overlapping leaves: one traversal finds the pairs a query per moving
//! collider would, with less work). If none did, the overlapping leaves are the last
//! traversal's, kept sorted (when few leaves changed, as in a pile coming to rest, that traversal keeps them):
//! a resting pyramid does no traversal at all. The overlaps with at least one moving collider that pass the
//! filters (same body, enabled, sensor, groups, disabled body pairs, at least one dynamic body) are the
//! candidate pairs, sorted by collider handle: the order never depends on the tree's shape. Two balls whose
//! centres are farther apart than their radii plus the narrow phase's prediction distance (which counts
//! their *relative* speed, where the boxes count each one's own) are dropped here: they can get no contact
//! this step. Balls moving together — a swinging chain, a falling pile — have boxes fattened by their speed
//! that overlap many neighbours they cannot reach (the chain scene: some 2,000 such pairs a step for 500
//! balls).
//!
//! **At the end of a step** (and whenever the world is edited through the facade) the leaves are made to hold
//! the tight boxes of the new poses (a leaf that contains its box is kept), so queries between steps see the
//! current state. After `body_mut` the tree may be stale; queries then test every collider's current box
//! instead (slower, always correct) until the next step or [`crate::PhysicsWorld::refresh_queries`].
//!
//! **Determinism.** Kept leaves are larger than the current fat boxes, so the candidate pairs depend on the
//! history of the tree (a restored snapshot starts from a new tree of tight boxes) — but only by pairs whose
//! current fat boxes do not overlap, and those can get no contact: the narrow phase's prediction distance for
//! a pair, `speculative_margin + (|v₁ − v₂| + |ω₁|·r₁ + |ω₂|·r₂)·dt`, is at most the sum of the two margins,
//! and shapes whose fattened boxes are apart are farther apart than that. The narrow phase treats each pair
//! on its own (a pair's persistent cache forgets its history, a box pair is recycled from last step's
//! *contacts* only), so the contacts — and the step — are a function of the current state alone, which is
//! what makes a restored snapshot step like the world that never stopped.

use crate::pair_sort::radix_sort_pairs;
use crate::prediction::{ball_center_at, is_swept, rotation_reach};
use crate::shape::to_parry_pose;
use crate::{Collider, ColliderHandle, ColliderSet, ColliderShape, MAX_SHAPE_COORDINATE};
use pair_filter::{Candidate, PairFilter, filter_kept, leaf_pair};
pub(crate) use pair_filter::{is_active, ordered};
use parry3d::bounding_volume::{Aabb, BoundingVolume};
use parry3d::partitioning::{Bvh, BvhWorkspace};
#[cfg(feature = "parallel")]
use pool::{POOL_SEARCH_BELOW, on_pool, search_on_pool};
use rebound_dynamics::RigidBody;
use rebound_math::{Pose, Vec3};
use rebound_world::{BodyHandle, BodySet};
use std::collections::BTreeSet;

mod pair_filter;
#[cfg(feature = "parallel")]
mod pool;
#[cfg(feature = "parallel")]
mod self_overlaps;

/// A slow body's new leaf is its fat box loosened by this fraction of the speculative margin, so that it
/// holds the body's fat box for many steps of resting jitter (see the module docs).
const LEAF_SLACK: f32 = 0.5;

/// A body counts as slow while the speed part of its margin, `(|v| + |ω|·r)·dt`, is below this fraction of
/// the speculative margin; a faster body's leaf would not hold its next fat box anyway.
const LEAF_SLACK_BELOW: f32 = 0.5;

/// The overlapping leaves are kept for the next steps when at most one leaf in this many changed this step.
const KEEP_OVERLAPS_BELOW: usize = 8;

/// The largest fattening margin (m). A margin beyond this (absurd velocities or steps) already makes every
/// box overlap every other; capping it keeps the tree's arithmetic finite.
const MAX_MARGIN: f32 = 1.0e7;

/// The world-space box of `collider` on a body at `body`'s pose.
pub(crate) fn world_aabb(collider: &Collider, body: &RigidBody) -> Aabb {
    aabb_at(collider, body.pose())
}

/// The world-space box of `collider` on a body at `body_pose`. A ball's is its centre ± its radius, computed
/// here (what parry computes, without composing the poses, converting them and calling through the shape
/// trait object: two boxes a step for every collider of a pile of balls or a chain).
pub(crate) fn aabb_at(collider: &Collider, body_pose: Pose) -> Aabb {
    match collider.desc.shape {
        ColliderShape::Ball { radius } => {
            let (center, r) = (ball_center_at(collider, body_pose), Vec3::splat(radius));
            return Aabb::new(center - r, center + r);
        }
        ColliderShape::HalfSpace { .. } => {
            // parry's box of a half-space is ±f32::MAX/2, whose volume and merges overflow in the tree.
            let reach = Vec3::splat(MAX_SHAPE_COORDINATE);
            return Aabb::new(-reach, reach);
        }
        _ => {}
    }
    collider
        .shape
        .compute_aabb(&to_parry_pose(collider.world_pose(body_pose)))
}

/// One collider at the start of the pair search: its fat box, its [`Candidate`], whether its body is slow
/// (its new leaf gets some slack), and its body's pose if the body turns far enough to be swept ([`crate::prediction::is_swept`]).
#[cfg_attr(feature = "parallel", derive(Clone))]
struct Fattened {
    fat: Aabb,
    candidate: Candidate,
    /// The speed part of its margin is below [`LEAF_SLACK_BELOW`] of the speculative margin.
    slow: bool,
    swept: Option<Pose>,
}

impl Fattened {
    /// Collider `handle` (`collider`) on `body`, for a step of `dt` seconds.
    #[inline(always)]
    fn of(
        handle: ColliderHandle,
        collider: &Collider,
        body: &RigidBody,
        speculative_margin: f32,
        dt: f32,
    ) -> Self {
        let aabb = world_aabb(collider, body);
        let active = is_active(body);
        // How far rotation can move the collider's surface per second this step (m/s; 0 for a body that
        // does not move).
        let reach = if active {
            rotation_reach(body, &aabb)
        } else {
            0.0
        };
        let margin = if active {
            let speed = body.linear_velocity().length() + reach;
            (speculative_margin + speed * dt).min(MAX_MARGIN)
        } else {
            0.0
        };
        Self {
            fat: aabb.loosened(margin),
            candidate: Candidate::of(handle, collider, body, reach),
            slow: margin - speculative_margin < LEAF_SLACK_BELOW * speculative_margin,
            swept: (active && is_swept(collider, body, dt)).then(|| body.pose()),
        }
    }

    /// How much a new leaf loosens the fat box (m): some slack if the body is slow, so that a resting
    /// body's jitter does not change its leaf every step.
    #[inline(always)]
    fn slack(&self, speculative_margin: f32) -> f32 {
        if self.slow {
            LEAF_SLACK * speculative_margin
        } else {
            0.0
        }
    }
}

/// The BVH and the candidate pairs of the last step.
#[derive(Clone, Default)]
pub(crate) struct BroadPhase {
    bvh: Bvh,
    workspace: BvhWorkspace,
    /// Whether every leaf holds (contains) the collider's box at its body's current pose.
    query_ready: bool,
    /// Candidate pairs of the last step, sorted, lower handle first.
    pub(crate) pairs: Vec<(ColliderHandle, ColliderHandle)>,
    /// Every pair of overlapping leaves (sorted, lower handle first, before any filter) as the last traversal
    /// of the tree found them, and whether the leaves are still the ones it traversed: a step whose leaves all
    /// still hold their colliders' fat boxes filters this list again instead of traversing the tree.
    overlaps: Vec<(ColliderHandle, ColliderHandle)>,
    overlaps_current: bool,
    /// This step's [`Candidate`] of each collider slot (`None`: no collider, or its body is gone).
    candidates: Vec<Option<Candidate>>,
    /// Whether any collider of a moving body took part in the last pair search (without one there are no
    /// pairs to find).
    any_mover: bool,
    /// The bodies the last pair search found turning far enough to be swept, with their poses then.
    swept: Vec<(BodyHandle, Pose)>,
    /// Scratch of the pair sort (reused: no allocation per step).
    sort_scratch: Vec<(ColliderHandle, ColliderHandle)>,
    /// Candidate pairs the last pair search left out because of its cap.
    capped: usize,
    /// Scratch of the kept overlaps' filter on the pool: the pairs of each run (reused: no allocation per
    /// step).
    filter_parts: Vec<Vec<(ColliderHandle, ColliderHandle)>>,
    /// The pool's traversal of the tree against itself: its copy of the tree and its buffers (reused).
    #[cfg(feature = "parallel")]
    self_overlaps: self_overlaps::SelfOverlaps<(ColliderHandle, ColliderHandle)>,
    /// The pool's sort of the pairs its traversal found: its buffers (reused).
    #[cfg(feature = "parallel")]
    pool_sort: crate::pair_sort::PartSort,
    /// Per collider slot, what the pool computed for the pair search's boxes and for the refresh (scratch of
    /// `pool::on_pool`, reused: no allocation per step).
    #[cfg(feature = "parallel")]
    pool_fattened: Vec<Option<Option<(Fattened, bool)>>>,
    #[cfg(feature = "parallel")]
    pool_tightened: Vec<Option<Option<(Aabb, bool)>>>,
}

impl core::fmt::Debug for BroadPhase {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("BroadPhase")
            .field("leaf_count", &self.bvh.leaf_count())
            .field("query_ready", &self.query_ready)
            .field("pairs", &self.pairs.len())
            .finish_non_exhaustive()
    }
}

impl BroadPhase {
    /// Stage *collide*, part 1: fattened boxes, refit, sorted candidate pairs.
    pub(crate) fn find_pairs(
        &mut self,
        colliders: &ColliderSet,
        bodies: &BodySet,
        disabled_pairs: &BTreeSet<(BodyHandle, BodyHandle)>,
        speculative_margin: f32,
        dt: f32,
        max_pairs: usize,
    ) {
        // Candidate pairs the last search found, those its cap left out included.
        #[cfg(feature = "parallel")]
        let last_found = self.pairs.len() + self.capped;
        self.any_mover = false;
        self.capped = 0;
        // One record per collider slot, `None` until its collider is seen.
        self.candidates.clear();
        self.candidates.resize(colliders.arena.capacity(), None);
        self.swept.clear();
        let changed = self.fatten_all(colliders, bodies, speculative_margin, dt);
        self.query_ready = false;
        if changed > 0 {
            refit(&mut self.bvh, &mut self.workspace);
            // Moving leaves degrade the tree; parry rebuilds a few subtrees per call (rapier does this per
            // step).
            self.bvh.optimize_incremental(&mut self.workspace);
            self.overlaps_current = false;
        }

        self.pairs.clear();
        if !self.any_mover {
            return;
        }
        let filter = PairFilter {
            candidates: &self.candidates,
            disabled_pairs,
            speculative_margin,
            dt,
        };
        // Few leaves changed (a pile coming to rest): the overlaps are traversed and kept, for the steps
        // after, in which no leaf changes, to filter again. Many changed (bodies on the move): the traversal
        // filters as it goes and keeps nothing, as the next step traverses again anyway.
        if self.overlaps_current || changed * KEEP_OVERLAPS_BELOW <= self.bvh.leaf_count() as usize
        {
            if !self.overlaps_current {
                // More overlaps than the cap allows pairs: not kept (the traversal below caps them).
                self.overlaps_current = find_overlaps(
                    &mut self.bvh,
                    &mut self.workspace,
                    colliders,
                    &mut self.overlaps,
                    &mut self.sort_scratch,
                    max_pairs,
                );
            }
            if self.overlaps_current {
                filter_kept(
                    &self.overlaps,
                    &filter,
                    &mut self.filter_parts,
                    &mut self.pairs,
                );
                return;
            }
        }
        // On a pool of several threads, while the last search stayed well below the cap.
        #[cfg(feature = "parallel")]
        if rebound_math::par::is_parallel() && last_found * POOL_SEARCH_BELOW <= max_pairs {
            self.capped += search_on_pool(
                &self.bvh,
                &mut self.self_overlaps,
                |slot1, slot2| filter.keeps_leaves(slot1, slot2),
                self.candidates.len(),
                &mut self.pool_sort,
                &mut self.pairs,
                max_pairs,
            );
            return;
        }
        let (pairs, scratch, capped) = (&mut self.pairs, &mut self.sort_scratch, &mut self.capped);
        let trim_at = 2 * max_pairs;
        self.bvh
            .traverse_bvtt_single_tree::<false>(&mut self.workspace, &mut |slot1, slot2| {
                if let Some(pair) = filter.keeps_leaves(slot1, slot2) {
                    pairs.push(pair);
                    if pairs.len() >= trim_at {
                        *capped += keep_lowest(pairs, scratch, max_pairs);
                    }
                }
            });
        // Sorted by the two slot indices: the same order as the handles' (live colliders have distinct
        // slots, and a handle orders by slot first).
        self.capped += keep_lowest(&mut self.pairs, &mut self.sort_scratch, max_pairs);
    }

    /// The first part of the pair search: every collider's [`Fattened`] box and [`Candidate`], each leaf
    /// that does not hold its collider's fat box updated, the leaves of colliders on removed bodies removed
    /// (on a pool of several threads the boxes and leaf tests over the pool, then the tree's updates in
    /// collider order: `on_pool`). Returns how many leaves changed.
    fn fatten_all(
        &mut self,
        colliders: &ColliderSet,
        bodies: &BodySet,
        speculative_margin: f32,
        dt: f32,
    ) -> usize {
        let mut changed = 0;
        #[cfg(feature = "parallel")]
        if rebound_math::par::is_parallel() {
            let mut computed = core::mem::take(&mut self.pool_fattened);
            on_pool(
                self,
                colliders,
                &mut computed,
                |bp, handle, collider| {
                    let body = bodies.get(collider.body)?;
                    let f = Fattened::of(handle, collider, body, speculative_margin, dt);
                    let holds = holds(&bp.bvh, handle, &f.fat);
                    Some((f, holds))
                },
                |bp, handle, collider, fattened| {
                    changed += match fattened {
                        Some((f, holds)) => {
                            bp.take(handle, collider.body, &f, holds, speculative_margin)
                        }
                        None => bp.remove_gone(handle),
                    };
                },
            );
            self.pool_fattened = computed;
            return changed;
        }
        for (handle, collider) in colliders.iter() {
            let Some(body) = bodies.get(collider.body) else {
                changed += self.remove_gone(handle);
                continue;
            };
            let f = Fattened::of(handle, collider, body, speculative_margin, dt);
            let holds = holds(&self.bvh, handle, &f.fat);
            changed += self.take(handle, collider.body, &f, holds, speculative_margin);
        }
        changed
    }

    /// Removes the leaf of collider `handle`, whose body is gone; returns 1 if there was one.
    #[inline]
    fn remove_gone(&mut self, handle: ColliderHandle) -> usize {
        let slot = handle.0.index;
        if self.bvh.leaf_node(slot).is_none() {
            return 0;
        }
        self.bvh.remove(slot);
        1
    }

    /// Records collider `handle`'s candidate (and its body `body` if swept) and, unless its leaf `holds` its
    /// fat box, gives the leaf the fat box loosened by its slack ([`Fattened::slack`]); returns 1 if the leaf
    /// changed.
    #[inline(always)]
    fn take(
        &mut self,
        handle: ColliderHandle,
        body: BodyHandle,
        f: &Fattened,
        holds: bool,
        speculative_margin: f32,
    ) -> usize {
        if let Some(pose) = f.swept
            && !self.swept.iter().any(|&(h, _)| h == body)
        {
            self.swept.push((body, pose));
        }
        self.any_mover |= f.candidate.mover;
        let slot = handle.0.index;
        if let Some(candidate) = self.candidates.get_mut(slot as usize) {
            *candidate = Some(f.candidate);
        }
        // A leaf that holds the fat box stays (see the module docs); a new one gets some slack if the body is
        // slow, so that a resting body's jitter does not change its leaf every step.
        if holds {
            return 0;
        }
        let slack = f.slack(speculative_margin);
        let _ = self
            .bvh
            .insert_or_update_partially(f.fat.loosened(slack), slot, 0.0);
        1
    }

    /// How many candidate pairs the last [`BroadPhase::find_pairs`] left out because of its cap.
    pub(crate) fn capped_pair_count(&self) -> usize {
        self.capped
    }

    /// Makes every leaf of the tree hold the box of its collider at its body's current pose (end of a step,
    /// after a restore, on request): a leaf that already contains that box — the fattened box of the step's
    /// pair search, which a body rarely leaves within the step — is kept, the others get the tight box, and
    /// the tree is refitted only if a leaf changed. Queries test their candidates exactly, so a leaf larger
    /// than its collider only adds a candidate; keeping the pair search's boxes spares a swinging chain a
    /// refit of the whole tree every step.
    pub(crate) fn refresh(&mut self, colliders: &ColliderSet, bodies: &BodySet) {
        let changed = self.tighten_all(colliders, bodies);
        if changed > 0 {
            refit(&mut self.bvh, &mut self.workspace);
            self.overlaps_current = false;
        }
        self.query_ready = true;
    }

    /// The leaves of [`BroadPhase::refresh`]: each that does not hold its collider's current box gets it, the
    /// leaves of colliders on removed bodies are removed (on a pool of several threads the boxes and leaf
    /// tests over the pool, then the tree's updates in collider order: `on_pool`). Returns how many leaves
    /// changed.
    fn tighten_all(&mut self, colliders: &ColliderSet, bodies: &BodySet) -> usize {
        let mut changed = 0;
        #[cfg(feature = "parallel")]
        if rebound_math::par::is_parallel() {
            let mut computed = core::mem::take(&mut self.pool_tightened);
            on_pool(
                self,
                colliders,
                &mut computed,
                |bp, handle, collider| {
                    let aabb = world_aabb(collider, bodies.get(collider.body)?);
                    Some((aabb, holds(&bp.bvh, handle, &aabb)))
                },
                |bp, handle, _, tight| match tight {
                    Some((_, true)) => {}
                    Some((aabb, false)) => {
                        let _ = bp.bvh.insert_or_update_partially(aabb, handle.0.index, 0.0);
                        changed += 1;
                    }
                    None => changed += bp.remove_gone(handle),
                },
            );
            self.pool_tightened = computed;
            return changed;
        }
        for (handle, collider) in colliders.iter() {
            let Some(body) = bodies.get(collider.body) else {
                changed += self.remove_gone(handle);
                continue;
            };
            let aabb = world_aabb(collider, body);
            if holds(&self.bvh, handle, &aabb) {
                continue;
            }
            let _ = self
                .bvh
                .insert_or_update_partially(aabb, handle.0.index, 0.0);
            changed += 1;
        }
        changed
    }

    /// A new tree holding every collider (after a restore): same leaves, whatever the old tree's shape.
    pub(crate) fn rebuild(&mut self, colliders: &ColliderSet, bodies: &BodySet) {
        self.bvh = Bvh::new();
        self.overlaps_current = false;
        self.pairs.clear();
        self.candidates.clear();
        self.refresh(colliders, bodies);
    }

    /// The bodies this step's pair search found turning far enough to be swept
    /// ([`crate::prediction::is_swept`]), with their poses at the start of the step.
    pub(crate) fn swept(&self) -> &[(BodyHandle, Pose)] {
        &self.swept
    }

    /// |ω|·r of collider `handle` this step (m/s; 0 for one this step's pair search did not see).
    pub(crate) fn rotation_reach(&self, handle: ColliderHandle) -> f32 {
        self.candidates
            .get(handle.0.index as usize)
            .and_then(Option::as_ref)
            .filter(|c| c.handle == handle)
            .map_or(0.0, |c| c.reach)
    }

    /// Adds or updates one collider's leaf, keeping the tree valid for queries.
    pub(crate) fn insert_leaf(
        &mut self,
        handle: ColliderHandle,
        collider: &Collider,
        body_pose: Pose,
    ) {
        self.bvh
            .insert(aabb_at(collider, body_pose), handle.0.index);
        self.overlaps_current = false;
    }

    /// Removes one collider's leaf.
    pub(crate) fn remove_leaf(&mut self, handle: ColliderHandle) {
        self.bvh.remove(handle.0.index);
        self.overlaps_current = false;
    }

    /// Marks the boxes as possibly stale (a body may have moved): queries test every collider until the next
    /// refresh.
    pub(crate) fn mark_stale(&mut self) {
        self.query_ready = false;
    }

    /// The colliders whose box passes `test`, sorted by handle (so results never depend on the tree's
    /// shape): a superset of those whose current box does — the tree's leaves contain the current boxes
    /// ([`BroadPhase::refresh`]) — for the caller to test exactly; without a refreshed tree, the current boxes
    /// themselves.
    pub(crate) fn candidates(
        &self,
        colliders: &ColliderSet,
        bodies: &BodySet,
        test: impl Fn(&Aabb) -> bool,
        out: &mut Vec<ColliderHandle>,
    ) {
        out.clear();
        if self.query_ready {
            out.extend(
                self.bvh
                    .leaves(|node| test(&node.aabb()))
                    .filter_map(|slot| colliders.at_slot(slot).map(|(h, _)| h)),
            );
        } else {
            for (handle, collider) in colliders.iter() {
                if let Some(body) = bodies.get(collider.body)
                    && test(&world_aabb(collider, body))
                {
                    out.push(handle);
                }
            }
        }
        out.sort_unstable();
        out.dedup();
    }
}

/// One traversal of `bvh` against itself: every pair of overlapping leaves into `overlaps` (cleared first),
/// sorted by the two slot indices — the same order as the handles' (live colliders have distinct slots, and
/// a handle orders by slot first) — whatever the tree's shape.
///
/// Returns `false`, with `overlaps` left incomplete, once they exceed `cap`: a pile that dense is left to the
/// capped pair search, whose result does not depend on whether overlaps were kept.
fn find_overlaps(
    bvh: &mut Bvh,
    workspace: &mut BvhWorkspace,
    colliders: &ColliderSet,
    overlaps: &mut Vec<(ColliderHandle, ColliderHandle)>,
    scratch: &mut Vec<(ColliderHandle, ColliderHandle)>,
    cap: usize,
) -> bool {
    overlaps.clear();
    let mut complete = true;
    bvh.traverse_bvtt_single_tree::<false>(workspace, &mut |slot1, slot2| {
        if complete {
            overlaps.extend(leaf_pair(colliders, slot1, slot2));
            complete = overlaps.len() <= 2 * cap;
        }
    });
    if !complete {
        overlaps.clear();
        return false;
    }
    radix_sort_pairs(overlaps, scratch);
    overlaps.dedup();
    if overlaps.len() > cap {
        overlaps.clear();
        return false;
    }
    true
}

/// Whether the leaf of collider `handle` in `bvh` holds (contains) `aabb`.
#[inline(always)]
fn holds(bvh: &Bvh, handle: ColliderHandle, aabb: &Aabb) -> bool {
    bvh.leaf_node(handle.0.index)
        .is_some_and(|leaf| leaf.contains_aabb(aabb))
}

/// Refits the tree after leaves changed: on the pool (parry's refit with its subtrees as tasks, the same
/// nodes in the same layout) when it has more than one thread.
fn refit(bvh: &mut Bvh, workspace: &mut BvhWorkspace) {
    #[cfg(feature = "parallel")]
    if rebound_math::par::is_parallel() {
        bvh.refit_parallel(workspace);
        return;
    }
    bvh.refit(workspace);
}

/// Sorts and deduplicates `pairs` and keeps the `cap` lowest; returns how many were left out. Called
/// whenever the pair search has gathered twice the cap, and at its end, it bounds the memory of the search at
/// `2·cap` pairs and keeps the same pairs whatever order the tree yields them in: the `cap` lowest of all.
/// Never inlined: the traversal's callback stays small enough to be inlined into the traversal.
#[inline(never)]
fn keep_lowest(
    pairs: &mut Vec<(ColliderHandle, ColliderHandle)>,
    scratch: &mut Vec<(ColliderHandle, ColliderHandle)>,
    cap: usize,
) -> usize {
    radix_sort_pairs(pairs, scratch);
    pairs.dedup();
    let dropped = pairs.len().saturating_sub(cap);
    pairs.truncate(cap);
    dropped
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;

    #[test]
    fn a_resting_stack_keeps_its_leaves_and_overlaps_and_a_moved_box_traverses_again() {
        let settings = WorldSettings {
            sleep_enabled: false,
            ..WorldSettings::default()
        };
        let mut world = PhysicsWorld::new(settings).unwrap();
        let ground = world
            .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)), ground)
            .unwrap();
        let boxes: Vec<BodyHandle> = (0..3)
            .map(|k| {
                let body = world
                    .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
                        0.0,
                        0.5 + k as f32,
                        0.0,
                    )))
                    .unwrap();
                world
                    .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), body)
                    .unwrap();
                body
            })
            .collect();
        for _ in 0..120 {
            world.step(1.0 / 60.0);
        }
        // A pair no traversal finds, appended to the kept overlaps: still last after a step means the step
        // filtered them again without traversing the tree.
        let marker = (ColliderHandle::invalid(), ColliderHandle::invalid());
        world.world.backend_mut().broad_phase.overlaps.push(marker);
        // (overlaps kept for the next step, marker still last, candidate pairs) after one more step.
        let step = |world: &mut PhysicsWorld| {
            world.step(1.0 / 60.0);
            let broad_phase = &world.world().backend().broad_phase;
            (
                broad_phase.overlaps_current,
                broad_phase.overlaps.last() == Some(&marker),
                broad_phase.pairs.len(),
            )
        };
        // At rest no leaf changes: the kept overlaps are filtered again, into every touching pair (ground–box
        // 0, box 0–1, box 1–2).
        assert_eq!(step(&mut world), (true, true, 3));
        assert_eq!(world.contacts().len(), 3);
        // A box teleported into the air leaves its leaf: the next step traverses again (one leaf in four
        // changed: filtering as it goes, keeping nothing) and drops its pairs; the step after, with no leaf
        // changed, traverses once more and keeps the overlaps.
        world
            .body_mut(boxes[2])
            .unwrap()
            .set_position(Vec3::new(5.0, 3.0, 0.0))
            .unwrap();
        assert_eq!(step(&mut world), (false, true, 2));
        assert_eq!(step(&mut world), (true, false, 2));
    }

    /// On a pool of two threads the pair search (boxes, traversal, filter, refit, the kept overlaps of a
    /// pile coming to rest) finds, step by step, the pairs one thread finds, and the worlds end in the same
    /// state: a falling cloud of 600 balls on a ground, then at rest.
    #[cfg(feature = "parallel")]
    #[test]
    fn the_pool_finds_the_pairs_of_one_thread() {
        let cloud = |threads: usize| {
            let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
            world.set_thread_count(threads).unwrap();
            world.set_min_work_for_threads(0);
            let ground = world.insert_body(BodyDesc::fixed()).unwrap();
            world
                .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), ground)
                .unwrap();
            for k in 0..600_u32 {
                let (i, j, l) = (k % 10, (k / 10) % 6, k / 60);
                // A lattice sheared by the height, so that columns do not line up.
                let position = Vec3::new(
                    i as f32 * 0.9 + j as f32 * 0.13,
                    1.0 + l as f32 * 0.9,
                    j as f32 * 0.9 + l as f32 * 0.07,
                );
                let body = world
                    .insert_body(BodyDesc::dynamic().with_position(position))
                    .unwrap();
                world
                    .insert_collider(ColliderDesc::ball(0.4), body)
                    .unwrap();
            }
            world
        };
        let (mut one, mut two) = (cloud(1), cloud(2));
        let mut with_pairs = 0;
        for step in 0..90 {
            one.step(1.0 / 60.0);
            two.step(1.0 / 60.0);
            // By slot: each world has its own handle generations.
            let pairs = |w: &PhysicsWorld| {
                let pairs = &w.world().backend().broad_phase.pairs;
                pairs
                    .iter()
                    .map(|(a, b)| (a.0.index, b.0.index))
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                pairs(&one),
                pairs(&two),
                "step {step}: other pairs on two threads"
            );
            with_pairs += usize::from(!pairs(&one).is_empty());
        }
        // The cloud lands within its first half second and touches from then on.
        assert!(with_pairs > 45, "pairs in only {with_pairs} of 90 steps");
        assert_eq!(one.state_digest(), two.state_digest());
    }
}
