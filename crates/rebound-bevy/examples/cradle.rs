//! Newton's cradle as Bevy entities: five steel balls on world ropes, 1 mm apart, perfectly elastic. The
//! first is lifted 30° and released; the impulse crosses the row and the last ball swings out. Headless: the
//! schedule runner runs a fixed number of frames, one physics step of 1/64 s each.
//!
//! Run: `cargo run -p rebound-bevy --example cradle`

#![allow(clippy::print_stdout, reason = "an example prints its results")]
#![allow(
    clippy::needless_pass_by_value,
    reason = "Bevy system parameters are passed by value"
)]

use bevy_app::{App, AppExit, ScheduleRunnerPlugin, Update};
use bevy_ecs::prelude::*;
use bevy_time::{TimePlugin, TimeUpdateStrategy};
use bevy_transform::components::Transform;
use core::time::Duration;
use rebound_bevy::prelude::*;

/// Frames to run (2 s).
const FRAMES: u32 = 128;

/// The balls, in order along +x.
#[derive(Resource)]
struct Balls(Vec<Entity>);

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugins((
        ScheduleRunnerPlugin::run_loop(Duration::ZERO),
        TimePlugin,
        ReboundPlugin::default(),
    ))
    .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
    .add_systems(Update, report);
    let (radius, length, gap) = (0.1f32, 1.0f32, 0.001f32);
    let mut balls = Vec::new();
    for i in 0..5 {
        let anchor = Vec3::new(i as f32 * (2.0 * radius + gap), 0.0, 0.0);
        let angle = if i == 0 { 30f32.to_radians() } else { 0.0 };
        let start = anchor + Vec3::new(-length * angle.sin(), -length * angle.cos(), 0.0);
        let steel = ColliderDesc::ball(radius)
            .with_density(7800.0)
            .with_restitution(1.0)
            .with_restitution_combine_rule(CombineRule::Max)
            .with_friction(0.0);
        let ball = app
            .world_mut()
            .spawn((
                Body::dynamic(),
                Collider::new(steel),
                Transform::from_translation(start),
            ))
            .id();
        let rope = Joint::new(Rope::new(length).expect("a positive length"))
            .with_local_anchors(anchor, Vec3::ZERO)
            .expect("finite anchors");
        app.world_mut().spawn(PhysicsJoint::to_world(rope, ball));
        balls.push(ball);
    }
    app.insert_resource(Balls(balls));
    let v0 = (2.0 * 9.81 * length * (1.0 - 30f32.to_radians().cos())).sqrt();
    println!("first ball released from 30°: speed at the bottom √(2gL(1 − cos 30°)) = {v0:.3} m/s");
    app.run()
}

/// Prints the velocities at the impact (when the first ball stops) and ends the app after [`FRAMES`].
fn report(
    balls: Res<'_, Balls>,
    velocities: Query<'_, '_, &Velocity>,
    mut frame: Local<'_, u32>,
    mut reported: Local<'_, bool>,
    mut exit: MessageWriter<'_, AppExit>,
) {
    *frame += 1;
    let vx: Vec<f32> = balls
        .0
        .iter()
        .map(|&e| velocities.get(e).map_or(0.0, |v| v.linear.x))
        .collect();
    let total: f32 = vx.iter().sum();
    if !*reported && vx[4] > 0.5 * total && total > 0.1 {
        *reported = true;
        let shown: Vec<String> = vx.iter().map(|v| format!("{v:+.3}")).collect();
        println!(
            "impact at frame {}: velocities [{}] m/s; the last ball carries {:.1} % of the momentum",
            *frame,
            shown.join(", "),
            100.0 * vx[4] / total
        );
    }
    if *frame >= FRAMES {
        exit.write(AppExit::Success);
    }
}
