//! Autostep: a grounded character blocked by something it cannot walk up tries to climb over it — rise by at
//! most `max_height`, move the rest of the horizontal motion, come down — and keeps the climb only if it
//! lands on walkable ground at least `min_width` deep. Called by the slide at a steep hit.

use super::sweep::{Probe, SweepHit};
use rebound_math::Vec3;

/// How far below the landing contact the face `min_width` beyond it may lie (m), beyond `skin`: a ledge
/// that drops away more is an edge, not the top of a step.
const LEDGE_DROP: f32 = 0.01;

/// The position after climbing over `obstacle` with the horizontal part of `remaining` (m), from the ground
/// at `ground_point`, or `None` when autostep is off or the obstacle is not a step (its top higher than
/// `max_height` above the ground, too thin, a dynamic body when those are excluded, not walkable).
pub(crate) fn try_step(
    probe: &Probe<'_>,
    position: Vec3,
    remaining: Vec3,
    obstacle: &SweepHit,
    ground_point: Vec3,
) -> Option<Vec3> {
    let step = probe.settings.autostep?;
    let up = probe.settings.up;
    let skin = probe.settings.skin;
    let body = probe.scene.bodies.get(obstacle.body)?;
    if body.is_dynamic() && !step.include_dynamic_bodies {
        return None;
    }
    let horizontal = probe.horizontal(remaining);
    let length = horizontal.length();
    let direction = horizontal.try_normalize()?;
    // Rise as far as the ceiling allows.
    let rise = probe
        .sweep(position, up, step.max_height, None)
        .map_or(step.max_height, |hit| hit.distance);
    if rise <= skin {
        return None;
    }
    let raised = position + up * rise;
    // The whole horizontal motion must be free at that height.
    if probe.sweep(raised, direction, length, None).is_some() {
        return None;
    }
    let forward = raised + direction * length;
    let landing = probe.sweep(forward, -up, rise, None)?;
    if landing.distance >= rise {
        return None;
    }
    let landing_body = probe.scene.bodies.get(landing.body)?;
    if landing_body.is_dynamic() && !step.include_dynamic_bodies {
        return None;
    }
    // The top must be walkable `min_width` beyond where the shape lands, not lower than the landing.
    let (top_point, top) = probe.face_below(
        landing.point + direction * step.min_width,
        rise + skin,
        skin + LEDGE_DROP,
        None,
    )?;
    let height = (top_point - ground_point).dot(up);
    (probe.is_walkable(top) && height <= step.max_height).then_some(forward - up * landing.distance)
}
