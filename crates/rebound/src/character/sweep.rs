//! The character controller's two probes of the scene: a shape cast that stops `skin` short of what it hits
//! and ignores surfaces the motion leaves or slides along, and a ray down to find the face under an edge.
//! Every phase of a move (slide, autostep, snap, ground, carry) asks its questions through [`Probe`].

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
/// looks past it.
const LEAVING: f32 = -1.0e-5;

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
        if !(max_distance > 0.0 && max_distance.is_finite()) {
            return None;
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
        let mut best: Option<SweepHit> = None;
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
            let Some(normal) = (collider_pose.rotation * hit.normal2).try_normalize() else {
                continue;
            };
            let candidate = SweepHit {
                collider: handle,
                body: collider.body(),
                distance: hit.time_of_impact.clamp(0.0, max_distance),
                point: collider_pose.transform_point(hit.witness2),
                normal,
            };
            if !(candidate.distance.is_finite() && candidate.point.is_finite())
                || direction.dot(normal) >= LEAVING
            {
                continue;
            }
            // Candidates come in handle order: a strictly closer hit replaces, a tie keeps the lower handle.
            if best.is_none_or(|b| candidate.distance < b.distance) {
                best = Some(candidate);
            }
        }
        best
    }

    /// The normal of `collider`'s face under `point` when a ray straight down from `height` (m) above it
    /// meets that face within `height + below` (m); `None` when the ray starts inside the collider or
    /// misses it. The normal is unit and faces up.
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

    /// Whether a surface with unit normal `normal` can be walked on (not steeper than the slope limit).
    pub(crate) fn is_walkable(&self, normal: Vec3) -> bool {
        normal.dot(self.settings.up) >= self.settings.min_walkable_cos() - 1.0e-6
    }

    /// The part of `v` across `up` (what moves the character along the ground).
    pub(crate) fn horizontal(&self, v: Vec3) -> Vec3 {
        v - self.settings.up * v.dot(self.settings.up)
    }
}
