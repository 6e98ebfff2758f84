//! Ground detection: whether the character stands on walkable ground, and on what (body, collider, point,
//! normal). Run before a move (to know whether it may step and snap) and after it (what the move reports).
//!
//! A convex shape resting on the edge of a step touches it along the edge, and the cast's normal there
//! points from the edge to the shape, tilted as steeply as the contact happens to be. Whether that is
//! standing on the step is a question about the face beyond the edge, so a steep contact normal is replaced
//! by the normal of the face a short ray finds just past the contact, on the far side from the character
//! ([`surface_normal`]). On a true slope that ray meets the slope itself (or starts inside it), and the
//! slope stays steep.

use super::sweep::{Probe, SweepHit};
use crate::ColliderHandle;
use rebound_math::Vec3;
use rebound_world::BodyHandle;

/// The steepest contact normal whose edge may be stood on (rad from `up`): a contact at the side of the
/// shape (a step's edge level with a capsule's bottom sphere centre) is not under it. 80°: a capsule of
/// radius 0.3 m walking onto a step edge at 0.3 m/s or faster (at 60 moves a second) lands within it.
const MAX_EDGE_CONTACT_ANGLE: f32 = 80.0 * core::f32::consts::PI / 180.0;

/// How far past a steep contact, across and above it, the ray looking for the face beyond an edge starts
/// (m).
const EDGE_REACH: f32 = 0.02;

/// What the character stands on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    /// The body under the character.
    pub body: BodyHandle,
    /// Its collider touched.
    pub collider: ColliderHandle,
    /// The contact point on the ground (m, world space).
    pub point: Vec3,
    /// The ground's unit normal there (world space, within the slope limit of `up`). On the edge of a step,
    /// the normal of the step's top face.
    pub normal: Vec3,
    /// The gap between the shape and the ground (m): `skin` when resting, up to twice `skin` while grounded
    /// (a gap below `skin`, reached only by rounding, reads as `skin`).
    pub gap: f32,
}

/// The normal of the surface under a contact, for deciding whether it can be stood on: the contact normal
/// when it is walkable or nearly horizontal, else the face a ray finds just beyond the contact away from the
/// character (the top of a step under an edge contact), else the contact normal.
pub(crate) fn surface_normal(probe: &Probe<'_>, hit: &SweepHit) -> Vec3 {
    if probe.is_walkable(hit.normal)
        || hit.normal.dot(probe.settings.up) < rebound_math::real::cos(MAX_EDGE_CONTACT_ANGLE)
    {
        return hit.normal;
    }
    let Some(away) = (-probe.horizontal(hit.normal)).try_normalize() else {
        return hit.normal;
    };
    probe
        .face_below(
            hit.point + away * EDGE_REACH,
            EDGE_REACH,
            EDGE_REACH * 0.25,
            Some(hit.collider),
        )
        .map_or(hit.normal, |(_, normal)| normal)
}

/// The walkable ground within `skin` below the shape at `position` (so within twice `skin` of it), if any:
/// the nearest surface walkable by its contact normal, else the nearest edge whose top is walkable.
pub(crate) fn detect(probe: &Probe<'_>, position: Vec3) -> Option<Ground> {
    let skin = probe.settings.skin;
    let hits = probe.sweep_all(position, -probe.settings.up, skin);
    let flat = hits.iter().find(|hit| probe.is_walkable(hit.normal));
    flat.or_else(|| hits.first())
        .and_then(|hit| ground_of(probe, hit))
}

/// `hit` as ground, when what it touched is walkable.
pub(crate) fn ground_of(probe: &Probe<'_>, hit: &SweepHit) -> Option<Ground> {
    let normal = surface_normal(probe, hit);
    probe.is_walkable(normal).then_some(Ground {
        body: hit.body,
        collider: hit.collider,
        point: hit.point,
        normal,
        gap: probe.settings.skin + hit.distance,
    })
}
