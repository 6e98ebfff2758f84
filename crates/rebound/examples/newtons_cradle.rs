//! Newton's cradle: five steel balls on ropes, 1 mm apart, perfectly elastic. The first is lifted 30° and
//! released; the impulse passes along the row and the last ball flies off.
//!
//! Run: `cargo run --release --example newtons_cradle`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

use rebound::prelude::*;

fn main() -> Result<(), Error> {
    let (radius, length, gap) = (0.1f32, 1.0f32, 0.001f32);
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let mut balls = Vec::new();
    for i in 0..5 {
        let anchor = Vec3::new(i as f32 * (2.0 * radius + gap), 0.0, 0.0);
        let angle = if i == 0 { 30f32.to_radians() } else { 0.0 };
        let start = anchor + Vec3::new(-length * angle.sin(), -length * angle.cos(), 0.0);
        let ball = world.insert_body(BodyDesc::dynamic().with_position(start))?;
        world.insert_collider(
            ColliderDesc::ball(radius)
                .with_density(7800.0)
                .with_restitution(1.0)
                .with_restitution_combine_rule(CombineRule::Max)
                .with_friction(0.0),
            ball,
        )?;
        let rope = Joint::new(Rope::new(length)?).with_local_anchors(anchor, Vec3::ZERO)?;
        world.insert_world_joint(rope, ball)?;
        balls.push(ball);
    }
    let velocity = |world: &PhysicsWorld, i: usize| {
        world.body(balls[i]).map_or(0.0, |b| b.linear_velocity().x)
    };
    let v0 = (2.0 * 9.81 * length * (1.0 - 30f32.to_radians().cos())).sqrt();
    println!("first ball released from 30°: speed at the bottom √(2gL(1 − cos 30°)) = {v0:.3} m/s");
    for step in 0..120 {
        let before = velocity(&world, 0);
        world.step(1.0 / 60.0);
        if before > 0.5 * v0 && velocity(&world, 0) < 0.5 * before {
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
            break;
        }
    }
    Ok(())
}
