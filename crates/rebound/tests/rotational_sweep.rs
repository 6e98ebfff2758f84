//! Rotational sweep (docs/physics.md, "Contacts", speculative contacts of spinning bodies): a body that turns
//! far within one step still meets what lies in the disc it sweeps, and the sweep creates no energy.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

fn zero_gravity() -> PhysicsWorld {
    PhysicsWorld::new(WorldSettings {
        gravity: Vec3::ZERO,
        sleep_enabled: false,
        ..WorldSettings::default()
    })
    .unwrap()
}

fn kinetic_energy(world: &PhysicsWorld, bodies: &[BodyHandle]) -> f32 {
    bodies
        .iter()
        .map(|&h| {
            let b = world.body(h).unwrap();
            let (v, w) = (b.linear_velocity(), b.angular_velocity());
            let inertia = b.inertia_world();
            0.5 * v.length_squared() / b.inv_mass() + 0.5 * w.dot(inertia * w)
        })
        .sum()
}

/// A plank 2 m long, 2 cm thick and 2 cm wide (10 kg) spinning at 150 rad/s about a short axis — its tips
/// move at 150 m/s, and it turns 143° per step — strikes a resting 1 kg ball of radius 0.1 m at 0.7 m from
/// its axis, in its disc, on its first pass: within the step in which it reaches the ball's bearing (90°,
/// 10.5 ms after the start) or the next, the ball is struck along the plank's motion there (−x, faster than
/// 10 m/s; the plank's face moves at 105 m/s there), and kinetic energy does not grow (within 0.1 %).
/// Frictionless: with friction, the impact step that follows the sweep, in which the plank still turns by 143°,
/// creates energy through contact rows linearised at the start of that step (docs/physics.md, "Rotational
/// sweep"; a limit of the solver, not of the sweep).
#[test]
fn a_spinning_plank_strikes_a_ball_in_its_disc_on_its_first_pass() {
    let mut w = zero_gravity();
    let plank = w
        .insert_body(BodyDesc::dynamic().with_angular_velocity(Vec3::Z * 150.0))
        .unwrap();
    let half = Vec3::new(1.0, 0.01, 0.01);
    let volume = 8.0 * half.x * half.y * half.z;
    w.insert_collider(
        ColliderDesc::cuboid(half)
            .with_density(10.0 / volume)
            .with_friction(0.0),
        plank,
    )
    .unwrap();
    let radius = 0.1;
    let ball = w
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.7, 0.0)))
        .unwrap();
    let ball_volume = 4.0 / 3.0 * core::f32::consts::PI * radius * radius * radius;
    w.insert_collider(
        ColliderDesc::ball(radius)
            .with_density(1.0 / ball_volume)
            .with_friction(0.0),
        ball,
    )
    .unwrap();
    let e0 = kinetic_energy(&w, &[plank, ball]);
    // The plank's long axis reaches the ball's bearing (90°) after 10.5 ms, within the first step. Its
    // first pass is over at 180° − the angle the ball subtends: it must have struck the ball before then.
    let bearing = |w: &PhysicsWorld| {
        let x = w.body(plank).unwrap().rotation() * Vec3::X;
        x.y.atan2(x.x).to_degrees()
    };
    let mut struck_at = None;
    for step in 1..=3 {
        w.step(DT);
        let v = w.body(ball).unwrap().linear_velocity();
        println!(
            "plank: after step {step} the plank is at {:.1}°, ball velocity {v}",
            bearing(&w)
        );
        if v.x < -10.0 {
            struck_at = Some(step);
            break;
        }
    }
    let v = w.body(ball).unwrap().linear_velocity();
    let e1 = kinetic_energy(&w, &[plank, ball]);
    println!("plank: struck at step {struck_at:?}, E/E0 = {}", e1 / e0);
    assert!(
        struck_at.is_some_and(|s| s <= 2),
        "the ball was not struck on the first pass: v = {v} m/s"
    );
    for _ in 0..30 {
        w.step(DT);
        let e = kinetic_energy(&w, &[plank, ball]);
        assert!(
            e <= 1.001 * e0,
            "kinetic energy grew to {} of the start",
            e / e0
        );
    }
    assert!(
        e1 <= 1.001 * e0,
        "kinetic energy grew to {} of the start",
        e1 / e0
    );
}

/// A 0.5 m box thrown at 100 m/s while spinning at 50 rad/s does not pass a fixed wall 1 cm thick: after
/// 1 s its centre is still on the near side, and its kinetic energy never grew (within 0.1 %).
#[test]
fn a_spinning_box_at_100_m_s_does_not_pass_a_1_cm_wall() {
    for axis in [Vec3::Y, Vec3::Z, Vec3::new(0.0, 1.0, 1.0).normalize()] {
        let mut w = zero_gravity();
        let wall = w.insert_body(BodyDesc::fixed()).unwrap();
        w.insert_collider(ColliderDesc::cuboid(Vec3::new(0.005, 3.0, 3.0)), wall)
            .unwrap();
        let cube = w
            .insert_body(
                BodyDesc::dynamic()
                    .with_position(Vec3::new(-4.0, 0.0, 0.0))
                    .with_linear_velocity(Vec3::X * 100.0)
                    .with_angular_velocity(axis * 50.0),
            )
            .unwrap();
        w.insert_collider(ColliderDesc::cuboid(Vec3::splat(0.25)), cube)
            .unwrap();
        let e0 = kinetic_energy(&w, &[cube]);
        let mut farthest = f32::MIN;
        for _ in 0..60 {
            w.step(DT);
            farthest = farthest.max(w.body(cube).unwrap().position().x);
            let e = kinetic_energy(&w, &[cube]);
            assert!(
                e <= 1.001 * e0,
                "axis {axis}: energy grew to {} of the start",
                e / e0
            );
        }
        println!("box spinning about {axis}: farthest centre x = {farthest}");
        assert!(
            farthest < 0.0,
            "axis {axis}: the box passed the wall (x = {farthest})"
        );
    }
}
