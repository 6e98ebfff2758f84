//! The character controller's probes of the scene: a shape cast that stops `skin` short of what it hits and
//! ignores surfaces the motion leaves or slides along, a ray down to find the face under an edge, and the
//! deepest collider within a distance. Every phase of a move (slide, autostep, skin, snap, ground, carry)
//! asks its questions through [`Probe`].

use super::CharacterSettings;
use crate::query::Scene;
use crate::shape::to_parry_pose;
use crate::{ColliderHandle, QueryFilter};
use parry3d::bounding_volume::BoundingVolume;
use parry3d::query::ShapeCastOptions;
use parry3d::shape::Shape;
use rebound_math::{Pose, Quat, Vec3};
use rebound_world::BodyHandle;

/// Below this `direction · normal`, a surface touched at the start of a cast is one the motion goes into;
/// at or above it the motion leaves the surface or runs along it (walking on flat ground), and the cast
/// looks past it. The margin covers the error of a cast's normal (about 10⁻⁴ rad).
const LEAVING: f32 = -1.0e-4;

/// Where a cast shape came to rest, `skin` short of a collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SweepHit {
    /// The collider hit.
    pub(crate) collider: ColliderHandle,
    /// Its body.
    pub(crate) body: BodyHandle,
    /// How far the shape went along the direction before stopping (m, ≥ 0).
    pub(crate) distance: f32,
    /// The closest point of the collider (m, world space).
    pub(crate) point: Vec3,
    /// The collider's outward unit normal there (world space): it points at the character.
    pub(crate) normal: Vec3,
}

/// The scene, the character's shape and orientation, and the settings a move runs with.
pub(crate) struct Probe<'a> {
    pub(crate) scene: Scene<'a>,
    pub(crate) shape: &'a dyn Shape,
    pub(crate) rotation: Quat,
    pub(crate) filter: QueryFilter,
    pub(crate) settings: &'a CharacterSettings,
}

impl Probe<'_> {
    /// Casts the shape from `from` along the unit `direction` for at most `max_distance` (m) and returns the
    /// first collider it comes within `skin` of, moving towards it. Colliders of `skip_body` are ignored
    /// (the platform a carried character moves with). Ties go to the lower collider handle.
    pub(crate) fn sweep(
        &self,
        from: Vec3,
        direction: Vec3,
        max_distance: f32,
        skip_body: Option<BodyHandle>,
    ) -> Option<SweepHit> {
        let mut best: Option<SweepHit> = None;
        self.each_hit(from, direction, max_distance, skip_body, |hit| {
            // Hits come in handle order: a strictly closer one replaces, a tie keeps the lower handle.
            if best.is_none_or(|b| hit.distance < b.distance) {
                best = Some(hit);
            }
        });
        best
    }

    /// Every collider [`Probe::sweep`] could return, nearest first (ties by handle).
    pub(crate) fn sweep_all(
        &self,
        from: Vec3,
        direction: Vec3,
        max_distance: f32,
    ) -> Vec<SweepHit> {
        let mut hits = Vec::new();
        self.each_hit(from, direction, max_distance, None, |hit| hits.push(hit));
        hits.sort_by(|a, b| {
            a.distance
                .total_cmp(&b.distance)
                .then(a.collider.cmp(&b.collider))
        });
        hits
    }

    fn each_hit(
        &self,
        from: Vec3,
        direction: Vec3,
        max_distance: f32,
        skip_body: Option<BodyHandle>,
        mut found: impl FnMut(SweepHit),
    ) {
        if !(max_distance > 0.0 && max_distance.is_finite()) {
            return;
        }
        let skin = self.settings.skin;
        let start = to_parry_pose(Pose::new(from, self.rotation));
        let end = to_parry_pose(Pose::new(from + direction * max_distance, self.rotation));
        let swept = self
            .shape
            .compute_aabb(&start)
            .merged(&self.shape.compute_aabb(&end))
            .loosened(skin);
        let options = ShapeCastOptions {
            max_time_of_impact: max_distance,
            target_distance: skin,
            // Shapes already within `skin` are reported only when the motion closes in on them.
            stop_at_penetration: false,
            compute_impact_geometry_on_penetration: true,
        };
        for (handle, collider, body) in self
            .scene
            .candidates(&self.filter, |aabb| aabb.intersects(&swept))
        {
            if skip_body == Some(collider.body()) {
                continue;
            }
            let collider_pose = to_parry_pose(collider.world_pose(body.pose()));
            let Ok(Some(hit)) = parry3d::query::cast_shapes(
                &start,
                direction,
                self.shape,
                &collider_pose,
                Vec3::ZERO,
                collider.shape.as_ref(),
                options,
            ) else {
                continue;
            };
            let distance = hit.time_of_impact.clamp(0.0, max_distance);
            // The cast's own normal comes from GJK's directional distance and is off by up to ~0.01 rad
            // on flat faces; the closest points at the stopping pose give it to float precision.
            let at_hit = to_parry_pose(Pose::new(from + direction * distance, self.rotation));
            let (point, normal) = match parry3d::query::contact(
                &at_hit,
                self.shape,
                &collider_pose,
                collider.shape.as_ref(),
                2.0 * skin,
            ) {
                Ok(Some(contact)) => (contact.point2, contact.normal2),
                _ => (
                    collider_pose.transform_point(hit.witness2),
                    collider_pose.rotation * hit.normal2,
                ),
            };
            let Some(normal) = normal.try_normalize() else {
                continue;
            };
            let hit = SweepHit {
                collider: handle,
                body: collider.body(),
                distance,
                point,
                normal,
            };
            if hit.distance.is_finite() && hit.point.is_finite() && direction.dot(normal) < LEAVING
            {
                found(hit);
            }
        }
    }

    /// The point and unit normal of the face under `point` (of `collider`, or of any collider when `None`)
    /// that a ray straight down from `height` (m) above it meets within `height + below` (m); `None` when the
    /// ray starts inside that collider, misses it, or meets it from below.
    pub(crate) fn face_below(
        &self,
        point: Vec3,
        height: f32,
        below: f32,
        collider: Option<ColliderHandle>,
    ) -> Option<(Vec3, Vec3)> {
        let up = self.settings.up;
        let origin = point + up * height;
        let hits = self
            .scene
            .cast_ray_all(origin, -up, height + below, &self.filter)
            .ok()?;
        let hit = hits
            .into_iter()
            .find(|h| collider.is_none_or(|c| c == h.collider))?;
        // A ray starting inside the collider hits it at distance 0 with no normal.
        let normal = hit.normal.try_normalize()?;
        (hit.distance > 0.0 && normal.dot(up) > 0.0).then_some((hit.point, normal))
    }

    /// The deepest collider the shape at `position` is closer to than `distance` (m): its gap (m, negative
    /// when overlapping) and outward unit normal.
    pub(crate) fn closest_within(&self, position: Vec3, distance: f32) -> Option<(f32, Vec3)> {
        let pose = to_parry_pose(Pose::new(position, self.rotation));
        let aabb = self.shape.compute_aabb(&pose).loosened(distance);
        let mut deepest: Option<(f32, Vec3)> = None;
        for (_, collider, body) in self
            .scene
            .candidates(&self.filter, |other| other.intersects(&aabb))
        {
            let collider_pose = to_parry_pose(collider.world_pose(body.pose()));
            let Ok(Some(contact)) = parry3d::query::contact(
                &pose,
                self.shape,
                &collider_pose,
                collider.shape.as_ref(),
                distance,
            ) else {
                continue;
            };
            let Some(normal) = contact.normal2.try_normalize() else {
                continue;
            };
            if contact.dist < distance && deepest.is_none_or(|(gap, _)| contact.dist < gap) {
                deepest = Some((contact.dist, normal));
            }
        }
        deepest
    }

    /// Whether a surface with unit normal `normal` can be walked on (not steeper than the slope limit).
    pub(crate) fn is_walkable(&self, normal: Vec3) -> bool {
        normal.dot(self.settings.up) >= self.settings.min_walkable_cos() - 1.0e-6
    }

    /// The part of `v` across `up` (what moves the character along the ground).
    pub(crate) fn horizontal(&self, v: Vec3) -> Vec3 {
        v - self.settings.up * v.dot(self.settings.up)
    }
}
