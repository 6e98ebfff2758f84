//! A rope bridge: 40 planks on hinges between two anchors, slack, with 10 balls dropped on it.
//!
//! Run: `cargo run --release --example rope_bridge [-- --record bridge.rrec --gif bridge.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound::prelude::*;
use rebound_suite::demos::{DT, rope_bridge};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let bridge = rope_bridge::build()?;
    let mut world = bridge.world;
    let mut output = support::Output::start(&world, &rope_bridge::ABOUT)?;
    let mut max_gap = 0.0f32;
    for _ in 0..rope_bridge::ABOUT.steps {
        output.step(&mut world, DT)?;
        max_gap = max_gap.max(joint_gap(&world, &bridge.joints));
    }
    let lowest = bridge
        .planks
        .iter()
        .filter_map(|p| world.body(*p).map(|b| b.position().y))
        .fold(f32::INFINITY, f32::min);
    let on_bridge = bridge
        .balls
        .iter()
        .filter(|b| {
            world
                .body(**b)
                .is_some_and(|b| b.position().y > lowest - 1.0)
        })
        .count();
    let deck = rope_bridge::PLANKS as f32 * 2.0 * rope_bridge::HALF.x;
    println!(
        "rope bridge: {} planks ({deck:.0} m of deck) on {} hinges between anchors {} m apart",
        rope_bridge::PLANKS,
        bridge.joints.len(),
        rope_bridge::SPAN
    );
    println!(
        "  sag: {:.2} m at the start, {:.2} m with the balls aboard",
        bridge.start_sag,
        rope_bridge::ANCHOR_HEIGHT - lowest
    );
    println!(
        "  largest gap at any hinge over 10 s: {:.2} mm",
        max_gap * 1000.0
    );
    println!(
        "  balls still on the bridge: {on_bridge} of {} (the others rolled off the 1.6 m wide deck)",
        bridge.balls.len()
    );
    for line in output.finish()? {
        println!("{line}");
    }
    Ok(())
}

/// The largest distance between the two world anchor points of any hinge (m).
fn joint_gap(world: &PhysicsWorld, joints: &[JointHandle]) -> f32 {
    let mut worst = 0.0f32;
    for &j in joints {
        let (Some(joint), Some((a, b))) = (world.joint(j), world.joint_bodies(j)) else {
            continue;
        };
        let pb = world.body(b).map_or(Vec3::ZERO, |body| {
            body.pose().transform_point(joint.local_anchor_b())
        });
        let pa = match a {
            Some(a) => world.body(a).map_or(Vec3::ZERO, |body| {
                body.pose().transform_point(joint.local_anchor_a())
            }),
            None => joint.local_anchor_a(),
        };
        worst = worst.max((pa - pb).length());
    }
    worst
}
