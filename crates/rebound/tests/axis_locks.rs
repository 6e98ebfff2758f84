//! Axis locks are exact: a locked axis's velocity stays `+0.0` bit for bit under contacts and joints, the
//! body stays in its plane, and the free axes follow closed forms (a body locked in y floats at constant
//! height; a pendulum locked to its plane swings at its period). A property test over random locks, poses
//! and pushes.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use proptest::prelude::*;
use rebound::RigidBody;
use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

fn world() -> PhysicsWorld {
    let settings = WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), ground)
        .unwrap();
    world
}

/// Whether every locked component of `body`'s velocities is `+0.0` (bits, not only equal to zero).
fn locked_components_are_zero(body: &RigidBody) -> bool {
    let locks = body.locked_axes();
    let (v, w) = (body.linear_velocity(), body.angular_velocity());
    (0..3).all(|i| {
        (!locks.translation[i] || v[i].to_bits() == 0)
            && (!locks.rotation[i] || w[i].to_bits() == 0)
    })
}

/// A unit box at `position`, turned by `rotation`, moving at `velocity` and spinning at `spin`, with `locks`.
fn add_box(
    world: &mut PhysicsWorld,
    position: Vec3,
    rotation: Quat,
    velocity: Vec3,
    spin: Vec3,
    locks: LockedAxes,
) -> BodyHandle {
    let body = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(position)
                .with_rotation(rotation)
                .with_linear_velocity(velocity)
                .with_angular_velocity(spin)
                .with_locked_axes(locks),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 0.3, 0.4)), body)
        .unwrap();
    body
}

#[test]
fn a_plane_locked_box_tumbling_onto_the_ground_and_a_neighbour_stays_in_its_plane() {
    let mut world = world();
    let tilt = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    let locked = add_box(
        &mut world,
        Vec3::new(0.0, 1.5, 0.25),
        tilt,
        Vec3::new(1.0, 0.0, 2.0),
        Vec3::new(3.0, -2.0, 1.0),
        LockedAxes::PLANE_XY,
    );
    // A free box it lands beside and knocks, off its plane: contacts push it along z and twist it.
    add_box(
        &mut world,
        Vec3::new(0.9, 0.3, 0.0),
        Quat::from_rotation_y(0.4),
        Vec3::ZERO,
        Vec3::ZERO,
        LockedAxes::NONE,
    );
    let z = world.body(locked).unwrap().position().z;
    let mut touched = false;
    for _ in 0..180 {
        world.step(DT);
        let body = world.body(locked).unwrap();
        assert!(locked_components_are_zero(body), "{body:?}");
        assert_eq!(body.position().z.to_bits(), z.to_bits(), "left its plane");
        touched |= world.contacts().len() > 1;
    }
    assert!(touched, "the boxes never met");
    // It came to rest on the ground, still only turned about z from where it started.
    let body = world.body(locked).unwrap();
    assert!(
        body.linear_velocity().length() < 0.05,
        "{:?}",
        body.linear_velocity()
    );
    let turned = body.rotation() * tilt.inverse();
    let (axis, angle) = turned.to_axis_angle();
    assert!(
        angle < 1e-3 || axis.abs_diff_eq(Vec3::Z, 1e-3) || axis.abs_diff_eq(-Vec3::Z, 1e-3),
        "{axis} {angle}"
    );
}

#[test]
fn a_body_locked_in_y_floats_at_its_height_while_pushed_along_x() {
    let mut world = world();
    let locks = LockedAxes {
        translation: [false, true, false],
        ..LockedAxes::NONE
    };
    let body = add_box(
        &mut world,
        Vec3::new(0.0, 3.0, 0.0),
        Quat::IDENTITY,
        Vec3::new(2.0, -5.0, 0.0),
        Vec3::ZERO,
        locks,
    );
    // The creation dropped the locked component of the velocity.
    assert_eq!(world.body(body).unwrap().linear_velocity().y.to_bits(), 0);
    for _ in 0..60 {
        world.step(DT);
    }
    // Gravity cannot move it: y = 3 exactly; along x it coasts: x = 2·t (1 s, to 1e-4).
    let b = world.body(body).unwrap();
    assert_eq!(b.position().y.to_bits(), 3.0f32.to_bits());
    assert!(
        (b.position().x - 2.0).abs() < 1e-4,
        "x = {}",
        b.position().x
    );
}

#[test]
fn a_pendulum_on_a_rod_locked_to_its_plane_swings_in_it_at_its_period() {
    // No ground contact: a small ball on a 1 m rod from a world anchor, displaced in x by a small angle,
    // pushed along z at creation (the lock drops it), not turning; it swings in the x–y plane at
    // T = 2π·√(L/g).
    let settings = WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let length = 1.0;
    let angle: f32 = 0.1;
    let locks = LockedAxes {
        translation: [false, false, true],
        rotation: [true, true, true],
    };
    let bob = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(
                    length * angle.sin(),
                    3.0 - length * angle.cos(),
                    0.0,
                ))
                .with_linear_velocity(Vec3::new(0.0, 0.0, 1.0))
                .with_locked_axes(locks),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.05), bob)
        .unwrap();
    world
        .insert_world_joint(
            Joint::new(Rod::new(length).unwrap())
                .with_local_anchors(Vec3::new(0.0, 3.0, 0.0), Vec3::ZERO)
                .unwrap(),
            bob,
        )
        .unwrap();
    let period = 2.0 * std::f32::consts::PI * (length / 9.81).sqrt();
    // Find the time of the first return to the start side's turning point (x maximal again).
    let mut previous_vx = 0.0f32;
    let mut turning = Vec::new();
    for step in 1..=240 {
        world.step(DT);
        let b = world.body(bob).unwrap();
        assert!(locked_components_are_zero(b), "{b:?}");
        assert_eq!(b.position().z.to_bits(), 0.0f32.to_bits());
        let vx = b.linear_velocity().x;
        if previous_vx < 0.0 && vx >= 0.0 || previous_vx > 0.0 && vx <= 0.0 {
            turning.push(step as f32 * DT);
        }
        previous_vx = vx;
    }
    // Turning points come every half period (small-angle pendulum: +0.06 % at 0.1 rad), to a step.
    assert!(turning.len() >= 3, "{turning:?}");
    let half = (turning[2] - turning[0]) / 2.0;
    assert!(
        (half - period / 2.0).abs() < 1.5 * DT,
        "half period {half} s, T/2 = {}",
        period / 2.0
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn locked_velocity_components_stay_exactly_zero(
        translation in proptest::array::uniform3(any::<bool>()),
        rotation in proptest::array::uniform3(any::<bool>()),
        x in -0.5f32..0.5,
        height in 0.4f32..2.0,
        axis in proptest::array::uniform3(-1.0f32..1.0),
        angle in 0.0f32..3.0,
        velocity in proptest::array::uniform3(-3.0f32..3.0),
        spin in proptest::array::uniform3(-5.0f32..5.0),
    ) {
        let locks = LockedAxes { translation, rotation };
        let mut world = world();
        let axis = Vec3::from_array(axis).try_normalize().unwrap_or(Vec3::X);
        let locked = add_box(
            &mut world,
            Vec3::new(x, height, 0.0),
            Quat::from_axis_angle(axis, angle),
            Vec3::from_array(velocity),
            Vec3::from_array(spin),
            locks,
        );
        // A free neighbour to collide with, and a rope from the world to pull it about.
        add_box(&mut world, Vec3::new(x + 0.8, 0.3, 0.1), Quat::IDENTITY, Vec3::ZERO, Vec3::ZERO, LockedAxes::NONE);
        world
            .insert_world_joint(
                Joint::new(Rope::new(1.5).unwrap())
                    .with_local_anchors(Vec3::new(0.0, 2.5, 0.5), Vec3::new(0.5, 0.3, 0.4))
                    .unwrap(),
                locked,
            )
            .unwrap();
        for _ in 0..90 {
            world.step(DT);
            let body = world.body(locked).unwrap();
            prop_assert!(locked_components_are_zero(body), "{:?}", body);
        }
    }
}
