//! Drag and drop: a ray from the "mouse" picks a box, a stiff damped spring from the moving cursor to the
//! picked point carries it across the floor and lifts it, then lets it go.
//!
//! Run: `cargo run --release --example drag_and_drop [-- --record drag.rrec --gif drag.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound::prelude::*;
use rebound_suite::demos::{DT, drag_and_drop};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = drag_and_drop::build()?.world;
    let mut output = support::Output::start(&world, &drag_and_drop::ABOUT)?;
    for _ in 0..30 {
        output.step(&mut world, DT)?;
    }

    // The mouse ray from above picks the box.
    let Some(hit) = world.pick_body(Vec3::new(0.2, 10.0, 0.1), -Vec3::Y, 100.0)? else {
        println!("the ray missed the box");
        return Ok(());
    };
    println!(
        "picked the box at {:.2?} ({:.2} m down the ray)",
        hit.point.to_array(),
        hit.distance
    );

    // The cursor is a kinematic body moved by target poses; a 5 Hz critically damped spring joins it to the
    // picked point.
    let cursor = world.insert_body(BodyDesc::kinematic().with_position(hit.point))?;
    let spring = Joint::new(Spring::new(0.0, SpringModel::soft_frequency(5.0, 1.0)?)?)
        .with_local_anchors(Vec3::ZERO, hit.local_point)?;
    let drag = world.insert_joint(spring, cursor, hit.body)?;

    let mut max_lag = 0.0f32;
    for step in 1..=180 {
        let t = step as f32 / 60.0;
        // Right at 2 m/s for 1.5 s while rising to 2 m, then hold.
        let target = hit.point + Vec3::new(2.0 * t.min(1.5), 2.0 * (t / 1.5).min(1.0), 0.0);
        world.set_kinematic_target(cursor, Pose::from_position(target))?;
        output.step(&mut world, DT)?;
        let grabbed = world
            .body(hit.body)
            .map_or(target, |b| b.pose().transform_point(hit.local_point));
        let lag = (grabbed - target).length();
        max_lag = max_lag.max(lag);
        if step % 45 == 0 {
            println!(
                "t = {t:.2} s: cursor at {:.2?}, the grabbed point lags by {lag:.3} m",
                target.to_array()
            );
        }
    }
    world.remove_joint(drag)?;
    let mut fall_time = f32::NAN;
    for step in 1..=180 {
        output.step(&mut world, DT)?;
        if fall_time.is_nan() && world.body(hit.body).is_some_and(|b| b.position().y < 0.51) {
            fall_time = step as f32 / 60.0;
        }
    }
    println!(
        "largest lag while dragging: {max_lag:.3} m; released, the box lands after {fall_time:.2} s"
    );
    for line in output.finish()? {
        println!("{line}");
    }
    Ok(())
}
