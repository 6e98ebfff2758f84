//! Newton's cradle: five steel balls on ropes, 1 mm apart, perfectly elastic. The first is lifted 30° and
//! released; the impulse passes along the row and the last ball flies off.
//!
//! Run: `cargo run --release --example newtons_cradle [-- --record cradle.rrec --gif cradle.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound::prelude::*;
use rebound_suite::demos::{DT, newtons_cradle};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let newtons_cradle::NewtonsCradle { mut world, balls } = newtons_cradle::build()?;
    let mut output = support::Output::start(&world, &newtons_cradle::ABOUT)?;
    let velocity = |world: &PhysicsWorld, i: usize| {
        world.body(balls[i]).map_or(0.0, |b| b.linear_velocity().x)
    };
    let (length, lift) = (
        newtons_cradle::LENGTH,
        newtons_cradle::LIFT_DEGREES.to_radians(),
    );
    let v0 = (2.0 * 9.81 * length * (1.0 - lift.cos())).sqrt();
    println!("first ball released from 30°: speed at the bottom √(2gL(1 − cos 30°)) = {v0:.3} m/s");
    let mut impact_seen = false;
    for step in 0..newtons_cradle::ABOUT.steps {
        let before = velocity(&world, 0);
        output.step(&mut world, DT)?;
        if !impact_seen && before > 0.5 * v0 && velocity(&world, 0) < 0.5 * before {
            impact_seen = true;
            let v: Vec<String> = (0..5)
                .map(|i| format!("{:+.3}", velocity(&world, i)))
                .collect();
            let total: f32 = (0..5).map(|i| velocity(&world, i)).sum();
            println!(
                "impact at t = {:.2} s: velocities [{}] m/s; the last ball carries {:.1} % of the momentum",
                (step + 1) as f32 / 60.0,
                v.join(", "),
                100.0 * velocity(&world, 4) / total
            );
        }
    }
    for line in output.finish()? {
        println!("{line}");
    }
    Ok(())
}
