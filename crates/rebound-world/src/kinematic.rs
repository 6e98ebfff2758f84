//! Stage *kinematic targets*, first in the step: a kinematic body asked to reach a pose by the end of the
//! step (`World::set_kinematic_target`) gets the velocities that take it there.

use crate::body_set::BodySet;
use crate::quarantine::Bounds;
use rebound_dynamics::BodyType;

/// Kinematic targets become velocities for this step: `v = Δx/dt`, `ω = axis·angle/dt`. Returns whether
/// every body given a velocity is within `bounds` (the quarantine then need not check the bodies again).
pub(crate) fn apply_kinematic_targets(bodies: &mut BodySet, dt: f32, bounds: &Bounds) -> bool {
    let mut within = true;
    for (_, entry) in bodies.arena.iter_mut() {
        let Some(target) = entry.kinematic_target.take() else {
            continue;
        };
        if entry.body.body_type() != BodyType::Kinematic {
            continue;
        }
        let linear = (target.position - entry.body.position()) / dt;
        let mut delta = target.rotation * entry.body.rotation().conjugate();
        if delta.w < 0.0 {
            delta = -delta;
        }
        let (axis, angle) = delta.to_axis_angle();
        // Both are finite: the target and the pose were validated, dt > 0.
        let _ = entry.body.set_linear_velocity(linear);
        let _ = entry.body.set_angular_velocity(axis * (angle / dt));
        let body = &entry.body;
        within &= bounds.within(
            body.position(),
            body.linear_velocity(),
            body.angular_velocity(),
        );
    }
    within
}
