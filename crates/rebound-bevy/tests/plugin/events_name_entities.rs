//! The step's events reach Bevy as `PhysicsEvent` messages naming the entities involved: the ball and the
//! ground for contacts, the sensor's (child) entity and the ball for sensor overlaps, the ball for sleep, and
//! the joint's entity for a broken joint.

use crate::support::{app, app_with, physics, take_events};
use bevy_ecs::hierarchy::ChildOf;
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider, PhysicsEvent, PhysicsJoint};

#[test]
fn contact_sensor_and_sleep_events_name_the_entities() {
    let mut app = app();
    let ground = app
        .world_mut()
        .spawn((
            Body::fixed(),
            Collider::cuboid(Vec3::new(10.0, 0.5, 10.0)),
            Transform::from_xyz(0.0, -0.5, 0.0),
        ))
        .id();
    let holder = app
        .world_mut()
        .spawn((Body::fixed(), Transform::from_xyz(0.0, 3.0, 0.0)))
        .id();
    let sensor = app
        .world_mut()
        .spawn((
            Collider::new(ColliderDesc::cuboid(Vec3::splat(1.0)).with_sensor(true)),
            Transform::default(),
            ChildOf(holder),
        ))
        .id();
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            Transform::from_xyz(0.0, 6.0, 0.0),
        ))
        .id();
    let mut seen = Vec::new();
    for _ in 0..900 {
        app.update();
        seen.extend(take_events(&mut app));
    }
    let pair = |a, b| {
        move |event: &PhysicsEvent| match *event {
            PhysicsEvent::ContactBegan {
                entity_a, entity_b, ..
            } => (entity_a, entity_b) == (a, b) || (entity_a, entity_b) == (b, a),
            _ => false,
        }
    };
    assert!(
        seen.iter().any(pair(ground, ball)),
        "contact ground-ball: {seen:?}"
    );
    assert!(
        seen.contains(&PhysicsEvent::SensorEntered {
            sensor,
            collider: ball
        }),
        "the ball entered the sensor child: {seen:?}"
    );
    assert!(
        seen.contains(&PhysicsEvent::SensorExited {
            sensor,
            collider: ball
        }),
        "and left it: {seen:?}"
    );
    let entered = seen
        .iter()
        .position(|e| matches!(e, PhysicsEvent::SensorEntered { .. }));
    let touched = seen.iter().position(pair(ground, ball));
    assert!(
        entered < touched,
        "through the sensor before reaching the ground"
    );
    assert!(
        seen.contains(&PhysicsEvent::BodyFellAsleep { entity: ball }),
        "the ball fell asleep at rest: {seen:?}"
    );
}

#[test]
fn broken_joint_event_names_the_joint_entity() {
    let mut app = app();
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            Transform::from_xyz(0.0, 1.0, 0.0),
        ))
        .id();
    // A 1 m rope from the world point (0, 2, 0), taut at once, holding a 0.52 kg ball (5.1 N) and breaking
    // above 1 N.
    let rope = Joint::new(Rope::new(1.0).unwrap())
        .with_local_anchors(Vec3::new(0.0, 2.0, 0.0), Vec3::ZERO)
        .unwrap()
        .with_break_force(1.0)
        .unwrap();
    let joint = app
        .world_mut()
        .spawn(PhysicsJoint::to_world(rope, ball))
        .id();
    let mut seen = Vec::new();
    for _ in 0..10 {
        app.update();
        seen.extend(take_events(&mut app));
    }
    assert!(
        seen.contains(&PhysicsEvent::JointBroken { joint }),
        "the rope broke: {seen:?}"
    );
}

/// A 10 kg box resting on the ground with a force event threshold sends a `ContactForce` message each
/// step naming the ground and the box and their colliders' entities, carrying the box's weight,
/// m·g = 98.1 N (±1 %), with the facade's own numbers.
#[test]
fn contact_force_events_name_the_entities_and_carry_the_weight() {
    let mut app = app_with(WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    });
    let ground = app
        .world_mut()
        .spawn((
            Body::fixed(),
            Collider::cuboid(Vec3::new(10.0, 0.5, 10.0)),
            Transform::from_xyz(0.0, -0.5, 0.0),
        ))
        .id();
    let crate_box = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::new(
                ColliderDesc::cuboid(Vec3::splat(0.5))
                    .with_density(10.0)
                    .with_force_event_threshold(50.0),
            ),
            Transform::from_xyz(0.0, 0.5, 0.0),
        ))
        .id();
    for _ in 0..120 {
        app.update();
    }
    take_events(&mut app);
    for _ in 0..30 {
        app.update();
        let forces: Vec<PhysicsEvent> = take_events(&mut app)
            .into_iter()
            .filter(|e| matches!(e, PhysicsEvent::ContactForce { .. }))
            .collect();
        // Each frame steps the world once (fixed time step): one event per frame.
        assert_eq!(forces.len(), 1, "{forces:?}");
        let PhysicsEvent::ContactForce {
            entity_a,
            entity_b,
            colliders,
            normal,
            total_force,
            total_impulse,
            ..
        } = forces[0]
        else {
            unreachable!("filtered above");
        };
        assert_eq!((entity_a, entity_b), (ground, crate_box));
        assert_eq!(colliders, Some((ground, crate_box)));
        assert!(normal.abs_diff_eq(Vec3::Y, 1e-5), "{normal}");
        assert!((total_force - 98.1).abs() < 0.981, "{total_force} N");
        let facade = physics(&app)
            .world()
            .events()
            .iter()
            .find_map(|e| match *e {
                Event::ContactForce { force, .. } => Some(force),
                _ => None,
            });
        let facade = facade.expect("the facade's event");
        assert_eq!(total_impulse.to_bits(), facade.total_impulse.to_bits());
        assert_eq!(total_force.to_bits(), facade.total_force.to_bits());
    }
}
