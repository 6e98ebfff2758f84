//! A car: a chassis on four wheel joints (suspension spring, free axle, rear-wheel drive) driving over a
//! bumpy height field.
//!
//! Run: `cargo run --release --example car [-- --record car.rrec --gif car.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound::prelude::*;
use rebound_suite::demos::{DT, car};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let car::Car {
        mut world,
        chassis,
        wheels,
    } = car::build()?;
    let mut output = support::Output::start(&world, &car::ABOUT)?;
    let (mut max_tilt, mut lowest_wheel) = (0.0f32, f32::INFINITY);
    for step in 1..=600 {
        output.step(&mut world, DT)?;
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
                lowest_wheel = lowest_wheel.min(b.position().y - car::WHEEL_RADIUS);
            }
        }
    }
    println!(
        "largest chassis tilt {:.1}°; lowest wheel bottom {:.2} m (the terrain dips to −0.15 m: the wheels ride on it)",
        max_tilt.to_degrees(),
        lowest_wheel
    );
    println!("drive target: 12 rad/s × 0.4 m = 4.8 m/s");
    for line in output.finish()? {
        println!("{line}");
    }
    Ok(())
}
