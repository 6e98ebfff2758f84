//! The narrow phase (second half of the collide stage): the contact manifold of each candidate pair — our
//! own generators for two balls and two boxes ([`crate::ball_ball`], [`crate::box_box`], into a stack
//! [`ShapeManifold`]), parry3d's persistent manifolds for everything else — turned into the world's
//! plain-data [`ContactManifold`] at one seam, [`Seam`]; box pairs that barely moved recycle last step's
//! ([`crate::recycling`]).
//!
//! # Pair cache
//!
//! A candidate pair with a composite shape (mesh, height field, compound) keeps its parry manifolds and its
//! [`ContactManifoldsWorkspace`] (the sub-shape bookkeeping) in an ordered map keyed by the ordered collider
//! pair (a vector sorted by key, merged with the step's sorted candidate list in one pass), so iteration is in
//! handle order and pairs that stop being candidates are dropped. A pair of two convex shapes keeps nothing:
//! it is computed in one scratch manifold shared by all such pairs (see [`NarrowPhase`]).
//!
//! The prediction distance of a pair — how far apart its colliders may be for the generators to report
//! points — is the speculative margin plus what the pair can close in the step ([`crate::prediction`]); the
//! narrow phase receives the candidate pairs and each collider's rotation reach, not the broad phase itself.
//!
//! # History independence (why the cache may be thrown away)
//!
//! parry's generators read two pieces of history from a cached manifold: the old contact points, which
//! `try_update_contacts` reuses (only refreshing their separations) while the relative pose changes by less
//! than 1° and 1 mm, and the old normal, which seeds GJK. Both make the contact points depend on the path
//! that led to the current poses, so a world restored from a snapshot (whose cache starts empty) would
//! generate different bits than the world that never stopped. Before each query the seam therefore clears
//! every cached manifold's points and normals: contact generation depends on the current poses only, and the
//! cache keeps what is worth keeping — its allocations and the composite shapes' sub-shape manifolds and
//! workspaces. Warm starting does not need parry's history either: the world matches each new point to last
//! step's impulses by collider pair (`key`) and feature id, and those impulses live in the world's manifolds,
//! which every snapshot contains.
//!
//! # The generators and the seam
//!
//! Two balls go to [`ball_ball`], two boxes to [`box_box_manifold`] (both write a stack [`ShapeManifold`]),
//! other convex pairs to parry's convex–convex generator in one scratch manifold, composite shapes to parry's
//! dispatcher with the pair's cache. Every manifold becomes the world's at [`Seam::push`]; a box pair that
//! barely moved is recycled instead ([`crate::recycling`]).

use crate::ball_ball::ball_ball;
use crate::box_box::box_box_manifold;
use crate::hooks::{self, ContactHooks, ContactPair};
use crate::prediction::prediction_distance;
use crate::recycling::recyclable;
use crate::seam::Seam;
use crate::shape::{from_parry_pose, to_parry_pose};
use crate::shape_manifold::ShapeManifold;
use crate::{Collider, ColliderHandle, ColliderSet, ColliderShape};
use parry3d::query::{
    ContactManifold as ParryManifold, ContactManifoldsWorkspace, DefaultQueryDispatcher,
    PersistentQueryDispatcher,
};
use rebound_dynamics::RigidBody;
use rebound_math::{Pose, Vec3, par, rotate_inverse};
use rebound_world::{BodySet, ContactBasis, ContactManifold, ManifoldWriter};

/// Points a cached parry manifold has room for (see `PairCache::forget_history`).
const POINT_CAPACITY: usize = 8;

/// parry's manifolds and workspace for one collider pair.
#[derive(Clone, Default)]
pub(crate) struct PairCache {
    manifolds: Vec<ParryManifold<(), ()>>,
    workspace: Option<ContactManifoldsWorkspace>,
}

impl PairCache {
    /// Forgets the contact points and normals of every cached manifold (see the module docs).
    fn forget_history(&mut self) {
        self.manifolds.iter_mut().for_each(forget_manifold_history);
    }
}

/// Forgets a parry manifold's contact points and normals (see the module docs), keeping its point buffer.
fn forget_manifold_history(manifold: &mut ParryManifold<(), ()>) {
    manifold.points.clear();
    // Room for a face-on-face clip (up to 8 points before reduction), reserved once per manifold, so that a
    // pair whose contact grows from a corner to a face does not reallocate mid-run.
    manifold.points.reserve(POINT_CAPACITY);
    manifold.local_n1 = Vec3::ZERO;
    manifold.local_n2 = Vec3::ZERO;
}

/// The pair cache: one entry per candidate pair of the last step that involves a composite shape (a mesh, a
/// height field, a compound), sorted by the ordered collider pair (an ordered map kept as a sorted vector: the
/// step's sorted candidate list is merged into it in one linear pass, instead of a tree lookup per pair).
///
/// A pair of two convex shapes keeps nothing: with its history forgotten (see the module docs), its parry
/// manifold is scratch space, so every convex pair is computed in the one manifold [`NarrowPhase::convex`]
/// holds, which stays in cache — a per-pair manifold on the heap would cost a cache miss per pair.
#[derive(Clone, Default)]
pub(crate) struct NarrowPhase {
    pairs: Vec<((ColliderHandle, ColliderHandle), PairCache)>,
    /// Last step's pair list while this step's is built (empty between steps, capacity kept), so that the
    /// step allocates no new list.
    previous: Vec<((ColliderHandle, ColliderHandle), PairCache)>,
    /// The scratch manifold of convex pairs parry generates.
    convex: ParryManifold<(), ()>,
    /// The collider pair of each manifold of the last collide stage that reports contact forces, by manifold
    /// key (sorted by key once the stage is done): contact force events name colliders.
    pub(crate) force_pairs: Vec<(u64, ColliderHandle, ColliderHandle)>,
    /// The runs of the parallel collide stage and their manifolds (scratch: each run writes over its list of
    /// the last stage, capacity kept).
    runs: Vec<(PairRun, Vec<ContactManifold>)>,
    /// Where each run's manifolds start in the stage's list (scratch of the parallel collide stage).
    run_starts: Vec<usize>,
    /// Whether some collider has a force event threshold, with the [`ColliderSet::revision`] it was read
    /// at: a stage without hooks and without such a collider runs the pair loop that watches nothing.
    thresholds: Option<(u64, bool)>,
}

/// The key extension of a convex pair's manifold: parry's sub-shape ids of a convex pair (both 0), so that a
/// pair keeps its key whichever generator made its manifold.
const CONVEX_SUBSHAPES: [u32; 2] = [0, 0];

impl core::fmt::Debug for NarrowPhase {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("NarrowPhase")
            .field("pairs", &self.pairs.len())
            .finish()
    }
}

impl NarrowPhase {
    /// Drops every cached pair (on restore). Contacts do not change: see the module docs.
    pub(crate) fn clear(&mut self) {
        self.pairs.clear();
        self.previous.clear();
    }

    /// The number of cached pairs (pairs with a composite shape).
    pub(crate) fn pair_count(&self) -> usize {
        self.pairs.len()
    }

    /// Stage *collide*, part 2: the manifolds of every candidate pair of `pairs` (the broad phase's, sorted,
    /// lower handle first) into `out`, in pair order; `reach` gives each collider's rotation reach this step
    /// (m/s, [`crate::prediction::rotation_reach`]). With `hooks`, each pair is filtered before and its
    /// manifolds edited after they are made ([`crate::hooks`]), and their failures counted in `failures`.
    ///
    /// A pair's manifolds depend on that pair alone (see the module docs), so without hooks (user code, called
    /// in pair order) the pairs are split into runs of [`PAIRS_PER_TASK`] over the thread pool, each with its
    /// share of the cache, and the runs' manifolds are appended in pair order: the same list for any number
    /// of threads.
    pub(crate) fn collide(
        &mut self,
        pairs: &[(ColliderHandle, ColliderHandle)],
        reach: impl Fn(ColliderHandle) -> f32 + Sync,
        colliders: &ColliderSet,
        bodies: &BodySet,
        speculative_margin: f32,
        dt: f32,
        previous: &[ContactManifold],
        hooks: Option<&dyn ContactHooks>,
        failures: &mut usize,
        out: &mut ManifoldWriter<'_>,
    ) {
        core::mem::swap(&mut self.pairs, &mut self.previous);
        self.force_pairs.clear();
        self.pairs.clear();
        let watched = hooks.is_some() || self.any_threshold(colliders);
        let input = PairInput {
            reach: &reach,
            colliders,
            bodies,
            speculative_margin,
            dt,
            previous,
        };
        if hooks.is_none() && par::is_parallel() && pairs.len() >= 2 * PAIRS_PER_TASK {
            self.collide_runs(pairs, &input, watched, out);
        } else {
            let mut run = PairRun {
                pairs: core::mem::take(&mut self.pairs),
                cached: Vec::new(),
                force_pairs: core::mem::take(&mut self.force_pairs),
                convex: core::mem::take(&mut self.convex),
            };
            let mut old = self.previous.drain(..).peekable();
            if watched {
                run.collide_pairs::<true, _>(pairs, &mut old, &input, hooks, failures, out);
            } else {
                run.collide_pairs::<false, _>(pairs, &mut old, &input, None, failures, out);
            }
            drop(old);
            (self.pairs, self.force_pairs, self.convex) = (run.pairs, run.force_pairs, run.convex);
        }
        self.force_pairs.sort_unstable_by_key(|&(key, _, _)| key);
    }

    /// Whether some collider of `colliders` has a force event threshold: read again only after the set
    /// changed (an insertion, edit, removal or restore moves its revision on).
    fn any_threshold(&mut self, colliders: &ColliderSet) -> bool {
        let revision = colliders.revision();
        match self.thresholds {
            Some((read_at, any)) if read_at == revision => any,
            _ => {
                let any = colliders
                    .iter()
                    .any(|(_, c)| c.desc.force_event_threshold.is_some());
                self.thresholds = Some((revision, any));
                any
            }
        }
    }

    /// [`NarrowPhase::collide`] over the pool: `pairs` in runs of [`PAIRS_PER_TASK`], each with the cached
    /// pairs of its range, its own scratch and its own manifold list, joined in pair order. `watched`: some
    /// collider reports contact forces.
    fn collide_runs(
        &mut self,
        pairs: &[(ColliderHandle, ColliderHandle)],
        input: &PairInput<'_>,
        watched: bool,
        out: &mut ManifoldWriter<'_>,
    ) {
        let count = pairs.len().div_ceil(PAIRS_PER_TASK);
        if self.runs.len() < count {
            self.runs.resize_with(count, Default::default);
        }
        // Each run takes the cached pairs up to its last pair (both lists are sorted) into its own list.
        let mut old = self.previous.drain(..);
        for (range, (run, _)) in pairs.chunks(PAIRS_PER_TASK).zip(&mut self.runs) {
            let last = range.last().copied();
            run.cached.clear();
            let mine = old
                .as_slice()
                .partition_point(|(key, _)| Some(*key) <= last);
            run.cached.extend(old.by_ref().take(mine));
        }
        drop(old);
        let runs = self.runs.get_mut(..count).unwrap_or_default();
        par::for_each_mut(runs, 1, |r, (run, manifolds)| {
            let start = (r * PAIRS_PER_TASK).min(pairs.len());
            let end = (start + PAIRS_PER_TASK).min(pairs.len());
            let range = pairs.get(start..end).unwrap_or_default();
            run.pairs.clear();
            run.force_pairs.clear();
            // Written over last step's in place, as the one-thread stage writes over its list.
            let manifolds = &mut ManifoldWriter::new(manifolds);
            let mut cached = core::mem::take(&mut run.cached);
            let mut old = cached.drain(..).peekable();
            if watched {
                run.collide_pairs::<true, _>(range, &mut old, input, None, &mut 0, manifolds);
            } else {
                run.collide_pairs::<false, _>(range, &mut old, input, None, &mut 0, manifolds);
            }
            drop(old);
            run.cached = cached;
        });
        // The runs' manifolds copied over the pool, each run's into its place in pair order (the slots the
        // list already has written over, the points in use only).
        self.run_starts.clear();
        let mut total = 0;
        for (_, manifolds) in &self.runs[..count] {
            self.run_starts.push(total);
            total += manifolds.len();
        }
        let runs = &self.runs;
        par::for_each_part_mut(
            out.next_slots(total),
            &self.run_starts,
            total,
            |r, slots| {
                if let Some((_, manifolds)) = runs.get(r) {
                    for (slot, manifold) in slots.iter_mut().zip(manifolds) {
                        slot.renew_from(manifold);
                    }
                }
            },
        );
        for (run, _) in &mut self.runs[..count] {
            self.pairs.append(&mut run.pairs);
            self.force_pairs.append(&mut run.force_pairs);
        }
    }

    /// The collider pair of the manifold of key `key` of the last collide stage, if it reports forces.
    pub(crate) fn force_pair(&self, key: u64) -> Option<(ColliderHandle, ColliderHandle)> {
        let i = self
            .force_pairs
            .binary_search_by_key(&key, |&(k, _, _)| k)
            .ok()?;
        self.force_pairs.get(i).map(|&(_, a, b)| (a, b))
    }
}

/// Candidate pairs per task of the parallel narrow phase (a box pair takes about a microsecond).
const PAIRS_PER_TASK: usize = 256;

/// What every pair of a collide stage reads.
struct PairInput<'a> {
    reach: &'a (dyn Fn(ColliderHandle) -> f32 + Sync),
    colliders: &'a ColliderSet,
    bodies: &'a BodySet,
    speculative_margin: f32,
    dt: f32,
    previous: &'a [ContactManifold],
}

/// What a run of consecutive candidate pairs writes besides its manifolds: the cache of its composite pairs,
/// its force-reporting pairs, and the scratch manifold of its convex pairs.
#[derive(Clone, Default)]
struct PairRun {
    pairs: Vec<((ColliderHandle, ColliderHandle), PairCache)>,
    /// Last step's cached pairs of the run's range (the parallel collide stage's; emptied as they are read).
    cached: Vec<((ColliderHandle, ColliderHandle), PairCache)>,
    force_pairs: Vec<(u64, ColliderHandle, ColliderHandle)>,
    convex: ParryManifold<(), ()>,
}

impl PairRun {
    /// The manifolds of `pairs` (sorted) onto `out`, in pair order; `old` holds last step's cached pairs from
    /// the first of `pairs` on, sorted.
    ///
    /// `WATCHED`: the stage has hooks or a collider with a force event threshold, so each pair is filtered,
    /// edited and recorded as it is made. Without (`false`, the common case) the loop is compiled without
    /// that bookkeeping: no per-pair state or test, and a loop small enough to take the generators inline.
    #[expect(
        clippy::too_many_lines,
        reason = "one loop over the pairs, dispatching to the generators"
    )]
    fn collide_pairs<
        const WATCHED: bool,
        I: Iterator<Item = ((ColliderHandle, ColliderHandle), PairCache)>,
    >(
        &mut self,
        pairs: &[(ColliderHandle, ColliderHandle)],
        old: &mut core::iter::Peekable<I>,
        input: &PairInput<'_>,
        hooks: Option<&dyn ContactHooks>,
        failures: &mut usize,
        out: &mut ManifoldWriter<'_>,
    ) {
        let PairInput {
            reach,
            colliders,
            bodies,
            speculative_margin,
            dt,
            previous,
        } = *input;
        // The pair whose manifolds (from `out[first..]`) the hooks edit once they are all made.
        let mut hooked: Option<(ContactPair<'_>, usize)> = None;
        // The pair whose manifolds (from `out[first..]`) report contact forces.
        let mut reporting: Option<(ColliderHandle, ColliderHandle, f32, usize)> = None;
        let mut cursor = 0;
        for &(h1, h2) in pairs {
            if WATCHED {
                if let Some(hooks) = hooks
                    && let Some((pair, first)) = hooked.take()
                {
                    hooks::modify(hooks, &pair, out, first, failures);
                }
                if let Some((a, b, threshold, first)) = reporting.take() {
                    report_forces(
                        &mut self.force_pairs,
                        a,
                        b,
                        threshold,
                        &mut out.as_mut_slice()[first..],
                    );
                }
            }
            let cached = take_cached(old, (h1, h2));
            let (Some(c1), Some(c2)) = (colliders.get(h1), colliders.get(h2)) else {
                continue;
            };
            let (Some(b1), Some(b2)) = (bodies.get(c1.body), bodies.get(c2.body)) else {
                continue;
            };
            if WATCHED && let Some(hooks) = hooks {
                let pair = ContactPair {
                    collider_a: h1,
                    collider_b: h2,
                    a: c1,
                    b: c2,
                    body_a: (c1.body, b1),
                    body_b: (c2.body, b2),
                };
                if !hooks::filter(hooks, &pair, failures) {
                    continue;
                }
                hooked = Some((pair, out.len()));
            }
            if WATCHED && let Some(threshold) = pair_threshold(c1, c2) {
                reporting = Some((h1, h2, threshold, out.len()));
            }
            // Two balls farther apart than this were dropped by the broad phase, with the same test on the
            // same values (`centres_clearly_apart`).
            let prediction = prediction_distance(
                (b1.linear_velocity(), b2.linear_velocity()),
                (reach(h1), reach(h2)),
                speculative_margin,
                dt,
            );
            // Only where a generator runs (a recycled box pair needs none).
            let pos12 = || relative_pose(c1, b1, c2, b2);
            let key_base = pair_key(h1, h2);
            let (shape1, shape2) = (c1.shape.as_ref(), c2.shape.as_ref());
            // Read from the descriptions: no call through the shape trait objects.
            if c1.desc.shape.is_convex() && c2.desc.shape.is_convex() {
                // The two commonest pairs skip parry's dispatch (two trait-object downcasts per shape and
                // pair) and its heap-backed manifold: two balls and two boxes go to our generators
                // (`ball_ball`, crate::box_box), which write a `ShapeManifold` on the stack. The shape kind is
                // read from the collider's description, which built the parry shape.
                let frames = (c1.desc.local_pose, c2.desc.local_pose);
                let seam = |key| Seam {
                    c1,
                    b1,
                    c2,
                    key,
                    frames,
                };
                let mut ours = ShapeManifold::default();
                match (&c1.desc.shape, &c2.desc.shape) {
                    (ColliderShape::Ball { radius: r1 }, ColliderShape::Ball { radius: r2 }) => {
                        ball_ball(&pos12(), *r1, *r2, prediction, &mut ours);
                    }
                    (
                        ColliderShape::Cuboid { half_extents: e1 },
                        ColliderShape::Cuboid { half_extents: e2 },
                    ) => {
                        let key = fnv1a(key_base, &CONVEX_SUBSHAPES);
                        let seam = seam(key);
                        let relative = b1.pose().inverse().mul_pose(&b2.pose());
                        // Not with hooks: a recycled manifold would keep the points a hook disabled.
                        if (!WATCHED || hooks.is_none())
                            && let Some(old) = recyclable(
                                previous,
                                &mut cursor,
                                (c1.body, c2.body, key),
                                &relative,
                            )
                        {
                            seam.recycle(old, &relative, prediction, out);
                            continue;
                        }
                        let pos12 = pos12();
                        box_box_manifold(
                            *e1,
                            *e2,
                            pos12.rotation,
                            pos12.translation,
                            prediction,
                            &mut ours,
                        );
                        let pushed = out.len();
                        seam.push(ours.local_n1, &ours.points, out);
                        if let Some(manifold) = out.get_mut(pushed) {
                            manifold.basis = Some(ContactBasis {
                                rotation: relative.rotation,
                                translation: relative.position,
                                local_normal: rotate_inverse(b1.rotation(), manifold.normal),
                            });
                        }
                        continue;
                    }
                    _ => {
                        // What parry's dispatcher does for two convex shapes, in the scratch manifold.
                        let manifold = &mut self.convex;
                        forget_manifold_history(manifold);
                        let computed = DefaultQueryDispatcher.contact_manifold_convex_convex(
                            &pos12(),
                            shape1,
                            shape2,
                            None,
                            None,
                            prediction,
                            manifold,
                        );
                        if computed.is_ok() {
                            let key = fnv1a(key_base, &[manifold.subshape1, manifold.subshape2]);
                            seam(key).push(manifold.local_n1, &manifold.points, out);
                        }
                        continue;
                    }
                }
                seam(fnv1a(key_base, &CONVEX_SUBSHAPES)).push(ours.local_n1, &ours.points, out);
                continue;
            }
            let mut cache = cached.unwrap_or_default();
            cache.forget_history();
            let dispatched = DefaultQueryDispatcher.contact_manifolds(
                &pos12(),
                shape1,
                shape2,
                prediction,
                &mut cache.manifolds,
                &mut cache.workspace,
            );
            if dispatched.is_err() {
                // A shape pair parry has no algorithm for: no contacts, nothing to cache.
                continue;
            }
            for m in &cache.manifolds {
                let seam = Seam {
                    c1,
                    b1,
                    c2,
                    key: fnv1a(key_base, &[m.subshape1, m.subshape2]),
                    frames: (
                        shape_frame(c1, m.subshape_pos1()),
                        shape_frame(c2, m.subshape_pos2()),
                    ),
                };
                seam.push(m.local_n1, &m.points, out);
            }
            self.pairs.push(((h1, h2), cache));
        }
        if WATCHED {
            if let (Some(hooks), Some((pair, first))) = (hooks, hooked) {
                hooks::modify(hooks, &pair, out, first, failures);
            }
            if let Some((a, b, threshold, first)) = reporting {
                report_forces(
                    &mut self.force_pairs,
                    a,
                    b,
                    threshold,
                    &mut out.as_mut_slice()[first..],
                );
            }
        }
    }
}

/// The cache of `pair` from `old` (last step's cached pairs, sorted, from this one on), dropping those
/// before it: both lists are sorted. Always inlined: `old` is empty but for composite shapes, and the test
/// is made for every pair.
#[inline(always)]
fn take_cached<I: Iterator<Item = ((ColliderHandle, ColliderHandle), PairCache)>>(
    old: &mut core::iter::Peekable<I>,
    pair: (ColliderHandle, ColliderHandle),
) -> Option<PairCache> {
    while let Some((key, _)) = old.peek() {
        if *key >= pair {
            break;
        }
        old.next();
    }
    match old.peek() {
        Some((key, _)) if *key == pair => old.next().map(|(_, cache)| cache),
        _ => None,
    }
}

/// Collider 2's pose in collider 1's frame, composed with our scalar rotations, not parry's `Pose::inv_mul`
/// (see `rebound_math::rotate`). Always inlined: the pair loop computes it for nearly every pair, and its
/// four call sites (one per kind of generator) would otherwise make it a call.
#[inline(always)]
fn relative_pose(
    c1: &Collider,
    b1: &RigidBody,
    c2: &Collider,
    b2: &RigidBody,
) -> parry3d::math::Pose {
    to_parry_pose(
        c1.world_pose(b1.pose())
            .inverse()
            .mul_pose(&c2.world_pose(b2.pose())),
    )
}

/// The force event threshold (N) of a pair of colliders: the lower of theirs (`None` if neither sets one).
fn pair_threshold(c1: &Collider, c2: &Collider) -> Option<f32> {
    match (c1.desc.force_event_threshold, c2.desc.force_event_threshold) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Gives each of `manifolds` (one pair's, just made) the pair's force event `threshold` (N), and records
/// the collider pair (`a`, `b`) of each by key. The manifolds of a pair without a threshold keep `None`.
fn report_forces(
    pairs: &mut Vec<(u64, ColliderHandle, ColliderHandle)>,
    a: ColliderHandle,
    b: ColliderHandle,
    threshold: f32,
    manifolds: &mut [ContactManifold],
) {
    for m in manifolds {
        m.force_event_threshold = Some(threshold);
        pairs.push((m.key, a, b));
    }
}

/// FNV-1a over the two colliders' slot indices: the base of every manifold key of the pair.
///
/// Slots, not generations: generations start at a per-world base, and the key orders the manifolds of one
/// body pair (hence the solver's order), so two worlds built by the same calls must get the same keys. Two
/// live colliders never share a slot, so keys stay unique within a step.
fn pair_key(h1: ColliderHandle, h2: ColliderHandle) -> u64 {
    let (i1, _) = h1.into_raw_parts();
    let (i2, _) = h2.into_raw_parts();
    fnv1a(0xcbf2_9ce4_8422_2325, &[i1, i2])
}

fn fnv1a(mut hash: u64, words: &[u32]) -> u64 {
    for word in words {
        for byte in word.to_le_bytes() {
            hash ^= u64::from(byte);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    hash
}

/// The frame of a (sub-)shape in its body's frame: the collider's local pose, then the sub-shape's pose in
/// the collider's shape (compounds).
fn shape_frame(collider: &Collider, subshape_pose: Option<&parry3d::math::Pose>) -> Pose {
    match subshape_pose {
        Some(sub) => collider.desc.local_pose.mul_pose(&from_parry_pose(sub)),
        None => collider.desc.local_pose,
    }
}
