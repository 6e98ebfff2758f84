//! Contacts survive sleep: a ball resting on the ground keeps its manifold in `contacts()` while it sleeps
//! and after it wakes, with no contact end or begin events; a kinematic target on a dynamic body is a typed
//! error that changes nothing.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;
const RADIUS: f32 = 0.5;

/// A ball resting on a fixed box whose top face is at y = 0; returns the world, the ground and the
/// ball.
fn resting_ball() -> (PhysicsWorld, BodyHandle, BodyHandle) {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(5.0, 0.5, 5.0)), ground)
        .unwrap();
    let ball = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, RADIUS + 0.01, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(RADIUS), ball)
        .unwrap();
    (world, ground, ball)
}

fn contact_events(world: &PhysicsWorld) -> Vec<Event> {
    world
        .events()
        .iter()
        .copied()
        .filter(|e| matches!(e, Event::ContactBegan { .. } | Event::ContactEnded { .. }))
        .collect()
}

/// The manifold between `a` and `b` in `contacts()`, if any.
fn manifold(world: &PhysicsWorld, a: BodyHandle, b: BodyHandle) -> Option<ContactManifold> {
    world
        .contacts()
        .iter()
        .find(|m| (m.body_a, m.body_b) == (a, b) || (m.body_a, m.body_b) == (b, a))
        .copied()
}

#[test]
fn a_resting_balls_manifold_stays_across_sleep_and_wake_without_events() {
    let (mut world, ground, ball) = resting_ball();
    // Settle and fall asleep; the first touch gives the one ContactBegan.
    let mut began = 0;
    let mut steps = 0;
    while world.is_sleeping(ball) != Some(true) {
        world.step(DT);
        steps += 1;
        began += contact_events(&world)
            .iter()
            .filter(|e| matches!(e, Event::ContactBegan { .. }))
            .count();
        assert!(steps < 600, "the ball never fell asleep");
    }
    assert_eq!(began, 1);
    let before = manifold(&world, ground, ball).expect("the manifold of the step it fell asleep");
    // Asleep for 2 s: the manifold stays, unchanged, and no contact event is sent.
    for _ in 0..120 {
        world.step(DT);
        assert_eq!(world.is_sleeping(ball), Some(true));
        assert_eq!(contact_events(&world), []);
        assert_eq!(manifold(&world, ground, ball), Some(before));
    }
    // Woken: the contact continues (no ContactBegan with approach speed 0), warm-started from the kept
    // impulses, and it carries the ball's weight: Σ λ_n = m·g·h, the impulse of the last substep of length
    // h = dt / substep_count (to 2 %).
    let mass = world.body(ball).unwrap().mass_properties().mass();
    world.wake_body(ball).unwrap();
    for _ in 0..10 {
        world.step(DT);
        assert_eq!(world.is_sleeping(ball), Some(false));
        assert_eq!(contact_events(&world), []);
        let m = manifold(&world, ground, ball).expect("the manifold after waking");
        let impulse: f32 = m.points().iter().map(|p| p.normal_impulse).sum();
        let weight = mass * 9.81 * DT / world.settings().substep_count as f32;
        assert!(
            (impulse - weight).abs() < 0.02 * weight,
            "Σ λ_n = {impulse}, m·g·dt = {weight}"
        );
    }
    let y = world.body(ball).unwrap().position().y;
    assert!(
        (y - RADIUS).abs() < 2e-3,
        "still resting on the ground: y = {y}"
    );
}

#[test]
fn a_removed_ground_ends_the_contact_of_a_sleeping_ball() {
    let (mut world, ground, ball) = resting_ball();
    while world.is_sleeping(ball) != Some(true) {
        world.step(DT);
    }
    world.step(DT);
    assert!(manifold(&world, ground, ball).is_some());
    world.remove_body(ground).unwrap();
    world.step(DT);
    assert!(manifold(&world, ground, ball).is_none());
    assert!(
        world
            .events()
            .iter()
            .any(|e| matches!(e, Event::ContactEnded { .. }))
    );
}

#[test]
fn a_kinematic_target_on_a_dynamic_or_fixed_body_is_refused_and_changes_nothing() {
    let (mut world, ground, ball) = resting_ball();
    world.step(DT);
    let digest = world.state_digest();
    let target = Pose::from_position(Vec3::new(1.0, 2.0, 3.0));
    for (body, body_type) in [(ball, BodyType::Dynamic), (ground, BodyType::Fixed)] {
        let error = world.set_kinematic_target(body, target).unwrap_err();
        assert!(
            matches!(
                error,
                Error::World(WorldError::NotKinematic { handle, body_type: t })
                    if handle == body && t == body_type
            ),
            "{error}"
        );
        assert!(error.to_string().contains("kinematic target"), "{error}");
    }
    assert_eq!(world.state_digest(), digest);
}
