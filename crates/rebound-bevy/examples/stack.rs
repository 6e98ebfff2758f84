//! A stack of ten boxes on the ground as Bevy entities: it settles and stays, each box resting half a box
//! above the one below. Headless: the schedule runner runs a fixed number of frames.
//!
//! Run: `cargo run -p rebound-bevy --example stack`

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

/// Frames to run (5 s).
const FRAMES: u32 = 320;
/// Boxes in the stack.
const BOXES: usize = 10;
/// Half the side of a box (m).
const HALF: f32 = 0.5;

/// The boxes, bottom first.
#[derive(Resource)]
struct Stack(Vec<Entity>);

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugins((
        ScheduleRunnerPlugin::run_loop(Duration::ZERO),
        TimePlugin,
        ReboundPlugin::default(),
    ))
    .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
    .add_systems(Update, report);
    app.world_mut().spawn((
        Body::fixed(),
        Collider::cuboid(Vec3::new(20.0, 0.5, 20.0)),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
    let stack = (0..BOXES)
        .map(|i| {
            // A little gap between boxes: they drop onto each other.
            let y = HALF + i as f32 * (2.0 * HALF + 0.01);
            app.world_mut()
                .spawn((
                    Body::dynamic(),
                    Collider::cuboid(Vec3::splat(HALF)),
                    Transform::from_xyz(0.0, y, 0.0),
                ))
                .id()
        })
        .collect();
    app.insert_resource(Stack(stack));
    app.run()
}

/// Prints the top box's height once a second and the drift of every box at the end.
fn report(
    stack: Res<'_, Stack>,
    transforms: Query<'_, '_, &Transform>,
    sleeping: Query<'_, '_, &Sleeping>,
    mut frame: Local<'_, u32>,
    mut exit: MessageWriter<'_, AppExit>,
) {
    *frame += 1;
    let y = |e: Entity| transforms.get(e).map_or(f32::NAN, |t| t.translation.y);
    if frame.is_multiple_of(64) {
        let top = stack.0.last().map_or(f32::NAN, |&e| y(e));
        let asleep = stack
            .0
            .iter()
            .filter(|&&e| sleeping.get(e).is_ok_and(|s| s.0))
            .count();
        println!(
            "t = {:.0} s: top box at y = {top:.3} m; {asleep} of {BOXES} boxes asleep",
            *frame as f32 / 64.0
        );
    }
    if *frame >= FRAMES {
        let worst = stack
            .0
            .iter()
            .enumerate()
            .map(|(i, &e)| (y(e) - (HALF + i as f32 * 2.0 * HALF)).abs())
            .fold(0.0f32, f32::max);
        let sway = stack
            .0
            .iter()
            .map(|&e| {
                transforms.get(e).map_or(f32::NAN, |t| {
                    Vec3::new(t.translation.x, 0.0, t.translation.z).length()
                })
            })
            .fold(0.0f32, f32::max);
        println!(
            "largest height error {worst:.4} m (the resting penetration of ten contacts, summed), largest sideways drift {sway:.4} m"
        );
        exit.write(AppExit::Success);
    }
}
