//! A 100-link rope chain released horizontally from a fixed point, with a 10× heavier ball at its end: it
//! swings down and hangs. Prints the stretch of the chain as it goes.
//!
//! Run: `cargo run --release --example chain [-- --record chain.rrec --gif chain.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound::prelude::*;
use rebound_suite::demos::{DT, chain};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain::Chain { mut world, balls } = chain::build()?;
    let mut output = support::Output::start(&world, &chain::ABOUT)?;
    let (link, links) = (chain::LINK, chain::LINKS);
    let stretch = |world: &PhysicsWorld| {
        let mut prev = Vec3::ZERO;
        let (mut worst, mut total) = (0.0f32, 0.0f32);
        for b in &balls {
            let p = world.body(*b).map_or(prev, rebound::RigidBody::position);
            let d = (p - prev).length();
            worst = worst.max(d / link - 1.0);
            total += d;
            prev = p;
        }
        (worst, total / (link * links as f32) - 1.0)
    };
    let mut worst_run = 0.0f32;
    for step in 1..=600 {
        output.step(&mut world, DT)?;
        worst_run = worst_run.max(stretch(&world).0);
        if step % 150 == 0 {
            let (worst, total) = stretch(&world);
            let tip = balls
                .last()
                .and_then(|b| world.body(*b))
                .map_or(Vec3::ZERO, rebound::RigidBody::position);
            println!(
                "t = {:>4.1} s: tip at ({:6.2}, {:7.2}) m, total stretch {:+.3} %, worst link {:+.3} %",
                step as f32 / 60.0,
                tip.x,
                tip.y,
                total * 100.0,
                worst * 100.0
            );
        }
    }
    println!(
        "worst link stretch at any step of the swing: {:.2} %",
        worst_run * 100.0
    );
    for line in output.finish()? {
        println!("{line}");
    }
    Ok(())
}
