//! Fixtures the facade's tests share: fixed grounds and dynamic balls to build scenes from, and the check
//! that everything a world stores — bodies, contact impulses, joint states — is finite.

#![allow(
    dead_code,
    clippy::unwrap_used,
    reason = "test fixtures: each test file uses part of them, and a failure to build one is a failed test"
)]

use rebound::prelude::*;
use rebound::{JointState, QuarantineReason};

/// A fixed body at `position` carrying a cuboid of `half_extents` (m): a ground, a wall.
pub fn fixed_box(world: &mut PhysicsWorld, position: Vec3, half_extents: Vec3) -> BodyHandle {
    let body = world
        .insert_body(BodyDesc::fixed().with_position(position))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(half_extents), body)
        .unwrap();
    body
}

/// A dynamic ball of `radius` (m, density 1) at `position` moving at `v`, `w` (m/s, rad/s).
pub fn ball(world: &mut PhysicsWorld, position: Vec3, radius: f32, v: Vec3, w: Vec3) -> BodyHandle {
    let body = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(position)
                .with_linear_velocity(v)
                .with_angular_velocity(w),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(radius), body)
        .unwrap();
    body
}

/// The bodies the last step quarantined, with the reasons, in event order.
pub fn quarantine_events(world: &PhysicsWorld) -> Vec<(BodyHandle, QuarantineReason)> {
    world
        .events()
        .iter()
        .filter_map(|e| match *e {
            Event::BodyQuarantined { body, reason } => Some((body, reason)),
            _ => None,
        })
        .collect()
}

/// Whether every number of a joint state is finite.
pub fn joint_state_is_finite(s: &JointState) -> bool {
    s.linear_impulse.is_finite()
        && s.angular_impulse.is_finite()
        && [
            s.axial_impulse,
            s.lower_impulse,
            s.upper_impulse,
            s.motor_impulse,
            s.tether_impulse,
            s.reaction_force,
            s.reaction_torque,
        ]
        .iter()
        .all(|x| x.is_finite())
}

/// Everything the world stores is finite: every body's pose, velocities and mass properties, every
/// manifold's normal, points and impulses, every joint state. `after` names what came before (a call, a
/// step) in the failure message.
pub fn assert_finite(world: &PhysicsWorld, after: &dyn core::fmt::Debug) {
    for (handle, body) in world.bodies().iter() {
        let pose = body.pose();
        assert!(
            pose.position.is_finite()
                && pose.rotation.is_finite()
                && body.linear_velocity().is_finite()
                && body.angular_velocity().is_finite()
                && body.mass_properties().mass().is_finite()
                && body.mass_properties().local_inertia().is_finite(),
            "after {after:?}: body {handle:?} {body:?}"
        );
    }
    for m in world.contacts() {
        assert!(
            m.normal.is_finite()
                && m.points().iter().all(|p| p.normal_impulse.is_finite()
                    && p.tangent_impulse.is_finite()
                    && p.separation.is_finite()),
            "after {after:?}: {m:?}"
        );
    }
    for (handle, _) in world.world().joints() {
        let state = world.joint_state(handle).unwrap();
        assert!(
            joint_state_is_finite(state),
            "after {after:?}: joint {handle:?} {state:?}"
        );
    }
}
