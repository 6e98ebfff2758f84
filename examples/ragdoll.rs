//! A 15-part ragdoll with human joint ranges (`rebound::ragdoll`) tumbling down six stairs. Prints how far
//! its joints open and pass their limits as it goes, and checks its bounds: no joint opens more than 5 mm, no
//! joint rests past its limits by more than 0.05 rad, and no part ever goes below the stairs' surface.
//!
//! Run: `cargo run --release --example ragdoll [-- --record ragdoll.rrec --gif ragdoll.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound_suite::demos::DT;
use rebound_suite::demos::ragdoll::{self, surface_height};

/// The largest anchor gap any joint may show (m).
const MAX_GAP: f32 = 5e-3;
/// The largest excess over a limit a joint may keep over the last half second (rad).
const MAX_RESTING_EXCESS: f32 = 0.05;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let ragdoll::RagdollStairs { mut world, ragdoll } = ragdoll::build()?;
    let mut output = support::Output::start(&world, &ragdoll::ABOUT)?;
    let steps = ragdoll::ABOUT.steps;
    let (mut worst_gap, mut worst_excess, mut resting_excess) = (0.0f32, 0.0f32, 0.0f32);
    let mut lowest_clearance = f32::INFINITY;
    for step in 1..=steps {
        output.step(&mut world, DT)?;
        let gap = ragdoll.worst_joint_gap(&world);
        let excess = ragdoll.worst_limit_excess(&world);
        worst_gap = worst_gap.max(gap);
        worst_excess = worst_excess.max(excess);
        if step > steps - 30 {
            resting_excess = resting_excess.max(excess);
        }
        for &part in &ragdoll.parts {
            if let Some(body) = world.body(part) {
                let p = body.position();
                lowest_clearance = lowest_clearance.min(p.y - surface_height(p.z));
            }
        }
        if step % 60 == 0 {
            let pelvis = world
                .body(ragdoll.parts[0])
                .map(rebound::RigidBody::position)
                .unwrap_or_default();
            println!(
                "t = {:>3.1} s: pelvis at ({:5.2}, {:5.2}, {:5.2}) m, worst joint gap {:.2} mm, past a limit by {:.3} rad",
                step as f32 * DT,
                pelvis.x,
                pelvis.y,
                pelvis.z,
                gap * 1000.0,
                excess
            );
        }
    }
    println!(
        "whole run: worst joint gap {:.2} mm, worst limit excess {:.3} rad ({:.3} rad over the last half second), \
         lowest part centre {:.3} m above the stairs",
        worst_gap * 1000.0,
        worst_excess,
        resting_excess,
        lowest_clearance
    );
    for line in output.finish()? {
        println!("{line}");
    }
    if worst_gap > MAX_GAP {
        return Err(format!(
            "a joint opened {:.2} mm (bound {} mm)",
            worst_gap * 1000.0,
            MAX_GAP * 1000.0
        )
        .into());
    }
    if resting_excess > MAX_RESTING_EXCESS {
        return Err(format!("a joint rests {resting_excess:.3} rad past its limit").into());
    }
    if lowest_clearance <= 0.0 {
        return Err(format!("a part went {:.3} m below the stairs", -lowest_clearance).into());
    }
    Ok(())
}
