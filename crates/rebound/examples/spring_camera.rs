//! A third-person camera on a damped spring: the camera body follows a point behind a moving target, lagging
//! while the target accelerates and overshooting when it stops, as much as its damping ratio allows.
//!
//! Run: `cargo run --release --example spring_camera`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

use rebound::prelude::*;

fn main() -> Result<(), Error> {
    for damping_ratio in [0.3f32, 1.0] {
        let mut world = PhysicsWorld::new(WorldSettings {
            gravity: Vec3::ZERO,
            ..WorldSettings::default()
        })?;
        // The target (a kinematic "player") drives along x; the boom point is 4 m behind and 2 m above it.
        let player = world.insert_body(BodyDesc::kinematic())?;
        let boom = Vec3::new(-4.0, 2.0, 0.0);
        let camera = world.insert_body(
            BodyDesc::dynamic()
                .with_position(boom)
                .with_can_sleep(false),
        )?;
        world.insert_collider(
            ColliderDesc::ball(0.2).with_density(50.0).with_sensor(true),
            camera,
        )?;
        let spring = Joint::new(Spring::new(
            0.0,
            SpringModel::soft_frequency(2.0, damping_ratio)?,
        )?)
        .with_local_anchors(boom, Vec3::ZERO)?;
        world.insert_joint(spring, player, camera)?;

        let (mut max_lag, mut overshoot, mut x) = (0.0f32, 0.0f32, 0.0f32);
        for step in 1..=300 {
            let t = step as f32 / 60.0;
            // Accelerate at 4 m/s² for 2 s, then stop dead and wait 3 s.
            x += if t < 2.0 { 4.0 * t } else { 0.0 } / 60.0;
            world.set_kinematic_target(player, Pose::from_position(Vec3::new(x, 0.0, 0.0)))?;
            world.step(1.0 / 60.0);
            let wanted = Vec3::new(x, 0.0, 0.0) + boom;
            let at = world
                .body(camera)
                .map_or(wanted, rebound::RigidBody::position);
            if t < 2.0 {
                max_lag = max_lag.max(wanted.x - at.x);
            } else {
                overshoot = overshoot.max(at.x - wanted.x);
            }
        }
        println!(
            "camera on a 2 Hz spring, damping ratio {damping_ratio}: largest lag while accelerating {max_lag:.2} m, overshoot after the stop {overshoot:.3} m"
        );
    }
    println!(
        "(the stop is instantaneous, so even the critically damped boom swings past once; the under-damped one further)"
    );
    Ok(())
}
