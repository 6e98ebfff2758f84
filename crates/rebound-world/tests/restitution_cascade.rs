//! Restitution cascades (docs/physics.md, "Restitution"): impulses pass along rows and through racks of
//! touching balls as a chain of two-body elastic collisions would pass them. Newton's cradle with three of
//! five balls lifted sends three out; a 15-ball billiard rack broken at 8 m/s with C_r = 1 and no friction
//! keeps its kinetic energy.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_constraints::{Joint, Rope};
use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::Vec3;
use rebound_world::testing::SimpleBackend;
use rebound_world::{BodyHandle, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;

/// A cradle of five 1 kg-class steel balls (radius 0.1 m) on 1 m ropes, 1 mm apart, C_r = 1; the first
/// `lifted` balls are raised together to 30° and released.
fn cradle(lifted: usize) -> (World<SimpleBackend>, Vec<BodyHandle>) {
    const RADIUS: f32 = 0.1;
    const LENGTH: f32 = 1.0;
    const GAP: f32 = 0.001;
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let mass = MassProperties::ball(1000.0, RADIUS).unwrap();
    let angle = 30f32.to_radians();
    let mut balls = Vec::new();
    for i in 0..5 {
        let anchor = Vec3::new(i as f32 * (2.0 * RADIUS + GAP), 0.0, 0.0);
        // Lifted balls keep their spacing along the arc: each hangs from its own anchor at the same angle.
        let position = if i < lifted {
            anchor + Vec3::new(-LENGTH * angle.sin(), -LENGTH * angle.cos(), 0.0)
        } else {
            anchor - Vec3::Y * LENGTH
        };
        let ball = world
            .insert_body(
                &BodyDesc::dynamic()
                    .with_position(position)
                    .with_mass_properties(mass),
            )
            .unwrap();
        world.backend_mut().add_sphere(ball, RADIUS, 0.0, 1.0);
        let rope = Joint::new(Rope::new(LENGTH).unwrap())
            .with_local_anchors(anchor, Vec3::ZERO)
            .unwrap();
        world.insert_world_joint(rope, ball).unwrap();
        balls.push(ball);
    }
    (world, balls)
}

/// Three balls lifted and released: after the impact, balls 3–5 carry ≥ 85 % of Σ|p| and balls 1–2 ≤ 5 %
/// (a chain of equal elastic collisions hands each ball's momentum on whole: three in, three out).
#[test]
fn a_cradle_with_three_balls_lifted_sends_out_three() {
    let (mut world, balls) = cradle(3);
    let p =
        |world: &World<SimpleBackend>, i: usize| world.body(balls[i]).unwrap().linear_velocity().x;
    // Run until the last ball leaves (its speed peaks), at most 2 s.
    let mut best: Option<[f32; 5]> = None;
    for _ in 0..120 {
        world.step(DT);
        let now: [f32; 5] = core::array::from_fn(|i| p(&world, i));
        if now[4] > 0.05 {
            let peaked = best.is_some_and(|b| now[4] < b[4]);
            if peaked {
                break;
            }
            best = Some(now);
        }
    }
    let momenta = best.expect("the last ball never moved");
    let total: f32 = momenta.iter().map(|v| v.abs()).sum();
    let out: f32 = momenta[2..].iter().map(|v| v.abs()).sum::<f32>() / total;
    let kept: f32 = momenta[..2].iter().map(|v| v.abs()).sum::<f32>() / total;
    println!("three lifted: momenta {momenta:?}, balls 3–5 {out:.3}, balls 1–2 {kept:.3}");
    assert!(out >= 0.85, "balls 3–5 carry {:.1} % of Σ|p|", 100.0 * out);
    assert!(kept <= 0.05, "balls 1–2 keep {:.1} % of Σ|p|", 100.0 * kept);
}

/// A 15-ball rack (radius 28.6 mm, 0.17 kg, touching, in a triangle of five rows) struck by the cue ball
/// at 8 m/s along its axis; no gravity, no friction, C_r = 1. Kinetic energy after the break stays within
/// [0.97, 1.001] of the cue ball's (the collisions are elastic: energy is neither lost nor made).
#[test]
fn a_billiard_break_keeps_its_kinetic_energy() {
    const RADIUS: f32 = 0.028_6;
    const MASS: f32 = 0.17;
    const SPEED: f32 = 8.0;
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = World::with_backend(settings, SimpleBackend::new()).unwrap();
    let density = MASS / (4.0 / 3.0 * core::f32::consts::PI * RADIUS.powi(3));
    let mass = MassProperties::ball(density, RADIUS).unwrap();
    let mut balls = Vec::new();
    let mut add = |world: &mut World<SimpleBackend>, position: Vec3, velocity: Vec3| {
        let ball = world
            .insert_body(
                &BodyDesc::dynamic()
                    .with_position(position)
                    .with_linear_velocity(velocity)
                    .with_mass_properties(mass),
            )
            .unwrap();
        world.backend_mut().add_sphere(ball, RADIUS, 0.0, 1.0);
        balls.push(ball);
    };
    // Rows along +x, touching: row r has r + 1 balls.
    let d = 2.0 * RADIUS;
    for row in 0..5 {
        for k in 0..=row {
            let x = row as f32 * d * 3f32.sqrt() / 2.0;
            let z = (k as f32 - row as f32 / 2.0) * d;
            add(&mut world, Vec3::new(x, 0.0, z), Vec3::ZERO);
        }
    }
    add(&mut world, Vec3::new(-0.5, 0.0, 0.0), Vec3::X * SPEED);
    let energy = |world: &World<SimpleBackend>| -> f32 {
        balls
            .iter()
            .map(|&b| 0.5 * MASS * world.body(b).unwrap().linear_velocity().length_squared())
            .sum()
    };
    let e0 = 0.5 * MASS * SPEED * SPEED;
    let (mut low, mut high) = (f32::MAX, f32::MIN);
    // 1 s: the cue ball reaches the rack at 1/16 s and the rack flies apart.
    for _ in 0..60 {
        world.step(DT);
        let ratio = energy(&world) / e0;
        low = low.min(ratio);
        high = high.max(ratio);
    }
    let end = energy(&world) / e0;
    println!("billiard break: E/E0 in [{low}, {high}], at 1 s {end}");
    assert!(
        low >= 0.97,
        "kinetic energy fell to {low} of the cue ball's"
    );
    assert!(
        high <= 1.001,
        "kinetic energy rose to {high} of the cue ball's"
    );
}
