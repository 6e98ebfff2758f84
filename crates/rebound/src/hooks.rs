//! Contact hooks (stage *collide*, inside the narrow phase): a user callback set on the world
//! ([`crate::PhysicsWorld::set_contact_hooks`]) that may drop a candidate pair before its contacts are
//! computed ([`ContactHooks::filter_pair`]) and edit each manifold the pair produced before the solver sees
//! it ([`ContactHooks::modify_contacts`]): disable points, change friction and restitution, give a surface a
//! velocity (a conveyor belt). [`crate::OneWayPlatform`] is built on it.
//!
//! The trait's docs say in which order hooks run and what a panicking hook does.

use crate::{Collider, ColliderHandle};
use rebound_dynamics::RigidBody;
use rebound_math::Vec3;
use rebound_world::{BodyHandle, ContactManifold, MAX_MANIFOLD_POINTS, ManifoldWriter};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// What a hook sees of a pair: its two colliders and their bodies. A is the collider with the lower handle;
/// a manifold's normal points from A to B.
#[derive(Debug, Clone, Copy)]
pub struct ContactPair<'a> {
    /// Collider A's handle.
    pub collider_a: ColliderHandle,
    /// Collider B's handle.
    pub collider_b: ColliderHandle,
    /// Collider A.
    pub a: &'a Collider,
    /// Collider B.
    pub b: &'a Collider,
    /// Body A (collider A's body) and its handle.
    pub body_a: (BodyHandle, &'a RigidBody),
    /// Body B and its handle.
    pub body_b: (BodyHandle, &'a RigidBody),
}

impl ContactPair<'_> {
    /// Whether `collider` is one of the pair.
    #[must_use]
    pub fn involves(&self, collider: ColliderHandle) -> bool {
        self.collider_a == collider || self.collider_b == collider
    }
}

/// One contact point as a hook edits it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPointEdit {
    /// The point in world space (m): the midpoint of its anchors on the two bodies.
    pub world_point: Vec3,
    /// Signed distance between the surfaces along the normal (m): negative when overlapping.
    pub separation: f32,
    /// Whether the solver gets the point. Default: `true`.
    pub enabled: bool,
    /// Friction coefficient (dimensionless, ≥ 0). Default: the pair's combined friction.
    pub friction: f32,
    /// Coefficient of restitution (dimensionless, in `[0, 1]`). Default: the pair's combined restitution.
    pub restitution: f32,
}

/// A manifold as a hook edits it: its normal, its points, and the surface velocity of the contact. Changes
/// are checked when the hook returns: a value out of range (a negative or non-finite friction, a restitution
/// outside `[0, 1]`, a non-finite velocity) rejects the whole edit and the manifold stays as made; the
/// rejection counts in [`rebound_world::StepReport::hook_failure_count`], as a panic does.
///
/// The solver's friction acts on the manifold's patch, with one coefficient per manifold (`docs/physics.md`,
/// Contacts): the enabled points' coefficients enter as their mean, which is exact when they agree (setting
/// every point's friction to 0 makes the contact frictionless). Restitution likewise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEdit {
    normal: Vec3,
    points: [ContactPointEdit; MAX_MANIFOLD_POINTS],
    count: usize,
    surface_velocity: Vec3,
}

impl ContactEdit {
    /// The unit normal in world space, from A to B.
    #[must_use]
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// The points.
    #[must_use]
    pub fn points(&self) -> &[ContactPointEdit] {
        &self.points[..self.count]
    }

    /// The points, to edit.
    pub fn points_mut(&mut self) -> &mut [ContactPointEdit] {
        &mut self.points[..self.count]
    }

    /// Disables every point: the pair does not touch this step.
    pub fn disable(&mut self) {
        self.points_mut().iter_mut().for_each(|p| p.enabled = false);
    }

    /// Sets every point's friction coefficient.
    pub fn set_friction(&mut self, friction: f32) {
        self.points_mut()
            .iter_mut()
            .for_each(|p| p.friction = friction);
    }

    /// Sets every point's coefficient of restitution.
    pub fn set_restitution(&mut self, restitution: f32) {
        self.points_mut()
            .iter_mut()
            .for_each(|p| p.restitution = restitution);
    }

    /// The velocity (m/s, world axes) at which B's surface slides relative to A's in the contact plane.
    /// Default: zero.
    #[must_use]
    pub fn surface_velocity(&self) -> Vec3 {
        self.surface_velocity
    }

    /// Makes the surface of `collider` (one of `pair`) move at `velocity` (m/s, world axes) relative to its
    /// body, like a conveyor belt: friction drives what touches it to that velocity instead of to the
    /// body's. Only the part in the contact plane counts. Nothing happens if `collider` is not in the pair.
    pub fn set_surface_velocity(
        &mut self,
        pair: &ContactPair<'_>,
        collider: ColliderHandle,
        velocity: Vec3,
    ) {
        let tangential = velocity - self.normal * self.normal.dot(velocity);
        // B relative to A: a moving A drags B along (+), a moving B slides against A (−).
        if collider == pair.collider_a {
            self.surface_velocity = tangential;
        } else if collider == pair.collider_b {
            self.surface_velocity = -tangential;
        }
    }

    /// The edit of `manifold` between bodies `a` and `b`.
    fn of(manifold: &ContactManifold, a: &RigidBody, b: &RigidBody) -> Self {
        let mut points = [ContactPointEdit {
            world_point: Vec3::ZERO,
            separation: 0.0,
            enabled: false,
            friction: manifold.friction,
            restitution: manifold.restitution,
        }; MAX_MANIFOLD_POINTS];
        for (edit, p) in points.iter_mut().zip(manifold.points()) {
            edit.world_point = p.world_point(a.pose(), b.pose());
            edit.separation = p.separation;
            edit.enabled = true;
        }
        Self {
            normal: manifold.normal,
            points,
            count: manifold.points().len(),
            surface_velocity: manifold.surface_velocity,
        }
    }

    /// Whether every value of the edit is in range (see the type's docs).
    fn is_valid(&self) -> bool {
        self.surface_velocity.is_finite()
            && self.points().iter().all(|p| {
                p.friction >= 0.0 && p.friction.is_finite() && (0.0..=1.0).contains(&p.restitution)
            })
    }

    /// Writes the edit into `manifold`: the enabled points, kept in order; the mean friction and restitution
    /// of the enabled points; the surface velocity.
    fn apply(&self, manifold: &mut ContactManifold) {
        let (mut kept, mut friction, mut restitution) = (0, 0.0, 0.0);
        for (k, p) in self.points().iter().enumerate() {
            if !p.enabled {
                continue;
            }
            manifold.points[kept] = manifold.points[k];
            friction += p.friction;
            restitution += p.restitution;
            kept += 1;
        }
        manifold.point_count = kept;
        if kept > 0 {
            manifold.friction = friction / kept as f32;
            manifold.restitution = restitution / kept as f32;
        }
        manifold.surface_velocity = self.surface_velocity;
    }
}

/// A user callback on the contacts of every step, set with [`crate::PhysicsWorld::set_contact_hooks`]: it may
/// drop a candidate pair before its contacts are computed ([`ContactHooks::filter_pair`]) and edit each
/// manifold the pair produced before the solver sees it ([`ContactHooks::modify_contacts`]). Both methods
/// have defaults that change nothing. A closure `Fn(&ContactPair, &mut ContactEdit)` is a hook that only
/// modifies; [`crate::OneWayPlatform`] is one.
///
/// **Order.** Hooks run in the narrow phase's order: candidate pairs sorted by collider handle (lower first),
/// a pair's manifolds in sub-shape order — never in an order that depends on hashing or addresses, so a world
/// with hooks steps deterministically as long as the hooks do.
///
/// **A hook that panics.** Each call runs under `catch_unwind`. A panicking `filter_pair` counts as `true`
/// (the pair is collided as if no hook were set); a panicking `modify_contacts` leaves the manifold as the
/// narrow phase made it (the edit is made on a copy, written back only when the call returns). Either way
/// the step goes on and [`rebound_world::StepReport::hook_failure_count`] counts the panics; the world stays
/// valid. The panic message still goes to the panic hook (stderr by default). State the hook itself holds may
/// be left half-updated: that is the hook's own business.
///
/// **Box pairs are not recycled while hooks are set**: a recycled manifold would keep the points an earlier
/// call disabled.
pub trait ContactHooks: Send + Sync {
    /// Whether the candidate pair `pair` gets contacts this step (`false`: none are computed, as if the
    /// colliders did not overlap). Default: `true`.
    fn filter_pair(&self, pair: &ContactPair<'_>) -> bool {
        let _ = pair;
        true
    }

    /// Edits one manifold of `pair` before the solver sees it. Default: nothing.
    fn modify_contacts(&self, pair: &ContactPair<'_>, contacts: &mut ContactEdit) {
        let _ = (pair, contacts);
    }
}

impl<F> ContactHooks for F
where
    F: Fn(&ContactPair<'_>, &mut ContactEdit) + Send + Sync,
{
    fn modify_contacts(&self, pair: &ContactPair<'_>, contacts: &mut ContactEdit) {
        self(pair, contacts);
    }
}

/// `hooks.filter_pair(pair)` under `catch_unwind`; a panic counts in `panics` and keeps the pair.
pub(crate) fn filter(hooks: &dyn ContactHooks, pair: &ContactPair<'_>, panics: &mut usize) -> bool {
    catch_unwind(AssertUnwindSafe(|| hooks.filter_pair(pair))).unwrap_or_else(|_| {
        *panics += 1;
        true
    })
}

/// Runs `hooks.modify_contacts` on each manifold of `manifolds` (one pair's, just made) under
/// `catch_unwind`, applies the checked edits and drops the manifolds left without points. A panic or a
/// refused edit leaves the manifold as made and counts in `failures`.
pub(crate) fn modify(
    hooks: &dyn ContactHooks,
    pair: &ContactPair<'_>,
    manifolds: &mut ManifoldWriter<'_>,
    first: usize,
    failures: &mut usize,
) {
    for manifold in &mut manifolds.as_mut_slice()[first..] {
        let mut edit = ContactEdit::of(manifold, pair.body_a.1, pair.body_b.1);
        let returned = catch_unwind(AssertUnwindSafe(|| hooks.modify_contacts(pair, &mut edit)));
        if returned.is_err() || !edit.is_valid() {
            *failures += 1;
            continue;
        }
        edit.apply(manifold);
    }
    // The manifolds left with points move down over the others, in order.
    let written = manifolds.as_mut_slice();
    let mut kept = first;
    for index in first..written.len() {
        if written[index].point_count != 0 {
            written[kept] = written[index];
            kept += 1;
        }
    }
    manifolds.truncate(kept);
}
