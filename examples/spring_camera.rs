//! A third-person camera on a damped spring: the camera body follows a point behind a moving target, lagging
//! while the target accelerates and overshooting when it stops, as much as its damping ratio allows.
//!
//! Run: `cargo run --release --example spring_camera [-- --record camera.rrec --gif camera.gif]` (the files
//! show the first, under-damped run).

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound::prelude::*;
use rebound_suite::demos::{DT, spring_camera};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut written = Vec::new();
    for (run, damping_ratio) in [0.3f32, 1.0].into_iter().enumerate() {
        let spring_camera::SpringCamera {
            mut world,
            player,
            camera,
        } = spring_camera::build(damping_ratio)?;
        let mut output = (run == 0)
            .then(|| support::Output::start(&world, &spring_camera::ABOUT))
            .transpose()?;
        let boom = spring_camera::BOOM;
        let (mut max_lag, mut overshoot, mut x) = (0.0f32, 0.0f32, 0.0f32);
        for step in 1..=300 {
            let t = step as f32 / 60.0;
            // Accelerate at 4 m/s² for 2 s, then stop dead and wait 3 s.
            x += if t < 2.0 { 4.0 * t } else { 0.0 } / 60.0;
            world.set_kinematic_target(player, Pose::from_position(Vec3::new(x, 0.0, 0.0)))?;
            match &mut output {
                Some(output) => {
                    output.step(&mut world, DT)?;
                }
                None => {
                    world.step(DT);
                }
            }
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
        if let Some(output) = output {
            written.extend(output.finish()?);
        }
    }
    println!(
        "(the stop is instantaneous, so even the critically damped boom swings past once; the under-damped one further)"
    );
    for line in written {
        println!("{line}");
    }
    Ok(())
}
