//! Contact force events against closed forms: a 10 kg box resting on the ground pushes with its weight,
//! 98.1 N; a dropped ball's bounce applies m·(1 + C_r)·v; a threshold above the force keeps the events
//! away; a negative threshold is refused.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

/// A world without sleep and a fixed ground whose top face is at y = 0, with `restitution`.
fn world_with_ground(restitution: f32) -> (PhysicsWorld, ColliderHandle) {
    let settings = WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    let collider = world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)).with_restitution(restitution),
            ground,
        )
        .unwrap();
    (world, collider)
}

/// The force events of the last step.
fn forces(world: &PhysicsWorld) -> Vec<(Option<(ColliderHandle, ColliderHandle)>, ContactForce)> {
    world
        .events()
        .iter()
        .filter_map(|e| match *e {
            Event::ContactForce { colliders, force } => Some((colliders, force)),
            _ => None,
        })
        .collect()
}

/// A unit box of 10 kg (density 10 kg/m³) resting on the ground, reporting forces from `threshold` N.
fn resting_box(threshold: f32) -> (PhysicsWorld, ColliderHandle, ColliderHandle) {
    let (mut world, ground) = world_with_ground(0.0);
    let body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    let collider = world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.5))
                .with_density(10.0)
                .with_force_event_threshold(threshold),
            body,
        )
        .unwrap();
    (world, ground, collider)
}

#[test]
fn a_10_kg_box_resting_on_the_ground_reports_98_1_newtons() {
    let (mut world, ground, collider) = resting_box(0.0);
    for _ in 0..60 {
        world.step(DT);
    }
    for _ in 0..60 {
        world.step(DT);
        let events = forces(&world);
        assert_eq!(events.len(), 1, "{events:?}");
        let (colliders, force) = events[0];
        assert_eq!(
            colliders,
            Some((ground.min(collider), ground.max(collider)))
        );
        // At rest the contact carries the weight: m·g = 98.1 N, to 1 %.
        assert!(
            (force.total_force - 98.1).abs() < 0.981,
            "F = {} N, m·g = 98.1 N",
            force.total_force
        );
        assert!((force.total_impulse - force.total_force * DT).abs() < 1e-4);
        assert!(
            force.normal.abs_diff_eq(Vec3::Y, 1e-4) || force.normal.abs_diff_eq(-Vec3::Y, 1e-4)
        );
        // Four corners share the load: the largest share lies between a quarter and all of it, at a
        // bottom corner of the box.
        assert!(force.max_impulse >= force.total_impulse / 4.0 - 1e-6);
        assert!(force.max_impulse <= force.total_impulse);
        let p = force.max_impulse_point;
        assert!(
            (p.x.abs() - 0.5).abs() < 1e-2 && (p.z.abs() - 0.5).abs() < 1e-2 && p.y.abs() < 1e-2,
            "{p}"
        );
    }
}

#[test]
fn a_threshold_above_the_force_reports_nothing() {
    let (mut world, _, _) = resting_box(200.0);
    for _ in 0..120 {
        world.step(DT);
        assert_eq!(forces(&world), []);
    }
}

#[test]
fn a_dropped_balls_bounce_applies_m_times_one_plus_restitution_times_v() {
    let restitution = 0.5;
    let (mut world, _) = world_with_ground(restitution);
    let ball = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 2.0, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::ball(0.5)
                .with_restitution(restitution)
                .with_force_event_threshold(0.0),
            ball,
        )
        .unwrap();
    let mass = world.body(ball).unwrap().mass_properties().mass();
    // Falling 1.5 m onto the ground: v = √(2·g·1.5) at impact.
    let v = (2.0 * G * 1.5).sqrt();
    // The impulses of the impact: the events from the first contact until the ball rises again. Gravity
    // acting during the impact step cancels out of the contact's impulse (the bounce is instantaneous).
    let mut impulse = 0.0;
    let mut touched = false;
    for _ in 0..120 {
        world.step(DT);
        let events = forces(&world);
        touched |= !events.is_empty();
        impulse += events.iter().map(|(_, f)| f.total_impulse).sum::<f32>();
        if touched && events.is_empty() {
            break;
        }
    }
    assert!(touched, "the ball never reported a contact force");
    let expected = mass * (1.0 + restitution) * v;
    println!("impact impulse {impulse} N·s, m·(1 + C_r)·v = {expected} N·s");
    assert!(
        (impulse - expected).abs() < 0.03 * expected,
        "J = {impulse} N·s, m·(1 + C_r)·v = {expected} N·s"
    );
}

#[test]
fn a_negative_or_non_finite_threshold_is_refused() {
    let (mut world, _) = world_with_ground(0.0);
    let body = world.insert_body(BodyDesc::dynamic()).unwrap();
    for threshold in [-1.0, f32::NAN, f32::INFINITY] {
        let error = world
            .insert_collider(
                ColliderDesc::ball(0.5).with_force_event_threshold(threshold),
                body,
            )
            .unwrap_err();
        assert!(
            error.to_string().contains("force_event_threshold"),
            "{error}"
        );
    }
    assert!(world.world().backend().colliders().iter().count() == 1);
}

#[test]
fn a_collider_with_a_threshold_added_to_a_running_world_reports_its_forces() {
    // A world without thresholds steps a while (its narrow phase skips the force bookkeeping), then a 10 kg
    // box reporting from 0 N is put on the ground: once at rest it reports its weight, 98.1 N to 1 %, and
    // the box without a threshold beside it reports nothing.
    let (mut world, ground) = world_with_ground(0.0);
    let plain = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(-3.0, 0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.5)).with_density(10.0),
            plain,
        )
        .unwrap();
    for _ in 0..30 {
        world.step(DT);
        assert!(forces(&world).is_empty());
    }
    let body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(3.0, 0.5, 0.0)))
        .unwrap();
    let reporting = world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.5))
                .with_density(10.0)
                .with_force_event_threshold(0.0),
            body,
        )
        .unwrap();
    for _ in 0..60 {
        world.step(DT);
    }
    let events = forces(&world);
    assert_eq!(events.len(), 1, "{events:?}");
    let (colliders, force) = events[0];
    assert_eq!(
        colliders,
        Some((ground.min(reporting), ground.max(reporting)))
    );
    assert!(
        (force.total_force - 98.1).abs() < 0.981,
        "{}",
        force.total_force
    );
    world.remove_collider(reporting).unwrap();
    world.step(DT);
    assert!(forces(&world).is_empty());
}
