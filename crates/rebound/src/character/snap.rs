//! Snap to ground: after the slide, a character that was on the ground and is not rising is pulled straight
//! down onto walkable ground within `snap_to_ground` (m), so it follows a downhill slope or a step down
//! instead of flying off it.

use super::ground::{self, Ground};
use super::sweep::Probe;
use rebound_math::Vec3;

/// The position `skin` above the walkable ground within `distance` (m) below `position`, and that ground;
/// `None` when there is none (a drop deeper than `distance`, or only steep surfaces).
pub(crate) fn snap(probe: &Probe<'_>, position: Vec3, distance: f32) -> Option<(Vec3, Ground)> {
    let down = -probe.settings.up;
    let hit = probe.sweep(position, down, distance, None)?;
    let ground = ground::ground_of(probe, &hit)?;
    Some((position + down * hit.distance, ground))
}
