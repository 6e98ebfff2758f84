//! Contact hooks against closed forms: a ball passes up through a one-way platform and lands on it; a box on
//! a conveyor accelerates at μ·g to the belt speed; a box whose points' friction a hook sets to 0 slides as
//! on ice; a filtered pair falls freely; a hook that panics or edits out of range leaves the step as without
//! hooks; hooks run in collider-pair order.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;
use std::sync::Mutex;

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

fn settings() -> WorldSettings {
    WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    }
}

/// A fixed box of half extents `half` whose top face is at y = `top`; returns its collider.
fn slab(world: &mut PhysicsWorld, half: Vec3, top: f32, friction: f32) -> ColliderHandle {
    let body = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, top - half.y, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(half).with_friction(friction), body)
        .unwrap()
}

/// A unit box resting on the top face at y = 0 (centre at 0.5 m), moving at `velocity`.
fn crate_box(
    world: &mut PhysicsWorld,
    velocity: Vec3,
    friction: f32,
) -> (BodyHandle, ColliderHandle) {
    let body = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(0.0, 0.5, 0.0))
                .with_linear_velocity(velocity),
        )
        .unwrap();
    let collider = world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.5)).with_friction(friction),
            body,
        )
        .unwrap();
    (body, collider)
}

/// The highest and the final height of a ball of radius 0.25 m thrown up from y = 0.5 m at the speed that
/// takes it to 3.5 m, under a platform 0.1 m thick whose top is at 2.05 m, over 4 s.
fn throw_at_platform(one_way: bool) -> (f32, f32, usize) {
    let mut world = PhysicsWorld::new(settings()).unwrap();
    let platform = slab(&mut world, Vec3::new(2.0, 0.05, 2.0), 2.05, 0.5);
    if one_way {
        world.set_contact_hooks(OneWayPlatform::new(platform, Vec3::Y).unwrap());
    }
    let v0 = (2.0 * G * 3.0).sqrt();
    let ball = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(0.0, 0.5, 0.0))
                .with_linear_velocity(Vec3::new(0.0, v0, 0.0)),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.25), ball)
        .unwrap();
    let (mut highest, mut failures) = (f32::NEG_INFINITY, 0);
    for _ in 0..240 {
        failures += world.step(DT).hook_failure_count;
        highest = highest.max(world.body(ball).unwrap().position().y);
    }
    (highest, world.body(ball).unwrap().position().y, failures)
}

#[test]
fn a_ball_passes_up_through_a_one_way_platform_and_lands_on_it() {
    // Free flight: apex y0 + v0²/2g = 3.5 m (the integrator's apex is within |v0|·h/2 ≈ 1.6 cm of it).
    let (highest, last, failures) = throw_at_platform(true);
    assert!(
        (highest - 3.5).abs() < 0.03,
        "apex {highest} m, free flight 3.5 m"
    );
    // Then it rests on the top face: centre at 2.05 + 0.25 m.
    assert!(
        (last - 2.30).abs() < 3e-3,
        "rests at {last} m, on the platform 2.30 m"
    );
    assert_eq!(failures, 0);
    // Without the hook the underside stops it: it never gets higher than touching it (1.70 m).
    let (highest, last, _) = throw_at_platform(false);
    assert!(
        highest < 1.70 + 0.01,
        "apex {highest} m under a solid platform"
    );
    assert!(last < 1.0, "falls back to {last} m");
}

#[test]
fn a_box_on_a_conveyor_accelerates_at_mu_g_to_the_belt_speed() {
    let mut world = PhysicsWorld::new(settings()).unwrap();
    let belt = slab(&mut world, Vec3::new(20.0, 0.5, 2.0), 0.0, 0.5);
    let (body, _) = crate_box(&mut world, Vec3::ZERO, 0.5);
    let speed = 2.0;
    world.set_contact_hooks(move |pair: &ContactPair<'_>, contacts: &mut ContactEdit| {
        if pair.involves(belt) {
            contacts.set_surface_velocity(pair, belt, Vec3::new(speed, 0.0, 0.0));
        }
    });
    // Sliding on the belt, friction μ·m·g accelerates the box: v = μ·g·t until v = 2 m/s at t = 0.41 s.
    let mu = 0.5;
    for step in 1..=120 {
        world.step(DT);
        let v = world.body(body).unwrap().linear_velocity();
        let t = step as f32 * DT;
        let expected = (mu * G * t).min(speed);
        if t < 0.35 {
            assert!(
                (v.x - expected).abs() < 0.05 * expected + 0.01,
                "t = {t}: v = {} m/s, μ·g·t = {expected}",
                v.x
            );
        }
        if t > 0.6 {
            assert!(
                (v.x - speed).abs() < 0.01 * speed,
                "t = {t}: v = {v}, belt 2 m/s"
            );
        }
        assert!(v.z.abs() < 1e-3, "no sideways drift: {v}");
    }
}

/// The speed (m/s) of a unit box set sliding at 3 m/s on ground of friction 1.0 after `steps` steps, with
/// or without a hook that sets each of its points' friction to 0, and how far it went (m).
fn slide(frictionless_points: bool, steps: usize) -> (f32, f32) {
    let mut world = PhysicsWorld::new(settings()).unwrap();
    slab(&mut world, Vec3::new(50.0, 0.5, 2.0), 0.0, 1.0);
    let (body, collider) = crate_box(&mut world, Vec3::new(3.0, 0.0, 0.0), 1.0);
    if frictionless_points {
        world.set_contact_hooks(move |pair: &ContactPair<'_>, contacts: &mut ContactEdit| {
            if pair.involves(collider) {
                for point in contacts.points_mut() {
                    point.friction = 0.0;
                }
            }
        });
    }
    for _ in 0..steps {
        world.step(DT);
    }
    let b = world.body(body).unwrap();
    (b.linear_velocity().x, b.position().x)
}

#[test]
fn friction_zero_on_every_point_slides_as_friction_free() {
    // Frictionless: v stays 3 m/s, x = 3·t (1 s: 3 m).
    let (v, x) = slide(true, 60);
    assert!((v - 3.0).abs() < 1e-3, "v = {v} m/s, frictionless 3 m/s");
    assert!((x - 3.0).abs() < 0.01, "x = {x} m, frictionless 3 m");
    // With the ground's friction 1.0 the box stops after v/(μ·g) = 0.31 s, within v²/(2μg) = 0.46 m.
    let (v, x) = slide(false, 60);
    assert!(v.abs() < 1e-3, "stopped: v = {v}");
    assert!(
        (x - 3.0f32.powi(2) / (2.0 * G)).abs() < 0.03,
        "x = {x} m, v²/2μg = 0.46 m"
    );
}

#[test]
fn a_filtered_pair_falls_freely_through_the_ground() {
    struct NoGround(ColliderHandle);
    impl ContactHooks for NoGround {
        fn filter_pair(&self, pair: &ContactPair<'_>) -> bool {
            !pair.involves(self.0)
        }
    }
    let mut world = PhysicsWorld::new(settings()).unwrap();
    let ground = slab(&mut world, Vec3::new(5.0, 0.5, 5.0), 0.0, 0.5);
    world.set_contact_hooks(NoGround(ground));
    let (body, _) = crate_box(&mut world, Vec3::ZERO, 0.5);
    for _ in 0..60 {
        world.step(DT);
    }
    // Falling freely for 1 s from 0.5 m: y = 0.5 − g/2 (within the integrator's g·h·t/2 ≈ 2 cm).
    let y = world.body(body).unwrap().position().y;
    assert!((y - (0.5 - G / 2.0)).abs() < 0.03, "y = {y}");
    assert!(world.contacts().is_empty());
}

#[test]
fn a_panicking_or_out_of_range_hook_leaves_the_step_as_without_hooks() {
    let build = || {
        let mut world = PhysicsWorld::new(settings()).unwrap();
        slab(&mut world, Vec3::new(5.0, 0.5, 5.0), 0.0, 0.5);
        let ball = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 1.0, 0.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::ball(0.5), ball)
            .unwrap();
        world
    };
    struct Panics;
    impl ContactHooks for Panics {
        fn filter_pair(&self, _: &ContactPair<'_>) -> bool {
            panic!("a hook's bug");
        }
        fn modify_contacts(&self, _: &ContactPair<'_>, _: &mut ContactEdit) {
            panic!("another");
        }
    }
    let mut plain = build();
    let mut panicking = build();
    panicking.set_contact_hooks(Panics);
    let mut out_of_range = build();
    out_of_range.set_contact_hooks(|_: &ContactPair<'_>, contacts: &mut ContactEdit| {
        contacts.set_friction(f32::NAN);
        contacts.set_restitution(2.0);
    });
    let (mut panics, mut refusals) = (0, 0);
    for _ in 0..60 {
        plain.step(DT);
        panics += panicking.step(DT).hook_failure_count;
        refusals += out_of_range.step(DT).hook_failure_count;
    }
    // Every step called the filter (1 pair); the steps with contacts called the edit too.
    assert!(panics > 60, "{panics} failures counted");
    assert!(refusals > 0);
    assert_eq!(panicking.state_digest(), plain.state_digest());
    assert_eq!(out_of_range.state_digest(), plain.state_digest());
}

#[test]
fn hooks_run_in_collider_pair_order() {
    let seen = std::sync::Arc::new(Mutex::new(Vec::new()));
    let record = std::sync::Arc::clone(&seen);
    let mut world = PhysicsWorld::new(settings()).unwrap();
    slab(&mut world, Vec3::new(5.0, 0.5, 5.0), 0.0, 0.5);
    for i in 0..6 {
        let ball = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
                i as f32 * 0.9 - 2.0,
                0.5,
                0.0,
            )))
            .unwrap();
        world
            .insert_collider(ColliderDesc::ball(0.5), ball)
            .unwrap();
    }
    world.set_contact_hooks(move |pair: &ContactPair<'_>, _: &mut ContactEdit| {
        record
            .lock()
            .unwrap()
            .push((pair.collider_a, pair.collider_b));
    });
    world.step(DT);
    let seen = seen.lock().unwrap().clone();
    // Six balls on the ground and five touching neighbours: eleven pairs, sorted, each A below B.
    assert_eq!(seen.len(), 11, "{seen:?}");
    assert!(seen.windows(2).all(|w| w[0] < w[1]), "{seen:?}");
    assert!(seen.iter().all(|(a, b)| a < b));
}
