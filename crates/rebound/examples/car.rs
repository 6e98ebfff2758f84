//! A car: a chassis on four wheel joints (suspension spring, free axle, rear-wheel drive) driving over a
//! bumpy height field.
//!
//! Run: `cargo run --release --example car`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

use rebound::prelude::*;

fn main() -> Result<(), Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;

    // Terrain: 120 m × 20 m, 1 m cells, gentle bumps up to 15 cm.
    let (rows, cols) = (21usize, 121usize);
    let heights: Vec<f32> = (0..rows * cols)
        .map(|i| 0.15 * (0.5 * (i % cols) as f32).sin() * (0.7 * (i / cols) as f32).cos())
        .collect();
    let ground = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(50.0, 0.0, 0.0)))?;
    world.insert_collider(
        ColliderDesc::heightfield(
            rows,
            cols,
            heights,
            Vec3::new((cols - 1) as f32, 1.0, (rows - 1) as f32),
        )
        .with_friction(1.0),
        ground,
    )?;

    let chassis = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 1.2, 0.0)))?;
    world.insert_collider(
        ColliderDesc::cuboid(Vec3::new(1.5, 0.25, 0.8)).with_density(300.0),
        chassis,
    )?;
    let mut wheels = Vec::new();
    for (x, z, driven) in [
        (1.1, 0.9, false),
        (1.1, -0.9, false),
        (-1.1, 0.9, true),
        (-1.1, -0.9, true),
    ] {
        let mount = Vec3::new(x, -0.35, z);
        let wheel = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 1.2, 0.0) + mount))?;
        world.insert_collider(
            ColliderDesc::ball(0.4)
                .with_density(400.0)
                .with_friction(1.0),
            wheel,
        )?;
        let mut kind = WheelJoint::new(SoftSpring::frequency(2.0, 0.7)?)?
            .with_suspension_limits(Limits::new(-0.3, 0.2)?);
        if driven {
            // Spinning about −z rolls the car towards +x; at most 600 N·m per wheel.
            kind = kind.with_motor(Motor::new(-12.0, 600.0)?);
        }
        let joint = Joint::new(kind)
            .with_local_anchors(mount, Vec3::ZERO)?
            .with_local_axes(Vec3::Z, Vec3::Z)?;
        let handle = world.insert_joint(joint, chassis, wheel)?;
        world.set_joint_contacts_enabled(handle, false)?;
        wheels.push(wheel);
    }

    let (mut max_tilt, mut lowest_wheel) = (0.0f32, f32::INFINITY);
    for step in 1..=600 {
        world.step(1.0 / 60.0);
        if let Some(body) = world.body(chassis) {
            max_tilt = max_tilt.max((body.rotation() * Vec3::Y).angle_between(Vec3::Y));
            if step % 120 == 0 {
                println!(
                    "t = {:>4.1} s: chassis at x = {:6.2} m, y = {:.2} m, speed {:.2} m/s",
                    step as f32 / 60.0,
                    body.position().x,
                    body.position().y,
                    body.linear_velocity().length()
                );
            }
        }
        for w in &wheels {
            if let Some(b) = world.body(*w) {
                lowest_wheel = lowest_wheel.min(b.position().y - 0.4);
            }
        }
    }
    println!(
        "largest chassis tilt {:.1}°; lowest wheel bottom {:.2} m (the terrain dips to −0.15 m: the wheels ride on it)",
        max_tilt.to_degrees(),
        lowest_wheel
    );
    println!("drive target: 12 rad/s × 0.4 m = 4.8 m/s");
    Ok(())
}
