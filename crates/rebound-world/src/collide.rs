//! Stage *collide*, second in the step (after the kinematic targets): the backend's manifolds for the
//! current poses, sorted by order key and validated, each matched with last step's manifold of the same key
//! for warm starting (impulses and lever arms, point by point by feature id), with the approach speed the
//! events and the waking test need and the solver contact it gives.

mod pool;

use crate::body_set::BodySet;
use crate::handles::BodyHandle;
use crate::manifold::{
    CollisionBackend, ContactManifold, MAX_MANIFOLD_POINTS, ManifoldPoint, ManifoldWriter,
};
use crate::sorted_walk::walk_to;
use crate::state::WorldState;
use rebound_dynamics::{BodyType, RigidBody};
use rebound_math::par;
use rebound_math::{Mat3, Vec3};

/// This step's manifolds and what the stages after *collide* learn about each, reused from step to step.
#[derive(Debug, Default)]
pub(crate) struct Collision {
    /// The backend's manifolds of this step, validated and warm-started, sorted by order key. After the
    /// *store* stage (which swaps them with the world's), last step's.
    pub(crate) manifolds: Vec<ContactManifold>,
    /// For each manifold of this step, the approach speed of its bodies before the step (m/s, ≥ 0; 0 where
    /// neither the events nor waking need it): the contact events' speed and the waking test.
    pub(crate) approach_speeds: Vec<f32>,
    /// For each manifold of this step, whether the solver pushed with it (written by *store*): a contact that
    /// touched during the step, even one that bounced off and ended with no accumulated impulse.
    pub(crate) pushed: Vec<bool>,
    /// Body slot → the rotation matrix of the body's orientation and the collide call that computed it
    /// (`collide_calls`): each body's matrix is computed once per collide stage, at its first manifold.
    rotations: Vec<(u64, Mat3)>,
    /// How many collide stages ran (so that a matrix of an earlier one is never read as current).
    collide_calls: u64,
    /// The pool's walk's scratch (on a pool of several threads only).
    chunks: pool::Chunks,
}

/// The backend's manifolds for the current poses into `c.manifolds`, sorted, validated and warm-started
/// (impulses, and the lever arms each point's solver contact will use), with their approach speeds
/// (`c.approach_speeds`); manifolds with a quarantined body are dropped, and those past the cap on contact
/// points. Returns how many were dropped, by cause.
pub(crate) fn collide<B: CollisionBackend>(
    backend: &mut B,
    state: &WorldState,
    dt: f32,
    c: &mut Collision,
) -> Dropped {
    // Written over the list of two steps ago in place: each manifold writes only the slots it uses.
    let mut manifolds = core::mem::take(&mut c.manifolds);
    backend.collide(
        &state.bodies,
        &state.settings,
        dt,
        &state.manifolds,
        &mut ManifoldWriter::new(&mut manifolds),
    );
    let bodies = &state.bodies;
    // Unstable sort: no buffer to allocate, and the result does not depend on the input order because a
    // backend's keys are unique per body pair (equal keys — a faulty backend — still sort the same way
    // for the same input: the sort is deterministic). The key reads no number, so the manifolds the walk
    // below rejects (`is_usable`) sort like the others.
    // A backend that writes its manifolds in order (the facade's, for one collider per body) leaves
    // nothing to sort, on one thread or many alike (on the pool the order is checked chunk by chunk), so
    // equal keys keep the backend's order on both paths.
    let on_pool = par::is_parallel() && manifolds.len() > pool::MANIFOLDS_PER_CHUNK;
    let in_order = if on_pool {
        pool::is_sorted_on_pool(&mut manifolds, &mut c.chunks)
    } else {
        manifolds.is_sorted_by_key(ContactManifold::order_key)
    };
    if !in_order {
        manifolds.sort_unstable_by_key(ContactManifold::order_key);
    }
    // Contacts survive sleep: a pair of which neither body moves and one sleeps is not collided again (the
    // backend tests only pairs with a moving body), so last step's manifold carries over unchanged. The
    // pair stays in `contacts()` and touching, and its impulses warm-start the contact when a body wakes.
    let carried = !state.islands.is_empty() && carry_resting(state, &mut manifolds);

    // Warm start: copy impulses from last step's manifold with the same key, point by point by feature id;
    // a persisting point also keeps its lever arms (see `LEVER_ARM_TOLERANCE`). Both lists are sorted by
    // key, so one forward walk through last step's finds every match (`walk_to`).
    //
    // The same walk finds the manifolds whose approach speed (m/s, before the step) is needed: those of a
    // contact that may begin this step (no touching manifold last step: the speed goes in the event) and
    // those with a sleeping body (waking). The others get 0: nothing reads them, and a speed costs a pose
    // transform and two velocity evaluations per point.
    //
    // The walk also validates (one pass over the manifolds, and the bodies looked up once): an unusable
    // manifold is dropped, the kept ones move down over it in order.
    let mut speeds = core::mem::take(&mut c.approach_speeds);
    speeds.clear();
    // Whether each manifold counts as pushed before the solver runs (stage *store* adds the solver's
    // pushes): a carried manifold keeps the touching state its pair had last step. Without carried
    // manifolds none is, and the list stays empty (*store* fills it).
    let mut pushed = core::mem::take(&mut c.pushed);
    pushed.clear();
    let mut rotations = core::mem::take(&mut c.rotations);
    rotations.resize(bodies.slot_count(), (0, Mat3::IDENTITY));
    c.collide_calls += 1;
    let call = c.collide_calls;
    // A body's rotation matrix, computed at its first manifold of the stage: a point's lever arm is then
    // one matrix product, `R·(p_local − c_local)`, not two quaternion rotations (of the point and of the
    // centre of mass).
    let mut rotation_of = |handle: BodyHandle, body: &RigidBody| {
        let entry = &mut rotations[BodySet::slot(handle)];
        if entry.0 != call {
            *entry = (call, Mat3::from_quat(body.rotation()));
        }
        entry.1
    };
    let mut previous = state.manifolds.iter().peekable();
    let mut kept = 0;
    let mut counts = Dropped::default();
    let (mut points, max_points) = (0, state.settings.limits.max_contact_points as usize);
    // On a pool of several threads the walk runs chunk by chunk over the pool (`pool::walk_on_pool`).
    if par::is_parallel() && manifolds.len() > pool::MANIFOLDS_PER_CHUNK {
        kept = pool::walk_on_pool(
            state,
            &mut manifolds,
            &mut speeds,
            &mut pushed,
            carried,
            &mut c.chunks,
            &mut counts,
        );
    } else {
        // One pass over the manifolds on one thread.
        for index in 0..manifolds.len() {
            let (body_a, body_b) = (manifolds[index].body_a, manifolds[index].body_b);
            let (Some(entry_a), Some(entry_b)) = (bodies.entry(body_a), bodies.entry(body_b))
            else {
                continue;
            };
            // A quarantined body is in no step (a backend may not know it); not a fault of the backend.
            if entry_a.quarantined || entry_b.quarantined {
                counts.quarantined += 1;
                continue;
            }
            if !is_usable(&manifolds[index]) {
                continue;
            }
            // The cap on contact points: whole manifolds, in order, until the next would exceed it.
            let point_count = manifolds[index].point_count;
            if counts.capped > 0 || points + point_count > max_points {
                counts.capped += 1;
                continue;
            }
            points += point_count;
            let (body_a, body_b) = (&entry_a.body, &entry_b.body);
            if kept != index {
                manifolds.swap(kept, index);
            }
            let manifold = &mut manifolds[kept];
            kept += 1;
            let key = manifold.order_key();
            let old = walk_to(&mut previous, &key, ContactManifold::order_key);
            let may_begin = old.is_none_or(|o| !o.is_touching());
            let needs_speed = may_begin || body_a.is_sleeping() || body_b.is_sleeping();
            speeds.push(if needs_speed {
                approach_speed(manifold, body_a, body_b)
            } else {
                0.0
            });
            if carried {
                pushed.push(
                    !moves(body_a)
                        && !moves(body_b)
                        && state
                            .touching
                            .binary_search(&ordered(manifold.body_a, manifold.body_b))
                            .is_ok(),
                );
            }
            let rotations = [
                rotation_of(manifold.body_a, body_a),
                rotation_of(manifold.body_b, body_b),
            ];
            warm_start_points(manifold, (body_a, body_b), old, &rotations);
        }
    }
    counts.rejected = manifolds.len() - kept - counts.quarantined - counts.capped;
    manifolds.truncate(kept);
    c.rotations = rotations;
    c.approach_speeds = speeds;
    c.pushed = pushed;
    c.manifolds = manifolds;
    counts
}

/// Each point's lever arms, kept from last step's manifold `old` where its point persists (with its
/// impulses: the warm start), else fresh from the bodies' rotation matrices and centres of mass.
#[inline(always)]
fn warm_start_points(
    manifold: &mut ContactManifold,
    (body_a, body_b): (&RigidBody, &RigidBody),
    old: Option<&ContactManifold>,
    rotations: &[Mat3; 2],
) {
    let count = manifold.point_count.min(MAX_MANIFOLD_POINTS);
    let old_points = old.map_or(&[][..], ContactManifold::points);
    let centers = [
        body_a.mass_properties().local_center_of_mass(),
        body_b.mass_properties().local_center_of_mass(),
    ];
    for point in &mut manifold.points[..count] {
        let fresh = [
            rotations[0] * (point.local_anchor_a - centers[0]),
            rotations[1] * (point.local_anchor_b - centers[1]),
        ];
        if let Some(previous) = point.refresh_lever_arms(fresh, old_points) {
            point.normal_impulse = previous.normal_impulse;
            point.tangent_impulse = previous.tangent_impulse;
        }
    }
}

/// The backend's manifolds *collide* left out, by cause.
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct Dropped {
    /// Unusable: a stale handle, a body against itself, a non-finite or non-unit normal, a non-finite point.
    pub(crate) rejected: usize,
    /// With a quarantined body.
    pub(crate) quarantined: usize,
    /// Beyond the cap on contact points ([`crate::StepLimits::max_contact_points`]).
    pub(crate) capped: usize,
}

impl Collision {
    /// Drops this step's manifolds with a body quarantined after the solver passes (and their approach
    /// speeds and touching verdicts), before the passes run again.
    pub(crate) fn drop_quarantined(&mut self, bodies: &BodySet) {
        let mut kept = 0;
        for index in 0..self.manifolds.len() {
            let m = &self.manifolds[index];
            if bodies.is_quarantined(m.body_a) || bodies.is_quarantined(m.body_b) {
                continue;
            }
            self.manifolds.swap(kept, index);
            self.approach_speeds.swap(kept, index);
            if !self.pushed.is_empty() {
                self.pushed.swap(kept, index);
            }
            kept += 1;
        }
        self.manifolds.truncate(kept);
        self.approach_speeds.truncate(kept);
        self.pushed.truncate(kept);
    }
}

/// Whether a body moves this step and so has its contacts found by the backend: awake and not fixed.
fn moves(body: &RigidBody) -> bool {
    !body.is_sleeping() && body.body_type() != BodyType::Fixed
}

/// A pair in ascending order.
fn ordered(a: BodyHandle, b: BodyHandle) -> (BodyHandle, BodyHandle) {
    if a <= b { (a, b) } else { (b, a) }
}

/// Adds to `manifolds` (sorted by order key, and kept so) every manifold of last step between two bodies
/// that do not move, one of them asleep, which the backend did not report again. Returns whether any was
/// added.
fn carry_resting(state: &WorldState, manifolds: &mut Vec<ContactManifold>) -> bool {
    let reported = manifolds.len();
    for old in &state.manifolds {
        let (Some(a), Some(b)) = (state.bodies.get(old.body_a), state.bodies.get(old.body_b))
        else {
            continue;
        };
        if moves(a) || moves(b) || !(a.is_sleeping() || b.is_sleeping()) {
            continue;
        }
        let key = old.order_key();
        if manifolds[..reported]
            .binary_search_by_key(&key, ContactManifold::order_key)
            .is_err()
        {
            manifolds.push(*old);
        }
    }
    if manifolds.len() == reported {
        return false;
    }
    manifolds.sort_unstable_by_key(ContactManifold::order_key);
    true
}

/// Whether a backend's manifold (between live bodies) can be used: distinct bodies, finite unit normal, at most
/// [`MAX_MANIFOLD_POINTS`] points, all finite.
fn is_usable(m: &ContactManifold) -> bool {
    m.body_a != m.body_b
        && m.point_count <= MAX_MANIFOLD_POINTS
        && m.normal.is_finite()
        // |n|² within 2e-3 of 1 (|n| within 1e-3 of 1, to first order), without the square root.
        && (m.normal.length_squared() - 1.0).abs() < 2.0e-3
        && m.friction.is_finite()
        && m.friction >= 0.0
        && m.restitution.is_finite()
        && m.restitution >= 0.0
        && m.rolling_friction.is_finite()
        && m.rolling_friction >= 0.0
        && m.force_event_threshold.is_none_or(|f| f >= 0.0 && f.is_finite())
        && points_are_finite(m.points(), m.surface_velocity)
}

/// Whether every anchor and separation of `points`, and `surface_velocity`, are finite, without a branch per
/// number: `x·0` is `±0` for a finite `x` and NaN for an infinite or NaN one, so the sum of the products is
/// zero exactly when every number is finite (every point of every manifold is checked, every step).
fn points_are_finite(points: &[ManifoldPoint], surface_velocity: Vec3) -> bool {
    let zero_if_finite = points.iter().fold(surface_velocity * 0.0, |sum, p| {
        sum + p.local_anchor_a * 0.0 + p.local_anchor_b * 0.0 + Vec3::splat(p.separation * 0.0)
    });
    zero_if_finite == Vec3::ZERO
}

/// The approach speed of a manifold before the step: the fastest closing normal velocity over its points
/// (m/s, ≥ 0).
fn approach_speed(m: &ContactManifold, a: &RigidBody, b: &RigidBody) -> f32 {
    // The centres of mass found once per manifold (each is a rotation of the local centre), not per point.
    let (center_a, center_b) = (a.center_of_mass(), b.center_of_mass());
    m.points().iter().fold(0.0f32, |speed, p| {
        let world = a.pose().transform_point(p.local_anchor_a);
        let closing = -(b.velocity_at_offset(world - center_b)
            - a.velocity_at_offset(world - center_a))
        .dot(m.normal);
        speed.max(closing)
    })
}
