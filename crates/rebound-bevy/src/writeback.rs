//! The step and writeback systems ([`crate::PhysicsSystems::Step`], [`crate::PhysicsSystems::Writeback`]):
//! step the world by the schedule's `Time` delta, then write each body's pose, velocity and sleep state to
//! its components (only where they changed, so resting bodies trigger no change detection) and send the
//! step's events with entities.

use crate::prepare::{same_pose, same_vec3};
use crate::{
    Body, Physics, PhysicsEvent, PhysicsSettings, Sleeping, TransformInterpolation, Velocity,
};
use bevy_ecs::message::MessageWriter;
use bevy_ecs::query::{Has, With};
use bevy_ecs::system::{Query, Res, ResMut};
use bevy_time::Time;
use bevy_transform::components::Transform;
use rebound::Event;

/// Steps the world once by the `Time` delta of the schedule it runs in (the fixed timestep in
/// `FixedPostUpdate`). Nothing happens while paused, without a `Time` resource, or for a zero delta.
pub(crate) fn step_world(
    mut physics: ResMut<'_, Physics>,
    settings: Res<'_, PhysicsSettings>,
    time: Option<Res<'_, Time>>,
) {
    physics.stepped = false;
    let Some(time) = time else {
        return;
    };
    let dt = time.delta_secs();
    if settings.paused || dt <= 0.0 {
        return;
    }
    physics.last_report = physics.world.step(dt);
    physics.stepped = physics.last_report.skipped.is_none();
}

/// Writes the step's results to the body entities and sends its events.
pub(crate) fn writeback(
    mut physics: ResMut<'_, Physics>,
    mut query: Query<
        '_,
        '_,
        (
            &mut Transform,
            &mut Velocity,
            &mut Sleeping,
            Has<TransformInterpolation>,
        ),
        With<Body>,
    >,
    mut events: MessageWriter<'_, PhysicsEvent>,
) {
    let physics = &mut *physics;
    if !physics.stepped {
        return;
    }
    // Walking the ordered table and looking each entity up is cheaper than a table lookup per entity.
    let Physics { world, bodies, .. } = physics;
    for (&entity, record) in bodies.iter_mut() {
        let Ok((mut transform, mut velocity, mut sleeping, interpolated)) = query.get_mut(entity)
        else {
            continue;
        };
        let Some(body) = world.body(record.handle) else {
            continue;
        };
        let pose = body.pose();
        record.previous_pose = record.current_pose;
        record.current_pose = pose;
        // An interpolated body's Transform is written once per frame by the interpolation system.
        if !interpolated && !same_pose(pose, record.written_pose) {
            transform.translation = pose.position;
            transform.rotation = pose.rotation;
            record.written_pose = pose;
        }
        let (linear, angular) = (body.linear_velocity(), body.angular_velocity());
        if !same_vec3(linear, record.written_velocity.0)
            || !same_vec3(angular, record.written_velocity.1)
        {
            *velocity = Velocity::new(linear, angular);
            record.written_velocity = (linear, angular);
        }
        let asleep = world.is_sleeping(record.handle).unwrap_or(false);
        if asleep != record.written_sleeping {
            sleeping.0 = asleep;
            record.written_sleeping = asleep;
        }
    }
    for event in physics.world.events() {
        if let Some(event) = physics.to_entities(*event) {
            events.write(event);
        }
    }
    physics.removed_bodies.clear();
    physics.removed_colliders.clear();
}

impl Physics {
    /// A facade event with entities in place of handles (`None` if a handle has no entity: a body or collider
    /// that was never the plugin's).
    fn to_entities(&self, event: Event) -> Option<PhysicsEvent> {
        let body = |handle| {
            self.body_entities
                .get(&handle)
                .or_else(|| self.removed_bodies.get(&handle))
                .copied()
        };
        let collider = |handle| {
            self.collider_entities
                .get(&handle)
                .or_else(|| self.removed_colliders.get(&handle))
                .copied()
        };
        Some(match event {
            Event::ContactForce { colliders, force } => PhysicsEvent::ContactForce {
                entity_a: body(force.body_a)?,
                entity_b: body(force.body_b)?,
                colliders: match colliders {
                    Some((a, b)) => Some((collider(a)?, collider(b)?)),
                    None => None,
                },
                normal: force.normal,
                total_impulse: force.total_impulse,
                total_force: force.total_force,
                max_impulse_point: force.max_impulse_point,
                max_impulse: force.max_impulse,
            },
            Event::ContactBegan {
                body_a,
                body_b,
                approach_speed,
            } => PhysicsEvent::ContactBegan {
                entity_a: body(body_a)?,
                entity_b: body(body_b)?,
                approach_speed,
            },
            Event::ContactEnded { body_a, body_b } => PhysicsEvent::ContactEnded {
                entity_a: body(body_a)?,
                entity_b: body(body_b)?,
            },
            Event::JointBroken { joint } => PhysicsEvent::JointBroken {
                joint: self.joint_entity(joint)?,
            },
            Event::BodyFellAsleep { body: handle } => PhysicsEvent::BodyFellAsleep {
                entity: body(handle)?,
            },
            Event::BodyWoke { body: handle } => PhysicsEvent::BodyWoke {
                entity: body(handle)?,
            },
            Event::BodyQuarantined { body: handle, .. } => PhysicsEvent::BodyQuarantined {
                entity: body(handle)?,
            },
            Event::SensorEntered {
                sensor,
                collider: other,
            } => PhysicsEvent::SensorEntered {
                sensor: collider(sensor)?,
                collider: collider(other)?,
            },
            Event::SensorExited {
                sensor,
                collider: other,
            } => PhysicsEvent::SensorExited {
                sensor: collider(sensor)?,
                collider: collider(other)?,
            },
        })
    }
}
