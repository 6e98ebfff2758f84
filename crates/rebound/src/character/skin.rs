//! Keeping the skin: after the slide, a shape that ended closer than half the `skin` to a collider (a cast
//! that grazed a face and missed it by rounding, a platform or a body that moved into the character) is
//! pushed back out to the full `skin`. Off walkable ground it is lifted straight up, which keeps the
//! horizontal motion; off anything else it moves along the surface normal.

use super::sweep::Probe;
use rebound_math::Vec3;

/// At most this many push-outs per move (one per collider too close, deepest first).
const MAX_PUSHES: usize = 4;

/// `position` moved out to `skin` from every collider closer than `skin / 2`.
pub(crate) fn restore(probe: &Probe<'_>, position: Vec3) -> Vec3 {
    let skin = probe.settings.skin;
    let up = probe.settings.up;
    let mut position = position;
    for _ in 0..MAX_PUSHES {
        let Some((gap, normal)) = probe.closest_within(position, 0.5 * skin) else {
            break;
        };
        let depth = skin - gap;
        position += if probe.is_walkable(normal) {
            up * (depth / normal.dot(up))
        } else {
            normal * depth
        };
    }
    position
}
