//! Scene queries between steps: ray casts (first hit, all hits), shape casts, point projection, overlap with
//! a shape, and picking a body for drag and drop. Not a step stage; they read the colliders at their
//! bodies' current poses through the broad phase's BVH.
//!
//! Every query takes a [`QueryFilter`] (groups, a body to ignore, sensors) and always skips disabled
//! colliders. Results are deterministic: ties (equal distances) go to the lower collider handle, and lists
//! are sorted, whatever the shape of the BVH.

use crate::broad_phase::BroadPhase;
use crate::shape::{check_pose, to_parry_pose};
use crate::{Collider, ColliderHandle, ColliderSet, ColliderShape, CollisionGroups, Error};
use parry3d::bounding_volume::{Aabb, BoundingVolume};
use parry3d::query::{PointQuery, Ray, RayCast, ShapeCastOptions};
use parry3d::shape::SharedShape;
use rebound_math::validity::{check_direction, check_finite_vec3};
use rebound_math::{MathError, Pose, Vec3};
use rebound_world::{BodyHandle, BodySet};

/// Which colliders a query sees. Disabled colliders are never seen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct QueryFilter {
    /// The query's own groups, tested against each collider's as two colliders are
    /// ([`CollisionGroups::interacts_with`]). Default: [`CollisionGroups::ALL`] (sees everything).
    pub groups: CollisionGroups,
    /// A body whose colliders are ignored (e.g. the character casting the ray). Default: none.
    pub exclude_body: Option<BodyHandle>,
    /// Whether sensors are ignored. Default: false (sensors are hit like other colliders).
    pub exclude_sensors: bool,
}

impl QueryFilter {
    /// A filter that sees every enabled collider.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the query's groups.
    #[must_use]
    pub const fn with_groups(mut self, groups: CollisionGroups) -> Self {
        self.groups = groups;
        self
    }

    /// Ignores the colliders of `body`.
    #[must_use]
    pub const fn excluding_body(mut self, body: BodyHandle) -> Self {
        self.exclude_body = Some(body);
        self
    }

    /// Ignores sensors.
    #[must_use]
    pub const fn excluding_sensors(mut self) -> Self {
        self.exclude_sensors = true;
        self
    }

    /// Whether the filter lets `collider` through.
    #[must_use]
    pub fn accepts(&self, collider: &Collider) -> bool {
        collider.is_enabled()
            && !(self.exclude_sensors && collider.is_sensor())
            && self.exclude_body != Some(collider.body())
            && self.groups.interacts_with(collider.groups())
    }
}

/// Where a ray hit a collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// The collider hit.
    pub collider: ColliderHandle,
    /// Its body.
    pub body: BodyHandle,
    /// Distance from the ray origin along the (normalised) direction (m). 0 when the origin is inside a
    /// collider.
    pub distance: f32,
    /// The hit point (m, world space).
    pub point: Vec3,
    /// The surface normal at the hit point (world space, unit; zero when the origin is inside).
    pub normal: Vec3,
}

/// Where a cast shape first touched a collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeHit {
    /// The collider hit.
    pub collider: ColliderHandle,
    /// Its body.
    pub body: BodyHandle,
    /// How far the shape travelled along the (normalised) direction before touching (m); 0 if it overlapped
    /// at the start.
    pub distance: f32,
    /// The contact point on the collider hit (m, world space).
    pub point: Vec3,
    /// The collider's outward normal at that point (world space).
    pub normal: Vec3,
}

/// The closest point of a collider to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointHit {
    /// The collider.
    pub collider: ColliderHandle,
    /// Its body.
    pub body: BodyHandle,
    /// The closest point on (or, for a point inside, the point itself in) the collider (m, world space).
    pub point: Vec3,
    /// Distance from the query point (m); 0 when it is inside.
    pub distance: f32,
    /// Whether the query point is inside the collider.
    pub is_inside: bool,
}

/// What [`crate::PhysicsWorld::pick_body`] found: a dynamic body under the ray, and where to hold it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PickHit {
    /// The body.
    pub body: BodyHandle,
    /// The collider the ray hit.
    pub collider: ColliderHandle,
    /// The hit point (m, world space).
    pub point: Vec3,
    /// The hit point in the body's frame (m, relative to the body origin): the anchor for a drag spring.
    pub local_point: Vec3,
    /// Distance along the ray (m).
    pub distance: f32,
}

/// The colliders, bodies and index a query reads.
pub(crate) struct Scene<'a> {
    pub(crate) colliders: &'a ColliderSet,
    pub(crate) bodies: &'a BodySet,
    pub(crate) broad_phase: &'a BroadPhase,
}

/// A validated ray: unit direction, a maximum distance (m, may be +∞).
fn checked_ray(origin: Vec3, direction: Vec3, max_distance: f32) -> Result<(Ray, f32), Error> {
    check_finite_vec3("origin", origin)?;
    let (unit, _) = check_direction("direction", direction)?;
    let max = checked_max_distance(max_distance)?;
    Ok((Ray::new(origin, unit), max))
}

/// A maximum distance: ≥ 0, +∞ allowed (then parry gets `f32::MAX`).
fn checked_max_distance(max_distance: f32) -> Result<f32, Error> {
    if max_distance.is_nan() {
        return Err(MathError::NonFinite {
            field: "max_distance",
            value: max_distance,
        }
        .into());
    }
    if max_distance < 0.0 {
        return Err(MathError::Negative {
            field: "max_distance",
            value: max_distance,
        }
        .into());
    }
    Ok(max_distance.min(f32::MAX))
}

impl Scene<'_> {
    /// Accepted candidates whose box passes `test`, sorted by handle, with their bodies.
    pub(crate) fn candidates(
        &self,
        filter: &QueryFilter,
        test: impl Fn(&Aabb) -> bool,
    ) -> Vec<(ColliderHandle, &Collider, &rebound_dynamics::RigidBody)> {
        let mut handles = Vec::new();
        self.broad_phase
            .candidates(self.colliders, self.bodies, test, &mut handles);
        handles
            .into_iter()
            .filter_map(|h| {
                let c = self.colliders.get(h)?;
                let b = self.bodies.get(c.body())?;
                filter.accepts(c).then_some((h, c, b))
            })
            .collect()
    }

    fn ray_hits(&self, ray: &Ray, max: f32, filter: &QueryFilter) -> Vec<RayHit> {
        let mut hits: Vec<RayHit> = self
            .candidates(filter, |aabb| aabb.cast_local_ray(ray, max, true).is_some())
            .into_iter()
            .filter_map(|(handle, collider, body)| {
                let pose = to_parry_pose(collider.world_pose(body.pose()));
                let hit = collider
                    .shape
                    .cast_ray_and_get_normal(&pose, ray, max, true)?;
                Some(RayHit {
                    collider: handle,
                    body: collider.body(),
                    distance: hit.time_of_impact,
                    point: ray.point_at(hit.time_of_impact),
                    normal: hit.normal,
                })
            })
            .filter(|hit| hit.distance.is_finite() && hit.point.is_finite())
            .collect();
        hits.sort_by(|a, b| {
            a.distance
                .total_cmp(&b.distance)
                .then(a.collider.cmp(&b.collider))
        });
        hits
    }

    pub(crate) fn cast_ray(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<RayHit>, Error> {
        let (ray, max) = checked_ray(origin, direction, max_distance)?;
        Ok(self.ray_hits(&ray, max, filter).into_iter().next())
    }

    pub(crate) fn cast_ray_all(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Vec<RayHit>, Error> {
        let (ray, max) = checked_ray(origin, direction, max_distance)?;
        Ok(self.ray_hits(&ray, max, filter))
    }

    pub(crate) fn cast_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<ShapeHit>, Error> {
        let query_shape = shape.to_parry()?;
        let pose = check_pose("pose", pose)?;
        let (unit, _) = check_direction("direction", direction)?;
        let max = checked_max_distance(max_distance)?;
        if !max.is_finite() || max >= f32::MAX {
            return Err(MathError::NonFinite {
                field: "max_distance",
                value: max_distance,
            }
            .into());
        }
        let start = to_parry_pose(pose);
        let end = to_parry_pose(Pose::new(pose.position + unit * max, pose.rotation));
        let swept = query_shape
            .compute_aabb(&start)
            .merged(&query_shape.compute_aabb(&end));
        let options = ShapeCastOptions {
            max_time_of_impact: max,
            target_distance: 0.0,
            stop_at_penetration: true,
            compute_impact_geometry_on_penetration: true,
        };
        let mut best: Option<ShapeHit> = None;
        for (handle, collider, body) in self.candidates(filter, |aabb| aabb.intersects(&swept)) {
            let collider_pose = to_parry_pose(collider.world_pose(body.pose()));
            let Ok(Some(hit)) = parry3d::query::cast_shapes(
                &start,
                unit,
                query_shape.as_ref(),
                &collider_pose,
                Vec3::ZERO,
                collider.shape.as_ref(),
                options,
            ) else {
                continue;
            };
            let candidate = ShapeHit {
                collider: handle,
                body: collider.body(),
                distance: hit.time_of_impact,
                point: collider_pose.transform_point(hit.witness2),
                normal: collider_pose.rotation * hit.normal2,
            };
            if !(candidate.distance.is_finite() && candidate.point.is_finite()) {
                continue;
            }
            // Candidates come in handle order: a strictly closer hit replaces, a tie keeps the lower handle.
            if best.is_none_or(|b| candidate.distance < b.distance) {
                best = Some(candidate);
            }
        }
        Ok(best)
    }

    pub(crate) fn project_point(
        &self,
        point: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<PointHit>, Error> {
        check_finite_vec3("point", point)?;
        let max = checked_max_distance(max_distance)?;
        let mut best: Option<PointHit> = None;
        for (handle, collider, body) in self.candidates(filter, |aabb| {
            aabb.distance_to_local_point(point, true) <= max
        }) {
            let pose = to_parry_pose(collider.world_pose(body.pose()));
            let projection = collider.shape.project_point(&pose, point, true);
            let distance = if projection.is_inside {
                0.0
            } else {
                projection.point.distance(point)
            };
            if !(distance <= max && projection.point.is_finite()) {
                continue;
            }
            if best.is_none_or(|b| distance < b.distance) {
                best = Some(PointHit {
                    collider: handle,
                    body: collider.body(),
                    point: projection.point,
                    distance,
                    is_inside: projection.is_inside,
                });
            }
        }
        Ok(best)
    }

    pub(crate) fn intersect_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        filter: &QueryFilter,
    ) -> Result<Vec<ColliderHandle>, Error> {
        let query_shape: SharedShape = shape.to_parry()?;
        let pose = to_parry_pose(check_pose("pose", pose)?);
        let aabb = query_shape.compute_aabb(&pose);
        Ok(self
            .candidates(filter, |other| other.intersects(&aabb))
            .into_iter()
            .filter(|(_, collider, body)| {
                let collider_pose = to_parry_pose(collider.world_pose(body.pose()));
                parry3d::query::intersection_test(
                    &pose,
                    query_shape.as_ref(),
                    &collider_pose,
                    collider.shape.as_ref(),
                )
                .is_ok_and(|hit| hit.intersecting)
            })
            .map(|(handle, _, _)| handle)
            .collect())
    }

    pub(crate) fn pick_body(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
    ) -> Result<Option<PickHit>, Error> {
        let filter = QueryFilter::new().excluding_sensors();
        let Some(hit) = self.cast_ray(origin, direction, max_distance, &filter)? else {
            return Ok(None);
        };
        let Some(body) = self.bodies.get(hit.body) else {
            return Ok(None);
        };
        if !body.is_dynamic() {
            return Ok(None);
        }
        Ok(Some(PickHit {
            body: hit.body,
            collider: hit.collider,
            point: hit.point,
            local_point: body.pose().inverse_transform_point(hit.point),
            distance: hit.distance,
        }))
    }
}
