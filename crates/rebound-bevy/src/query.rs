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

/// A facade query result ([`rebound::RayHit`], [`rebound::ShapeHit`], [`rebound::PointHit`],
/// [`rebound::PickHit`]) with the entities of the collider and the body it names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntityHit<H> {
    /// The collider's entity.
    pub collider: Entity,
    /// Its body's entity.
    pub body: Entity,
    /// The facade's result: distance, point, normal and the rest, each documented there (its handles name
    /// the same collider and body).
    pub hit: H,
}

/// Where a ray hit a collider (see [`rebound::RayHit`]).
pub type EntityRayHit = EntityHit<rebound::RayHit>;
/// Where a cast shape first touched a collider (see [`rebound::ShapeHit`]).
pub type EntityShapeHit = EntityHit<rebound::ShapeHit>;
/// The closest point of a collider to a query point (see [`rebound::PointHit`]).
pub type EntityPointHit = EntityHit<rebound::PointHit>;
/// A dynamic body under a ray, and where to hold it (see [`rebound::PickHit`]).
pub type EntityPickHit = EntityHit<rebound::PickHit>;

/// A facade query result that names a collider and its body.
trait Hit {
    fn handles(&self) -> (rebound::ColliderHandle, rebound::BodyHandle);
}

macro_rules! impl_hit {
    ($($hit:ty),*) => {$(
        impl Hit for $hit {
            fn handles(&self) -> (rebound::ColliderHandle, rebound::BodyHandle) {
                (self.collider, self.body)
            }
        }
    )*};
}
impl_hit!(
    rebound::RayHit,
    rebound::ShapeHit,
    rebound::PointHit,
    rebound::PickHit
);

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

    /// `hit` with the entities it names (`None` if one is not the plugin's).
    fn named<H: Hit>(&self, hit: H) -> Option<EntityHit<H>> {
        let (collider, body) = hit.handles();
        Some(EntityHit {
            collider: self.physics.collider_entity(collider)?,
            body: self.physics.body_entity(body)?,
            hit,
        })
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
        Ok(hit.and_then(|hit| self.named(hit)))
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
        Ok(hits.into_iter().filter_map(|hit| self.named(hit)).collect())
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
        Ok(hit.and_then(|hit| self.named(hit)))
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
        Ok(hit.and_then(|hit| self.named(hit)))
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
        Ok(hit.and_then(|hit| self.named(hit)))
    }
}
