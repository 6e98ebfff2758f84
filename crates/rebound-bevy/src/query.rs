//! [`SpatialQuery`]: the facade's scene queries (ray casts, shape casts, point projection, overlap, picking) as
//! a system parameter whose results name entities. Not part of the step: queries read the colliders at
//! the poses of the last step (or of the last edit).

use crate::Physics;
use bevy_ecs::entity::Entity;
use bevy_ecs::system::{Res, SystemParam};
use rebound::prelude::{ColliderShape, CollisionGroups, Pose, QueryFilter, Vec3};

/// Which colliders a query sees, by entity. Disabled colliders are never seen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SpatialQueryFilter {
    /// The query's own groups, tested against each collider's ([`CollisionGroups::interacts_with`]).
    /// Default: [`CollisionGroups::ALL`].
    pub groups: CollisionGroups,
    /// A body entity whose colliders are ignored (the character casting the ray). Default: none.
    pub exclude_body: Option<Entity>,
    /// Whether sensors are ignored. Default: false.
    pub exclude_sensors: bool,
}

impl SpatialQueryFilter {
    /// Ignores the colliders of the body of `entity`.
    #[must_use]
    pub const fn excluding_body(mut self, entity: Entity) -> Self {
        self.exclude_body = Some(entity);
        self
    }

    /// Ignores sensors.
    #[must_use]
    pub const fn excluding_sensors(mut self) -> Self {
        self.exclude_sensors = true;
        self
    }

    /// Sets the query's groups.
    #[must_use]
    pub const fn with_groups(mut self, groups: CollisionGroups) -> Self {
        self.groups = groups;
        self
    }
}

/// Where a ray hit a collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntityRayHit {
    /// The collider's entity.
    pub collider: Entity,
    /// Its body's entity.
    pub body: Entity,
    /// Distance along the (normalised) direction (m); 0 when the origin is inside.
    pub distance: f32,
    /// The hit point (m, world space).
    pub point: Vec3,
    /// The surface normal there (unit, world space; zero when the origin is inside).
    pub normal: Vec3,
}

/// Where a cast shape first touched a collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntityShapeHit {
    /// The collider's entity.
    pub collider: Entity,
    /// Its body's entity.
    pub body: Entity,
    /// How far the shape travelled before touching (m); 0 if it overlapped at the start.
    pub distance: f32,
    /// The contact point on the collider hit (m, world space).
    pub point: Vec3,
    /// The collider's outward normal there (world space).
    pub normal: Vec3,
}

/// The closest point of a collider to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntityPointHit {
    /// The collider's entity.
    pub collider: Entity,
    /// Its body's entity.
    pub body: Entity,
    /// The closest point (m, world space); the query point itself when it is inside.
    pub point: Vec3,
    /// Distance from the query point (m); 0 inside.
    pub distance: f32,
    /// Whether the query point is inside the collider.
    pub is_inside: bool,
}

/// A dynamic body under a ray, and where to hold it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntityPickHit {
    /// The body's entity.
    pub body: Entity,
    /// The collider's entity.
    pub collider: Entity,
    /// The hit point (m, world space).
    pub point: Vec3,
    /// The hit point in the body's frame (m): the anchor for a drag joint.
    pub local_point: Vec3,
    /// Distance along the ray (m).
    pub distance: f32,
}

/// Scene queries in a system: `fn aim(query: SpatialQuery) { ... }`. Each method is the facade's
/// ([`rebound::PhysicsWorld::cast_ray`] and its siblings) with entities in the results; hits on colliders that
/// are not the plugin's are skipped.
///
/// # Errors
/// Every method returns the facade's error for an invalid argument (a zero direction, a NaN distance, an
/// invalid shape or pose).
#[derive(SystemParam)]
pub struct SpatialQuery<'w> {
    physics: Res<'w, Physics>,
}

impl SpatialQuery<'_> {
    fn filter(&self, filter: &SpatialQueryFilter) -> QueryFilter {
        QueryFilter {
            groups: filter.groups,
            exclude_body: filter
                .exclude_body
                .and_then(|entity| self.physics.body_handle(entity)),
            exclude_sensors: filter.exclude_sensors,
        }
    }

    fn entities(
        &self,
        collider: rebound::ColliderHandle,
        body: rebound::BodyHandle,
    ) -> Option<(Entity, Entity)> {
        Some((
            self.physics.collider_entity(collider)?,
            self.physics.body_entity(body)?,
        ))
    }

    /// The first collider a ray from `origin` along `direction` hits within `max_distance` (m, may be +∞).
    ///
    /// # Errors
    /// As [`rebound::PhysicsWorld::cast_ray`].
    pub fn cast_ray(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &SpatialQueryFilter,
    ) -> Result<Option<EntityRayHit>, rebound::Error> {
        let hit =
            self.physics
                .world
                .cast_ray(origin, direction, max_distance, &self.filter(filter))?;
        Ok(hit.and_then(|hit| self.ray_hit(hit)))
    }

    fn ray_hit(&self, hit: rebound::RayHit) -> Option<EntityRayHit> {
        let (collider, body) = self.entities(hit.collider, hit.body)?;
        Some(EntityRayHit {
            collider,
            body,
            distance: hit.distance,
            point: hit.point,
            normal: hit.normal,
        })
    }

    /// Every collider the ray hits within `max_distance`, nearest first.
    ///
    /// # Errors
    /// As [`rebound::PhysicsWorld::cast_ray_all`].
    pub fn cast_ray_all(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &SpatialQueryFilter,
    ) -> Result<Vec<EntityRayHit>, rebound::Error> {
        let hits = self.physics.world.cast_ray_all(
            origin,
            direction,
            max_distance,
            &self.filter(filter),
        )?;
        Ok(hits
            .into_iter()
            .filter_map(|hit| self.ray_hit(hit))
            .collect())
    }

    /// Sweeps `shape` from `pose` along `direction` for up to `max_distance` (m) and returns the first collider
    /// it touches.
    ///
    /// # Errors
    /// As [`rebound::PhysicsWorld::cast_shape`].
    pub fn cast_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        direction: Vec3,
        max_distance: f32,
        filter: &SpatialQueryFilter,
    ) -> Result<Option<EntityShapeHit>, rebound::Error> {
        let hit = self.physics.world.cast_shape(
            shape,
            pose,
            direction,
            max_distance,
            &self.filter(filter),
        )?;
        Ok(hit.and_then(|hit| {
            let (collider, body) = self.entities(hit.collider, hit.body)?;
            Some(EntityShapeHit {
                collider,
                body,
                distance: hit.distance,
                point: hit.point,
                normal: hit.normal,
            })
        }))
    }

    /// The collider closest to `point` within `max_distance` (m, may be +∞).
    ///
    /// # Errors
    /// As [`rebound::PhysicsWorld::project_point`].
    pub fn project_point(
        &self,
        point: Vec3,
        max_distance: f32,
        filter: &SpatialQueryFilter,
    ) -> Result<Option<EntityPointHit>, rebound::Error> {
        let hit = self
            .physics
            .world
            .project_point(point, max_distance, &self.filter(filter))?;
        Ok(hit.and_then(|hit| {
            let (collider, body) = self.entities(hit.collider, hit.body)?;
            Some(EntityPointHit {
                collider,
                body,
                point: hit.point,
                distance: hit.distance,
                is_inside: hit.is_inside,
            })
        }))
    }

    /// The collider entities overlapping `shape` at `pose`, in collider-handle order.
    ///
    /// # Errors
    /// As [`rebound::PhysicsWorld::intersect_shape`].
    pub fn intersect_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        filter: &SpatialQueryFilter,
    ) -> Result<Vec<Entity>, rebound::Error> {
        let hits = self
            .physics
            .world
            .intersect_shape(shape, pose, &self.filter(filter))?;
        Ok(hits
            .into_iter()
            .filter_map(|collider| self.physics.collider_entity(collider))
            .collect())
    }

    /// The dynamic body under a ray (sensors ignored), for drag and drop.
    ///
    /// # Errors
    /// As [`rebound::PhysicsWorld::pick_body`].
    pub fn pick(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
    ) -> Result<Option<EntityPickHit>, rebound::Error> {
        let hit = self
            .physics
            .world
            .pick_body(origin, direction, max_distance)?;
        Ok(hit.and_then(|hit| {
            let (collider, body) = self.entities(hit.collider, hit.body)?;
            Some(EntityPickHit {
                body,
                collider,
                point: hit.point,
                local_point: hit.local_point,
                distance: hit.distance,
            })
        }))
    }
}
