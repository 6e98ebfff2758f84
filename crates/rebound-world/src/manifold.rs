//! The collision seam: the plain-data [`ContactManifold`] a collision backend reports, and the
//! [`CollisionBackend`] trait the world calls once per step (stage 2, *collide*). No collision library here:
//! the `rebound` facade implements the trait with parry3d; [`crate::testing`] has a small one for tests.

use crate::{BodyHandle, BodySet, WorldSettings};
use rebound_math::Vec3;

/// The most points a manifold carries.
pub const MAX_MANIFOLD_POINTS: usize = rebound_dynamics::MAX_CONTACT_POINTS;

/// One contact point of a manifold.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ManifoldPoint {
    /// The contact point on body A, in A's body frame (relative to its origin, m).
    pub local_anchor_a: Vec3,
    /// The contact point on body B, in B's body frame (m).
    pub local_anchor_b: Vec3,
    /// Signed distance between the surfaces along the normal (m): negative when overlapping, positive for a
    /// speculative point.
    pub separation: f32,
    /// Identifies the touching features, so the point can be matched next step (warm starting).
    pub feature_id: u32,
    /// Normal impulse of the last step (N·s), filled in by the world.
    pub normal_impulse: f32,
    /// Friction impulse of the last step as a world vector (N·s), filled in by the world.
    pub tangent_impulse: Vec3,
}

/// Contact between two bodies as the backend reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactManifold {
    /// Body A.
    pub body_a: BodyHandle,
    /// Body B.
    pub body_b: BodyHandle,
    /// A key the backend keeps stable for this manifold from step to step (e.g. the collider pair), so that
    /// two manifolds between the same bodies are told apart when warm starting.
    pub key: u64,
    /// Unit normal in world space, from A to B.
    pub normal: Vec3,
    /// Combined friction coefficient (dimensionless, ≥ 0).
    pub friction: f32,
    /// Combined coefficient of restitution (dimensionless, in `[0, 1]`).
    pub restitution: f32,
    /// Rolling resistance lever arm (m, ≥ 0; see `rebound_dynamics::Contact::rolling_friction`).
    pub rolling_friction: f32,
    /// The points; only the first `point_count` are meaningful.
    pub points: [ManifoldPoint; MAX_MANIFOLD_POINTS],
    /// How many points are in use.
    pub point_count: usize,
}

impl ContactManifold {
    /// A manifold with no points yet.
    #[must_use]
    pub fn new(
        body_a: BodyHandle,
        body_b: BodyHandle,
        key: u64,
        normal: Vec3,
        friction: f32,
        restitution: f32,
    ) -> Self {
        Self {
            body_a,
            body_b,
            key,
            normal,
            friction,
            restitution,
            rolling_friction: 0.0,
            points: [ManifoldPoint::default(); MAX_MANIFOLD_POINTS],
            point_count: 0,
        }
    }

    /// Adds a point; returns `false` when the manifold is full.
    pub fn push_point(&mut self, point: ManifoldPoint) -> bool {
        if self.point_count >= MAX_MANIFOLD_POINTS {
            return false;
        }
        self.points[self.point_count] = point;
        self.point_count += 1;
        true
    }

    /// The points in use.
    #[must_use]
    pub fn points(&self) -> &[ManifoldPoint] {
        &self.points[..self.point_count.min(MAX_MANIFOLD_POINTS)]
    }

    /// Whether any point overlaps or touches (separation ≤ 0).
    #[must_use]
    pub fn is_touching(&self) -> bool {
        self.points().iter().any(|p| p.separation <= 0.0)
    }

    /// The sort key that orders manifolds deterministically: body pair, then the backend's key.
    #[must_use]
    pub fn order_key(&self) -> (BodyHandle, BodyHandle, u64) {
        (self.body_a, self.body_b, self.key)
    }
}

/// Finds contacts between bodies. Called once per step with the current poses.
pub trait CollisionBackend {
    /// Pushes the manifolds of the current poses into `out` (cleared by the world). Impulses may be left at
    /// zero: the world matches points to last step's by body pair, key and feature id. The order of `out`
    /// must not depend on hashing or addresses; the world sorts by [`ContactManifold::order_key`] anyway.
    ///
    /// `dt` is the step about to be taken (s); a backend adds `|v|·dt` to
    /// [`WorldSettings::speculative_margin`] so fast bodies get their contacts before they arrive.
    fn collide(
        &mut self,
        bodies: &BodySet,
        settings: &WorldSettings,
        dt: f32,
        out: &mut Vec<ContactManifold>,
    );
}

/// A backend that finds nothing: for worlds of joints only.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoCollision;

impl CollisionBackend for NoCollision {
    fn collide(&mut self, _: &BodySet, _: &WorldSettings, _: f32, _: &mut Vec<ContactManifold>) {}
}
