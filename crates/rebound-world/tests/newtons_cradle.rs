//! docs/scenes.md "Newton's cradle": five equal balls on ropes in a row, 1 mm apart, C_r = 1; the first lifted 30°
//! and released. After the first impact the last ball must carry ≥ 90 % of the momentum and the first keep
//! ≤ 10 %. A solver that applies restitution only from pre-solve velocities moves the row as one block; the
//! bounce here is an impulse that passes along the row within one Gauss–Seidel pass (Guendelman et al. 2003).

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_constraints::{Joint, Rope};
use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::Vec3;
use rebound_world::testing::SimpleBackend;
use rebound_world::{World, WorldSettings};

const RADIUS: f32 = 0.1;
const LENGTH: f32 = 1.0;
const GAP: f32 = 0.001;

#[test]
fn the_last_ball_carries_the_momentum_after_the_first_impact() {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let mass = MassProperties::ball(1000.0, RADIUS).unwrap();
    let mut balls = Vec::new();
    for i in 0..5 {
        let anchor = Vec3::new(i as f32 * (2.0 * RADIUS + GAP), 0.0, 0.0);
        let angle = if i == 0 { 30f32.to_radians() } else { 0.0 };
        let position = anchor + Vec3::new(-LENGTH * angle.sin(), -LENGTH * angle.cos(), 0.0);
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
    // Speed at the bottom of the swing: √(2gL(1 − cos 30°)).
    let v0 = (2.0 * 9.81 * LENGTH * (1.0 - 30f32.to_radians().cos())).sqrt();
    let momentum =
        |world: &World<SimpleBackend>, i: usize| world.body(balls[i]).unwrap().linear_velocity().x;
    let mut impact = None;
    for step in 0..120 {
        let before = momentum(&world, 0);
        world.step(1.0 / 60.0);
        if before > 0.5 * v0 && momentum(&world, 0) < 0.5 * before {
            impact = Some(step);
            break;
        }
    }
    assert!(impact.is_some(), "the first ball never struck the row");
    let total: f32 = (0..5).map(|i| momentum(&world, i)).sum();
    let first = momentum(&world, 0) / total;
    let last = momentum(&world, 4) / total;
    assert!(
        last >= 0.9,
        "the last ball carries {:.1} % of the momentum",
        100.0 * last
    );
    assert!(
        first.abs() <= 0.1,
        "the first ball keeps {:.1} %",
        100.0 * first
    );
    // And the collision chain is elastic: the last ball leaves at the first ball's impact speed (±3 %; the
    // rope swing accelerates the first ball a little past v0 within the impact step).
    let v_last = momentum(&world, 4);
    assert!(
        (v_last - v0).abs() < 0.03 * v0,
        "last ball leaves at {v_last} m/s, impact speed {v0} m/s"
    );
}
