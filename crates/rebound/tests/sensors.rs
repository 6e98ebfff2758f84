//! Sensors report enter and exit events (at the poses after the step), never push anything, ignore other
//! sensors and filtered groups, and report an exit when the collider inside is removed or disabled.

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

fn sensor_events(world: &PhysicsWorld) -> Vec<Event> {
    world
        .events()
        .iter()
        .copied()
        .filter(|e| matches!(e, Event::SensorEntered { .. } | Event::SensorExited { .. }))
        .collect()
}

#[test]
fn a_falling_ball_enters_and_leaves_a_trigger_without_being_touched() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    // A trigger slab: y in [2, 3].
    let post = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, 2.5, 0.0)))
        .unwrap();
    let trigger = world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(2.0, 0.5, 2.0)).with_sensor(true),
            post,
        )
        .unwrap();
    // A second sensor inside the first, off the ball's path: sensors do not detect each other.
    let other_sensor_body = world
        .insert_body(BodyDesc::kinematic().with_position(Vec3::new(1.5, 2.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.3).with_sensor(true), other_sensor_body)
        .unwrap();
    let ball_body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 4.0, 0.0)))
        .unwrap();
    let ball = world
        .insert_collider(ColliderDesc::ball(0.25), ball_body)
        .unwrap();

    let mut entered = None;
    let mut exited = None;
    for step in 1..=90 {
        world.step(DT);
        let y = world.body(ball_body).unwrap().position().y;
        for event in sensor_events(&world) {
            match event {
                Event::SensorEntered { sensor, collider } => {
                    assert_eq!((sensor, collider), (trigger, ball));
                    assert!(entered.is_none());
                    // The ball's bottom has just crossed the slab's top (y = 3).
                    assert!(y - 0.25 < 3.0, "entered at y = {y}");
                    entered = Some((step, y));
                }
                Event::SensorExited { sensor, collider } => {
                    assert_eq!((sensor, collider), (trigger, ball));
                    assert!(y + 0.25 < 2.0, "exited at y = {y}");
                    exited = Some((step, y));
                }
                _ => {}
            }
        }
        // While inside, the overlap is listed.
        let inside = world.sensor_overlaps().contains(&(trigger, ball));
        assert_eq!(inside, entered.is_some() && exited.is_none());
    }
    println!("entered at {entered:?}, exited at {exited:?} (step, ball centre y)");
    assert!(entered.is_some() && exited.is_some());
    // Free fall all the way through: v = g·t, no contact response from the sensor.
    let v = world.body(ball_body).unwrap().linear_velocity().y;
    assert!(world.contacts().is_empty());
    assert!((v + 9.81 * 1.5).abs() < 0.01, "v = {v}");
}

#[test]
fn removing_or_disabling_the_collider_inside_reports_an_exit() {
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let post = world.insert_body(BodyDesc::fixed()).unwrap();
    let trigger = world
        .insert_collider(
            ColliderDesc::ball(2.0)
                .with_sensor(true)
                .with_groups(CollisionGroups::new(0b001, 0b001)),
            post,
        )
        .unwrap();
    let a_body = world.insert_body(BodyDesc::dynamic()).unwrap();
    let a = world
        .insert_collider(ColliderDesc::ball(0.2), a_body)
        .unwrap();
    let b_body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::X))
        .unwrap();
    let b = world
        .insert_collider(ColliderDesc::ball(0.2), b_body)
        .unwrap();
    // A collider whose filter does not accept the sensor's group is never reported.
    let c_body = world
        .insert_body(BodyDesc::dynamic().with_position(-Vec3::X))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::ball(0.2).with_groups(CollisionGroups::new(0b100, 0b100)),
            c_body,
        )
        .unwrap();

    world.step(DT);
    assert_eq!(
        sensor_events(&world),
        vec![
            Event::SensorEntered {
                sensor: trigger,
                collider: a
            },
            Event::SensorEntered {
                sensor: trigger,
                collider: b
            },
        ]
    );
    world.remove_collider(a).unwrap();
    world.set_collider_enabled(b, false).unwrap();
    world.step(DT);
    assert_eq!(
        sensor_events(&world),
        vec![
            Event::SensorExited {
                sensor: trigger,
                collider: a
            },
            Event::SensorExited {
                sensor: trigger,
                collider: b
            },
        ]
    );
    world.set_collider_enabled(b, true).unwrap();
    world.step(DT);
    assert_eq!(
        sensor_events(&world),
        vec![Event::SensorEntered {
            sensor: trigger,
            collider: b
        }]
    );
    // A sleeping body inside a fixed trigger stays inside without events.
    for _ in 0..120 {
        world.step(DT);
        assert!(sensor_events(&world).is_empty());
    }
    assert_eq!(world.is_sleeping(b_body), Some(true));
    assert_eq!(world.sensor_overlaps(), &[(trigger, b)]);
}

#[test]
fn a_sensor_added_to_a_running_world_reports_what_it_holds() {
    // A world without a sensor steps a while (it skips the sensor pass), then a sensor box is put around a
    // resting ball: the next step reports the ball inside it; the sensor removed, the next step the exit.
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)), ground)
        .unwrap();
    let ball_body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    let ball = world
        .insert_collider(ColliderDesc::ball(0.5), ball_body)
        .unwrap();
    let post = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    for _ in 0..30 {
        world.step(DT);
        assert!(sensor_events(&world).is_empty());
    }
    let cage = world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(2.0)).with_sensor(true),
            post,
        )
        .unwrap();
    world.step(DT);
    assert_eq!(
        sensor_events(&world),
        [Event::SensorEntered {
            sensor: cage,
            collider: ball,
        }]
    );
    assert_eq!(world.sensor_overlaps(), [(cage, ball)]);
    world.remove_collider(cage).unwrap();
    world.step(DT);
    assert_eq!(
        sensor_events(&world),
        [Event::SensorExited {
            sensor: cage,
            collider: ball,
        }]
    );
    assert!(world.sensor_overlaps().is_empty());
}
