//! `PhysicsWorld`'s spatial queries: rays, shape casts, point projections, overlaps and picking, answered by
//! [`Scene`] over the query BVH.

use super::PhysicsWorld;
use crate::query::Scene;
use crate::{
    ColliderHandle, ColliderShape, Error, PickHit, PointHit, QueryFilter, RayHit, ShapeHit,
};
use rebound_math::{Pose, Vec3};

impl PhysicsWorld {
    pub(crate) fn scene(&self) -> Scene<'_> {
        let backend = self.world.backend();
        Scene {
            colliders: &backend.colliders,
            bodies: self.world.bodies(),
            broad_phase: &backend.broad_phase,
        }
    }

    /// The first collider a ray from `origin` along `direction` (any non-zero length; normalised) hits within
    /// `max_distance` (m, may be +∞). A ray starting inside a collider hits it at distance 0. Ties go to the
    /// lower collider handle.
    ///
    /// # Errors
    /// A non-finite origin, a zero or non-finite direction, a negative or NaN `max_distance`.
    pub fn cast_ray(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<RayHit>, Error> {
        self.scene()
            .cast_ray(origin, direction, max_distance, filter)
    }

    /// Every collider the ray hits within `max_distance`, nearest first (ties by handle).
    ///
    /// # Errors
    /// As [`PhysicsWorld::cast_ray`].
    pub fn cast_ray_all(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Vec<RayHit>, Error> {
        self.scene()
            .cast_ray_all(origin, direction, max_distance, filter)
    }

    /// Sweeps `shape` from `pose` along `direction` (normalised) for up to `max_distance` (m, finite) and
    /// returns the first collider it touches.
    ///
    /// # Errors
    /// An invalid shape or pose, a zero direction, a negative or non-finite `max_distance`.
    pub fn cast_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<ShapeHit>, Error> {
        self.scene()
            .cast_shape(shape, pose, direction, max_distance, filter)
    }

    /// The collider closest to `point` within `max_distance` (m, may be +∞), with the closest point on it.
    ///
    /// # Errors
    /// A non-finite point, a negative or NaN `max_distance`.
    pub fn project_point(
        &self,
        point: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<PointHit>, Error> {
        self.scene().project_point(point, max_distance, filter)
    }

    /// The colliders overlapping `shape` placed at `pose`, sorted by handle.
    ///
    /// # Errors
    /// An invalid shape or pose.
    pub fn intersect_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        filter: &QueryFilter,
    ) -> Result<Vec<ColliderHandle>, Error> {
        self.scene().intersect_shape(shape, pose, filter)
    }

    /// Drag and drop: the dynamic body under a ray (sensors ignored), with the hit point in world space and in
    /// the body's frame (the anchor for a drag spring). `None` when the ray hits nothing, or hits a fixed or
    /// kinematic collider first.
    ///
    /// # Errors
    /// As [`PhysicsWorld::cast_ray`].
    pub fn pick_body(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
    ) -> Result<Option<PickHit>, Error> {
        self.scene().pick_body(origin, direction, max_distance)
    }
}
