//! A 100-link rope chain released horizontally from a fixed point, with a 10× heavier ball at its end: it
//! swings down and hangs. Prints the stretch of the chain as it goes.
//!
//! Run: `cargo run --release --example chain`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

use rebound::prelude::*;

const LINKS: usize = 100;
const LINK: f32 = 0.25;

fn main() -> Result<(), Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let mut balls = Vec::new();
    let mut previous = None;
    for i in 0..LINKS {
        let density = if i == LINKS - 1 { 10_000.0 } else { 1_000.0 };
        let ball = world.insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new((i + 1) as f32 * LINK, 0.0, 0.0))
                .with_can_sleep(false),
        )?;
        world.insert_collider(ColliderDesc::ball(0.1).with_density(density), ball)?;
        let rope = Joint::new(Rope::new(LINK)?);
        match previous {
            None => world.insert_world_joint(rope, ball)?,
            Some(prev) => world.insert_joint(rope, prev, ball)?,
        };
        balls.push(ball);
        previous = Some(ball);
    }
    let stretch = |world: &PhysicsWorld| {
        let mut prev = Vec3::ZERO;
        let (mut worst, mut total) = (0.0f32, 0.0f32);
        for b in &balls {
            let p = world.body(*b).map_or(prev, rebound::RigidBody::position);
            let d = (p - prev).length();
            worst = worst.max(d / LINK - 1.0);
            total += d;
            prev = p;
        }
        (worst, total / (LINK * LINKS as f32) - 1.0)
    };
    let mut worst_run = 0.0f32;
    for step in 1..=600 {
        world.step(1.0 / 60.0);
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
    Ok(())
}
