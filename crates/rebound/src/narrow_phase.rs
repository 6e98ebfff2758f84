//! The narrow phase (second half of the collide stage): the contact manifold of each candidate pair — our
//! own generators for two balls and two boxes ([`crate::box_box`], into a stack [`ShapeManifold`]), parry3d's
//! persistent manifolds for everything else — turned into the world's plain-data [`ContactManifold`] at one
//! seam, [`Seam`]; box pairs that barely moved recycle last step's (see "Contact recycling").
//!
//! # Pair cache
//!
//! A candidate pair with a composite shape (mesh, height field, compound) keeps its parry manifolds and its
//! [`ContactManifoldsWorkspace`] (the sub-shape bookkeeping) in an ordered map keyed by the ordered collider
//! pair (a vector sorted by key, merged with the step's sorted candidate list in one pass), so iteration is in
//! handle order and pairs that stop being candidates are dropped. A pair of two convex shapes keeps nothing:
//! it is computed in one scratch manifold shared by all such pairs (see [`NarrowPhase`]).
//!
//! The prediction distance of a pair — how far apart its colliders may be for parry to report points — is
//! the speculative margin plus what the pair can close in the step: `(|v₁ − v₂| + |ω₁|·r₁ + |ω₂|·r₂)·dt`,
//! with `r` bounding each collider's reach from its body's centre of mass (computed by the broad phase).
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
//! # Contact recycling
//!
//! The coherence shortcut is taken from the world's state instead of parry's: a box pair's manifold records
//! where it was computed ([`ContactBasis`]: the bodies' relative pose and the normal in A's frame), and while
//! the bodies have moved less than 1 mm and turned less than 0.5° relative to that, the pair keeps last step's
//! points as material points of each body and only measures their separations again ([`recyclable`],
//! `Seam::recycle`). The basis is in the world's manifolds, hence in every snapshot: recycling depends on the
//! world's state only. Box pairs only — they are what stacks are made of, and their generator is the most
//! expensive. In the SCENES.md pyramid this skips most box tests (−20 % instructions per step) and a column of
//! equal boxes stands straighter than with fresh manifolds (a kept patch does not switch reference face on
//! rounding-level ties; `docs/performance.md`, "Contact recycling").
//!
//! # The seam
//!
//! parry's points are in each shape's (or sub-shape's) local frame; the world wants them in each body's
//! frame relative to the body origin, with the normal in world space from A to B, at most
//! [`MAX_MANIFOLD_POINTS`] points, a 32-bit feature id per point and a 64-bit key that is stable for a
//! collider pair and sub-shape pair.

use crate::box_box::{ShapeManifold, ShapePoint, box_box_manifold};
use crate::broad_phase::BroadPhase;
use crate::shape::{from_parry_pose, to_parry_pose};
use crate::{Collider, ColliderHandle, ColliderSet, ColliderShape};
use parry3d::query::{
    ContactManifold as ParryManifold, ContactManifoldsWorkspace, DefaultQueryDispatcher,
    PersistentQueryDispatcher, TrackedContact,
};
use parry3d::shape::PackedFeatureId;
use rebound_dynamics::{CombineRule, RigidBody};
use rebound_math::{Pose, Vec3, rotate, rotate_inverse};
use rebound_world::{
    BodyHandle, BodySet, ContactBasis, ContactManifold, MAX_MANIFOLD_POINTS, ManifoldPoint,
};

/// The largest prediction distance (m); see the broad phase's margin cap.
const MAX_PREDICTION: f32 = 1.0e7;

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
/// holds, which stays in cache — a per-pair manifold on the heap cost a cache miss per pair (8 % of the
/// balls scene's step).
#[derive(Clone, Default)]
pub(crate) struct NarrowPhase {
    pairs: Vec<((ColliderHandle, ColliderHandle), PairCache)>,
    /// Last step's pair list while this step's is built (empty between steps, capacity kept), so that the
    /// step allocates no new list.
    previous: Vec<((ColliderHandle, ColliderHandle), PairCache)>,
    /// The scratch manifold of convex pairs parry generates.
    convex: ParryManifold<(), ()>,
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

    /// Stage *collide*, part 2: the manifolds of every candidate pair (in pair order) into `out`.
    pub(crate) fn collide(
        &mut self,
        broad_phase: &BroadPhase,
        colliders: &ColliderSet,
        bodies: &BodySet,
        speculative_margin: f32,
        dt: f32,
        previous: &[ContactManifold],
        out: &mut Vec<ContactManifold>,
    ) {
        core::mem::swap(&mut self.pairs, &mut self.previous);
        self.pairs.clear();
        let mut old = self.previous.drain(..).peekable();
        let mut cursor = 0;
        for &(h1, h2) in &broad_phase.pairs {
            // Both lists are sorted: drop the old pairs before this one, reuse this one's cache if present.
            while old.next_if(|(key, _)| *key < (h1, h2)).is_some() {}
            let cached = old
                .next_if(|(key, _)| *key == (h1, h2))
                .map(|(_, cache)| cache);
            let (Some(c1), Some(c2)) = (colliders.get(h1), colliders.get(h2)) else {
                continue;
            };
            let (Some(b1), Some(b2)) = (bodies.get(c1.body), bodies.get(c2.body)) else {
                continue;
            };
            // Two balls farther apart than this were dropped by the broad phase, with the same test on the
            // same values (`centres_clearly_apart`).
            let prediction = prediction_distance(
                (b1.linear_velocity(), b2.linear_velocity()),
                (
                    broad_phase.rotation_reach(h1),
                    broad_phase.rotation_reach(h2),
                ),
                speculative_margin,
                dt,
            );
            // Composed with our scalar rotations, not parry's `Pose::inv_mul` (see `rebound_math::rotate`); only
            // where a generator runs (a recycled box pair needs none).
            let pos12 = || {
                to_parry_pose(
                    c1.world_pose(b1.pose())
                        .inverse()
                        .mul_pose(&c2.world_pose(b2.pose())),
                )
            };
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
                        if let Some(old) =
                            recyclable(previous, &mut cursor, (c1.body, c2.body, key), &relative)
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

/// Packs parry's two feature ids (2-bit kind + 30-bit index each) into one `u32`: the first rotated by 16
/// bits, xor the second. Exact (no two feature pairs collide) while both indices are below 2¹⁴ = 16384,
/// which covers every primitive and, per sub-shape manifold, every triangle; beyond that ids may collide,
/// which only costs a warm start.
fn pack_feature_id(fid1: PackedFeatureId, fid2: PackedFeatureId) -> u32 {
    fid1.0.rotate_left(16) ^ fid2.0
}

/// The frame of a (sub-)shape in its body's frame: the collider's local pose, then the sub-shape's pose in
/// the collider's shape (compounds).
fn shape_frame(collider: &Collider, subshape_pose: Option<&parry3d::math::Pose>) -> Pose {
    match subshape_pose {
        Some(sub) => collider.desc.local_pose.mul_pose(&from_parry_pose(sub)),
        None => collider.desc.local_pose,
    }
}

/// A contact point as a generator leaves it, in its shapes' own frames: parry's [`TrackedContact`] or our
/// [`ShapePoint`], read as a [`ShapePoint`].
pub(crate) trait SeamPoint {
    /// The point's geometry and features.
    fn shape_point(&self) -> ShapePoint;
}

impl SeamPoint for TrackedContact<()> {
    fn shape_point(&self) -> ShapePoint {
        ShapePoint {
            local_p1: self.local_p1,
            local_p2: self.local_p2,
            fid1: self.fid1,
            fid2: self.fid2,
            dist: self.dist,
        }
    }
}

impl SeamPoint for ShapePoint {
    fn shape_point(&self) -> ShapePoint {
        *self
    }
}

/// Whether a point is finite (defensive: the generators' points always are).
fn is_usable(point: &impl SeamPoint) -> bool {
    let p = point.shape_point();
    p.local_p1.is_finite() && p.local_p2.is_finite() && p.dist.is_finite()
}

/// **The seam**: where one manifold of the collider pair (`c1`, `c2`), from parry or from our generators,
/// becomes the world's [`ContactManifold`].
///
/// - body A is `c1`'s body, body B is `c2`'s; the normal is the generator's `local_n1` (outward from shape 1,
///   towards shape 2) rotated into world space;
/// - anchors: `local_p1`/`local_p2` (in each shape's or sub-shape's frame) through `frames` (the sub-shape
///   pose, then the collider's local pose) into each body's frame, relative to the body origin;
/// - separation: the signed `dist` (negative when overlapping, positive for speculative points);
/// - feature ids: `fid1`/`fid2` packed into a `u32` ([`pack_feature_id`]);
/// - key: the collider pair's hash extended with the sub-shape ids, stable from step to step;
/// - material: friction, restitution and rolling friction combined with each collider's rules;
/// - more than [`MAX_MANIFOLD_POINTS`] points are reduced to the 4 that keep the deepest point and the
///   largest contact area ([`reduce_points`]).
pub(crate) struct Seam<'a> {
    /// Shape 1's collider (on body A).
    pub(crate) c1: &'a Collider,
    /// Body A.
    pub(crate) b1: &'a RigidBody,
    /// Shape 2's collider (on body B).
    pub(crate) c2: &'a Collider,
    /// The manifold's key.
    pub(crate) key: u64,
    /// Each shape's frame in its body's frame.
    pub(crate) frames: (Pose, Pose),
}

impl Seam<'_> {
    /// Pushes the manifold of normal `local_n1` and `points` onto `out`; nothing for a manifold without
    /// points (or, defensively, without a usable normal or finite points). The manifold is written in place.
    pub(crate) fn push<P: SeamPoint>(
        &self,
        local_n1: Vec3,
        points: &[P],
        out: &mut Vec<ContactManifold>,
    ) {
        // Most candidate pairs of a pile are within the margin but not touching: nothing to convert.
        if points.is_empty() {
            return;
        }
        let (c1, c2) = (self.c1, self.c2);
        let (frame1, frame2) = self.frames;
        let Some(normal) =
            rotate(self.b1.rotation(), frame1.transform_vector(local_n1)).try_normalize()
        else {
            return;
        };
        let (chosen, count) = reduce_points(points);
        if count == 0 {
            return;
        }
        let (friction, restitution, rolling_friction) = self.materials();
        out.push(ContactManifold::new(
            c1.body,
            c2.body,
            self.key,
            normal,
            friction,
            restitution,
        ));
        let Some(manifold) = out.last_mut() else {
            return;
        };
        manifold.rolling_friction = rolling_friction;
        // A shape at its body's origin (the common case) needs no transform.
        let to_body = |frame: &Pose, p: Vec3| {
            if *frame == Pose::IDENTITY {
                p
            } else {
                frame.transform_point(p)
            }
        };
        for point in chosen[..count].iter().map(|&i| points[i].shape_point()) {
            manifold.push_point(ManifoldPoint {
                local_anchor_a: to_body(&frame1, point.local_p1),
                local_anchor_b: to_body(&frame2, point.local_p2),
                separation: point.dist,
                feature_id: pack_feature_id(point.fid1, point.fid2),
                ..ManifoldPoint::default()
            });
        }
    }
}

/// How far (m) the bodies of a box pair may move relative to each other, since the pair's manifold was
/// computed from scratch, for the manifold to be recycled: 1 mm. See [`recyclable`].
const RECYCLE_DISTANCE: f32 = 1.0e-3;

/// How far the bodies of a box pair may turn relative to each other (the sine of half the angle): half a
/// degree's worth, `sin(0.25°)`, i.e. 0.5°. See [`recyclable`].
const RECYCLE_HALF_ANGLE_SINE: f32 = 4.363_3e-3;

/// Last step's manifold of the body pair and key `order_key` in `previous` (sorted by order key), if it may be
/// recycled at the bodies' relative pose `relative` (B's body pose in A's body frame): it has a
/// [`ContactBasis`], and the bodies moved less than [`RECYCLE_DISTANCE`] and turned less than
/// [`RECYCLE_HALF_ANGLE_SINE`] relative to each other since it was computed from scratch.
///
/// **Contact recycling** (rapier's: parry's `try_update_contacts`): a box resting on a box changes its contact
/// patch only when it moves, so its points are kept — as material points of each body — and only their
/// separations are measured again, until the bodies have moved far enough from where the points were computed
/// for the patch to differ. The basis is in the world's manifold, so the choice depends on the world's state
/// only and a restored snapshot recycles exactly as the world that never stopped.
///
/// `cursor` is where the last search ended: pairs come in nearly the order of `previous`, so the search
/// gallops forward from it ([`find_from`]) instead of bisecting all of `previous` for every pair.
fn recyclable<'a>(
    previous: &'a [ContactManifold],
    cursor: &mut usize,
    order_key: (BodyHandle, BodyHandle, u64),
    relative: &Pose,
) -> Option<&'a ContactManifold> {
    let old = previous.get(find_from(previous, cursor, order_key)?)?;
    let basis = old.basis?;
    let moved = relative.position.distance_squared(basis.translation);
    let turn = (basis.rotation.conjugate() * relative.rotation)
        .xyz()
        .length_squared();
    (moved < RECYCLE_DISTANCE * RECYCLE_DISTANCE
        && turn < RECYCLE_HALF_ANGLE_SINE * RECYCLE_HALF_ANGLE_SINE)
        .then_some(old)
}

/// The index of the manifold of `order_key` in `previous` (sorted by order key), searched from `*cursor`:
/// forward in steps of 1, 2, 4, … until passed, then by bisection within the last step; from the start if
/// the key lies before the cursor. `*cursor` is left where the key is or would be. The same answer as one
/// bisection of the whole slice, found in O(log d) reads for a key `d` places past the cursor — a pile's pairs
/// come in nearly manifold order, so `d` is small and the reads stay in cache.
fn find_from(
    previous: &[ContactManifold],
    cursor: &mut usize,
    order_key: (BodyHandle, BodyHandle, u64),
) -> Option<usize> {
    let start = (*cursor).min(previous.len());
    let ahead = previous
        .get(start)
        .is_some_and(|m| m.order_key() < order_key);
    let found = if ahead {
        // previous[start] < key: gallop until an element ≥ key (or the end), then bisect the bracket.
        let mut low = start + 1;
        let mut step = 1;
        while previous
            .get(low + step - 1)
            .is_some_and(|m| m.order_key() < order_key)
        {
            low += step;
            step *= 2;
        }
        let high = (low + step).min(previous.len());
        previous[low..high]
            .binary_search_by_key(&order_key, ContactManifold::order_key)
            .map(|i| low + i)
            .map_err(|i| low + i)
    } else if previous
        .get(start)
        .is_some_and(|m| m.order_key() == order_key)
    {
        Ok(start)
    } else if start == 0 || previous[start - 1].order_key() < order_key {
        // Between the cursor's neighbours: absent.
        Err(start)
    } else {
        previous[..start].binary_search_by_key(&order_key, ContactManifold::order_key)
    };
    match found {
        Ok(index) => {
            *cursor = index + 1;
            Some(index)
        }
        Err(index) => {
            *cursor = index;
            None
        }
    }
}

impl Seam<'_> {
    /// Pushes `old` (last step's manifold of this pair, see [`recyclable`]) recycled onto `out`: its points as
    /// material points of each body, each with its separation along the kept normal measured at the bodies'
    /// relative pose `relative` — `s = n·(T·p_B − p_A)` in A's body frame — those within `prediction`
    /// (m) kept; the normal turned with A; the basis kept; materials combined afresh (they may have changed).
    /// Nothing if no point is within `prediction`.
    fn recycle(
        &self,
        old: &ContactManifold,
        relative: &Pose,
        prediction: f32,
        out: &mut Vec<ContactManifold>,
    ) {
        let Some(basis) = old.basis else {
            return;
        };
        let n = basis.local_normal;
        // Written in place in `out` (a manifold is 432 bytes: built on the stack, its push was a memcpy).
        out.push(ContactManifold::new(
            old.body_a,
            old.body_b,
            old.key,
            rotate(self.b1.rotation(), n),
            0.0,
            0.0,
        ));
        let Some(manifold) = out.last_mut() else {
            return;
        };
        (
            manifold.friction,
            manifold.restitution,
            manifold.rolling_friction,
        ) = self.materials();
        manifold.basis = Some(basis);
        // s = n·(R·p_B + t − p_A) = (R*·n)·p_B + n·t − n·p_A: one rotation per manifold, two dot products
        // per point.
        let normal_in_b = rotate_inverse(relative.rotation, n);
        let offset = n.dot(relative.position);
        for p in old.points() {
            let separation = normal_in_b.dot(p.local_anchor_b) + offset - n.dot(p.local_anchor_a);
            if separation <= prediction {
                manifold.push_point(ManifoldPoint {
                    local_anchor_a: p.local_anchor_a,
                    local_anchor_b: p.local_anchor_b,
                    separation,
                    feature_id: p.feature_id,
                    ..ManifoldPoint::default()
                });
            }
        }
        if manifold.point_count == 0 {
            out.pop();
        }
    }

    /// The pair's friction, restitution and rolling friction, each combined with the colliders' rules.
    fn materials(&self) -> (f32, f32, f32) {
        let (d1, d2) = (&self.c1.desc, &self.c2.desc);
        (
            CombineRule::combine(
                d1.friction,
                d1.friction_combine_rule,
                d2.friction,
                d2.friction_combine_rule,
            ),
            CombineRule::combine(
                d1.restitution,
                d1.restitution_combine_rule,
                d2.restitution,
                d2.restitution_combine_rule,
            ),
            CombineRule::combine(
                d1.rolling_friction,
                d1.friction_combine_rule,
                d2.rolling_friction,
                d2.friction_combine_rule,
            ),
        )
    }
}

/// How much farther apart (m) than the prediction distance two balls' surfaces must be, measured in world
/// space, for [`centres_clearly_apart`] to skip the pair: far more than the rounding that separates the
/// world-space distance from the one `ball_ball` measures in ball 1's frame, so the skip never drops a
/// contact `ball_ball` would report.
const BALL_SKIP_MARGIN: f32 = 1.0e-3;

/// Whether two balls of world centres `center1`, `center2` and radii `r1`, `r2` (m) are farther apart than
/// `prediction` plus [`BALL_SKIP_MARGIN`]: their centres' world distance, without composing the poses that
/// [`ball_ball`] needs. Most overlapping boxes of a pile of balls hold balls this far apart; the broad phase
/// drops them before they become candidates.
#[inline]
pub(crate) fn centres_clearly_apart(
    (center1, r1): (Vec3, f32),
    (center2, r2): (Vec3, f32),
    prediction: f32,
) -> bool {
    let reach = r1 + r2 + prediction + BALL_SKIP_MARGIN;
    center1.distance_squared(center2) > reach * reach
}

/// The world position of the centre of ball collider `c` on body `b`: the body's origin for a ball at it (the
/// common case: no rotation to apply), else the collider's offset carried by the body's pose.
#[inline]
pub(crate) fn ball_center(c: &Collider, b: &RigidBody) -> Vec3 {
    ball_center_at(c, b.pose())
}

/// [`ball_center`] for a body at `body_pose`.
#[inline]
pub(crate) fn ball_center_at(c: &Collider, body_pose: Pose) -> Vec3 {
    let offset = c.desc.local_pose.position;
    if offset == Vec3::ZERO {
        body_pose.position
    } else {
        body_pose.transform_point(offset)
    }
}

/// How far apart (m) two colliders on bodies of linear velocities `v1` and `v2` (m/s) may be and still get a
/// (speculative) contact this step: the speculative margin plus how far they can close within `dt` — their
/// relative speed and each one's rotation reach `|ω|·r` (m/s, [`BroadPhase::rotation_reach`]).
#[inline]
pub(crate) fn prediction_distance(
    (v1, v2): (Vec3, Vec3),
    (reach1, reach2): (f32, f32),
    speculative_margin: f32,
    dt: f32,
) -> f32 {
    let closing = (v1 - v2).length() + reach1 + reach2;
    (speculative_margin + closing * dt).min(MAX_PREDICTION)
}

/// The contact of two balls of radii `r1` and `r2` (m), ball 2 at `pos12` in ball 1's frame, for gaps up to
/// `prediction` (m): one point on each ball along the line of centres (the normal is +y for coincident
/// centres). The formulas of parry's `contact_manifold_ball_ball`, into a [`ShapeManifold`].
fn ball_ball(
    pos12: &parry3d::math::Pose,
    r1: f32,
    r2: f32,
    prediction: f32,
    out: &mut ShapeManifold,
) {
    out.points.clear();
    let center = pos12.translation;
    let center_distance = center.length();
    let dist = center_distance - r1 - r2;
    // Written as parry's `dist < prediction`, so that a NaN distance is no contact.
    let within = dist < prediction;
    if !within {
        return;
    }
    let local_n1 = if center_distance != 0.0 {
        center / center_distance
    } else {
        Vec3::Y
    };
    let local_n2 = rotate_inverse(pos12.rotation, -local_n1);
    out.local_n1 = local_n1;
    out.local_n2 = local_n2;
    let face = PackedFeatureId::face(0);
    out.points.push(ShapePoint {
        local_p1: local_n1 * r1,
        local_p2: local_n2 * r2,
        fid1: face,
        fid2: face,
        dist,
    });
}

/// Indices (and their count) of at most [`MAX_MANIFOLD_POINTS`] usable points that keep the contact patch:
/// all of them if they fit; otherwise the deepest point, the point farthest from it, the point farthest from
/// their line, then the point adding the most area to that triangle (Box2D's and Jolt's manifold reduction).
/// Ties go to the lower index, so the choice is deterministic. Points are compared in shape 1's frame. No
/// allocation.
fn reduce_points<P: SeamPoint>(points: &[P]) -> ([usize; MAX_MANIFOLD_POINTS], usize) {
    let mut chosen = [0; MAX_MANIFOLD_POINTS];
    let mut count = 0;
    let usable_count = points.iter().filter(|p| is_usable(*p)).count();
    if usable_count <= MAX_MANIFOLD_POINTS {
        for (i, _) in points.iter().enumerate().filter(|(_, p)| is_usable(*p)) {
            chosen[count] = i;
            count += 1;
        }
        return (chosen, count);
    }
    let p = |i: usize| points[i].shape_point().local_p1;
    // The usable, not yet chosen point with the highest score (the first one on ties).
    let argmax = |score: &dyn Fn(usize) -> f32, taken: &[usize]| {
        (0..points.len())
            .filter(|&i| is_usable(&points[i]) && !taken.contains(&i))
            .fold(None, |best: Option<(usize, f32)>, i| {
                let s = score(i);
                match best {
                    Some((_, b)) if s <= b => best,
                    _ => Some((i, s)),
                }
            })
            .map(|(i, _)| i)
    };
    let Some(deepest) = argmax(&|i| -points[i].shape_point().dist, &[]) else {
        return (chosen, 0);
    };
    chosen[0] = deepest;
    count = 1;
    let a = p(deepest);
    let Some(second) = argmax(&|i| p(i).distance_squared(a), &chosen[..count]) else {
        return (chosen, count);
    };
    chosen[1] = second;
    count = 2;
    let b = p(second);
    let Some(third) = argmax(
        &|i| (b - a).cross(p(i) - a).length_squared(),
        &chosen[..count],
    ) else {
        return (chosen, count);
    };
    chosen[2] = third;
    count = 3;
    let c = p(third);
    // Area a point adds outside the triangle: the sum of the three sub-triangle areas minus the triangle's
    // own (0 inside).
    let triangle = (b - a).cross(c - a).length();
    let added = |i: usize| {
        let q = p(i);
        (a - q).cross(b - q).length()
            + (b - q).cross(c - q).length()
            + (c - q).cross(a - q).length()
            - triangle
    };
    if let Some(fourth) = argmax(&added, &chosen[..count]) {
        chosen[3] = fourth;
        count = 4;
    }
    (chosen, count)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contact(x: f32, z: f32, dist: f32) -> TrackedContact<()> {
        TrackedContact::new(
            Vec3::new(x, 0.0, z),
            Vec3::new(x, 0.0, z),
            PackedFeatureId::UNKNOWN,
            PackedFeatureId::UNKNOWN,
            dist,
        )
    }

    proptest::proptest! {
        /// The galloping search finds what one bisection of the whole slice finds, from any cursor, and leaves
        /// the cursor just past a found key or at an absent key's insertion point.
        #[test]
        fn galloping_search_matches_bisection(
            keys in proptest::collection::btree_set((0u32..40, 0u32..40, 0u64..3), 0..60),
            probes in proptest::collection::vec(((0u32..42, 0u32..42, 0u64..4), 0usize..70), 1..20),
        ) {
            let previous: Vec<ContactManifold> = keys
                .iter()
                .map(|&(a, b, key)| {
                    ContactManifold::new(
                        BodyHandle::from_raw_parts(a, 0),
                        BodyHandle::from_raw_parts(b, 0),
                        key,
                        Vec3::Y,
                        0.5,
                        0.0,
                    )
                })
                .collect();
            for ((a, b, key), mut cursor) in probes {
                let order_key = (BodyHandle::from_raw_parts(a, 0), BodyHandle::from_raw_parts(b, 0), key);
                let bisected = previous.binary_search_by_key(&order_key, ContactManifold::order_key);
                let found = find_from(&previous, &mut cursor, order_key);
                proptest::prop_assert_eq!(found, bisected.ok());
                proptest::prop_assert_eq!(cursor, bisected.map_or_else(|i| i, |i| i + 1));
            }
        }
    }

    #[test]
    fn reduction_keeps_the_deepest_point_and_the_corners() {
        // A square's corners, its centre (deepest) and edge midpoints.
        let points = [
            contact(0.0, 0.0, -0.02),
            contact(-1.0, -1.0, -0.01),
            contact(1.0, -1.0, -0.01),
            contact(1.0, 1.0, -0.01),
            contact(-1.0, 1.0, -0.01),
            contact(0.0, 1.0, -0.01),
        ];
        let (chosen, count) = reduce_points(&points);
        assert_eq!(count, 4);
        assert_eq!(chosen[0], 0, "the deepest point comes first");
        // Then a corner, the opposite corner, and one of the remaining corners.
        assert!(
            chosen[1..].iter().all(|&i| (1..=4).contains(&i)),
            "{chosen:?}"
        );
    }

    #[test]
    fn feature_ids_pack_without_collisions_for_small_indices() {
        let mut seen = std::collections::BTreeSet::new();
        for f1 in [
            PackedFeatureId::vertex(3),
            PackedFeatureId::edge(3),
            PackedFeatureId::face(3),
            PackedFeatureId::face(16383),
        ] {
            for f2 in [
                PackedFeatureId::vertex(3),
                PackedFeatureId::edge(5),
                PackedFeatureId::face(3),
                PackedFeatureId::vertex(16383),
            ] {
                let point = TrackedContact::<()>::new(Vec3::ZERO, Vec3::ZERO, f1, f2, 0.0);
                assert!(seen.insert(pack_feature_id(point.fid1, point.fid2)));
            }
        }
    }
}
