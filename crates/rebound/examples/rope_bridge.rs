//! A rope bridge: 40 planks on hinges between two anchors, slack, with 10 balls dropped on it.
//!
//! Run: `cargo run --release --example rope_bridge`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

use rebound::prelude::*;

const PLANKS: usize = 40;
const HALF: Vec3 = Vec3::new(0.25, 0.05, 0.8);

fn main() -> Result<(), Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    // 20 m of deck between anchors 19 m apart, so it sags.
    let span = 19.0f32;
    let deck = PLANKS as f32 * 2.0 * HALF.x;
    let (left, right) = (
        Vec3::new(-span / 2.0, 10.0, 0.0),
        Vec3::new(span / 2.0, 10.0, 0.0),
    );
    let hinge = |a: Vec3, b: Vec3| {
        Joint::new(HingeJoint::new())
            .with_local_anchors(a, b)?
            .with_local_axes(Vec3::Z, Vec3::Z)
    };

    // The planks start as the chords of a circular arc through both anchors, so every hinge starts
    // satisfied: R solves 2R·sin(n·asin(a/R)) = span (a = half a plank), by bisection.
    let n = PLANKS as f32;
    let chord = |r: f32| 2.0 * r * (n * (HALF.x / r).asin()).sin() - span;
    let (mut lo, mut hi) = (deck / 3.0, 1000.0f32);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if chord(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let radius = 0.5 * (lo + hi);
    let theta = 2.0 * (HALF.x / radius).asin();
    let half_angle = 0.5 * n * theta;
    let centre_y = 10.0 + radius * half_angle.cos();
    let point = |phi: f32| Vec3::new(radius * phi.sin(), centre_y - radius * phi.cos(), 0.0);

    let mut planks = Vec::new();
    let mut joints = Vec::new();
    for i in 0..PLANKS {
        let (a, b) = (
            point(-half_angle + i as f32 * theta),
            point(-half_angle + (i + 1) as f32 * theta),
        );
        let angle = -half_angle + (i as f32 + 0.5) * theta;
        let plank = world.insert_body(
            BodyDesc::dynamic()
                .with_position((a + b) * 0.5)
                .with_rotation(Quat::from_rotation_z(angle)),
        )?;
        world.insert_collider(
            ColliderDesc::cuboid(HALF)
                .with_density(600.0)
                .with_friction(0.8),
            plank,
        )?;
        let joint = match planks.last() {
            None => world.insert_world_joint(hinge(left, Vec3::new(-HALF.x, 0.0, 0.0))?, plank)?,
            Some(&prev) => world.insert_joint(
                hinge(Vec3::new(HALF.x, 0.0, 0.0), Vec3::new(-HALF.x, 0.0, 0.0))?,
                prev,
                plank,
            )?,
        };
        world.set_joint_contacts_enabled(joint, false)?;
        joints.push(joint);
        planks.push(plank);
    }
    if let Some(&last) = planks.last() {
        joints.push(world.insert_world_joint(hinge(right, Vec3::new(HALF.x, 0.0, 0.0))?, last)?);
    }
    // Let it settle for 3 s, then drop the balls from 1 m above the deck.
    for _ in 0..180 {
        world.step(1.0 / 60.0);
    }
    let mut balls = Vec::new();
    for k in 0..10 {
        let x = -7.0 + k as f32 * 1.5;
        let deck_y = centre_y - (radius * radius - x * x).sqrt();
        let ball = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(
            x,
            deck_y + 1.0,
            0.1 * (k % 3) as f32,
        )))?;
        world.insert_collider(
            ColliderDesc::ball(0.25)
                .with_density(1000.0)
                .with_friction(0.8),
            ball,
        )?;
        balls.push(ball);
    }
    let mut max_gap = 0.0f32;
    for _ in 0..600 {
        world.step(1.0 / 60.0);
        max_gap = max_gap.max(joint_gap(&world, &joints));
    }
    let lowest = planks
        .iter()
        .filter_map(|p| world.body(*p).map(|b| b.position().y))
        .fold(f32::INFINITY, f32::min);
    let on_bridge = balls
        .iter()
        .filter(|b| {
            world
                .body(**b)
                .is_some_and(|b| b.position().y > lowest - 1.0)
        })
        .count();
    println!(
        "rope bridge: {PLANKS} planks ({deck:.0} m of deck) on {} hinges between anchors {span} m apart",
        joints.len()
    );
    println!("  sag with the balls aboard: {:.2} m", 10.0 - lowest);
    println!(
        "  largest gap at any hinge over 10 s: {:.2} mm",
        max_gap * 1000.0
    );
    println!(
        "  balls still on the bridge: {on_bridge} of {} (the others rolled off the 1.6 m wide deck)",
        balls.len()
    );
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
