//! A car as Bevy entities: a chassis on four wheel joints (suspension spring, free axle, rear-wheel drive)
//! driving over a bumpy height field. The wheels' colliders are on the wheel entities; the joints live on
//! entities of their own and name chassis and wheel. Headless: the schedule runner runs a fixed number of
//! frames.
//!
//! Run: `cargo run -p rebound-bevy --example drive`

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
use rebound_bevy::rebound;
use rebound_bevy::rebound::SoftSpring;

/// Frames to run (8 s).
const FRAMES: u32 = 512;

/// The chassis.
#[derive(Resource)]
struct Chassis(Entity);

fn main() -> Result<AppExit, rebound::ConstraintError> {
    let mut app = App::new();
    app.add_plugins((
        ScheduleRunnerPlugin::run_loop(Duration::ZERO),
        TimePlugin,
        ReboundPlugin::default(),
    ))
    .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
    .add_systems(Update, report);

    // Terrain: 120 m × 20 m, 1 m cells, gentle bumps up to 15 cm.
    let (rows, cols) = (21usize, 121usize);
    let heights: Vec<f32> = (0..rows * cols)
        .map(|i| 0.15 * (0.5 * (i % cols) as f32).sin() * (0.7 * (i / cols) as f32).cos())
        .collect();
    let terrain = ColliderDesc::heightfield(
        rows,
        cols,
        heights,
        Vec3::new((cols - 1) as f32, 1.0, (rows - 1) as f32),
    )
    .with_friction(1.0);
    app.world_mut().spawn((
        Body::fixed(),
        Collider::new(terrain),
        Transform::from_xyz(50.0, 0.0, 0.0),
    ));

    let origin = Vec3::new(0.0, 1.2, 0.0);
    let chassis = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::new(ColliderDesc::cuboid(Vec3::new(1.5, 0.25, 0.8)).with_density(300.0)),
            Transform::from_translation(origin),
        ))
        .id();
    for (x, z, driven) in [
        (1.1, 0.9, false),
        (1.1, -0.9, false),
        (-1.1, 0.9, true),
        (-1.1, -0.9, true),
    ] {
        let mount = Vec3::new(x, -0.35, z);
        let wheel = app
            .world_mut()
            .spawn((
                Body::dynamic(),
                Collider::new(
                    ColliderDesc::ball(0.4)
                        .with_density(400.0)
                        .with_friction(1.0),
                ),
                Transform::from_translation(origin + mount),
            ))
            .id();
        let mut kind = WheelJoint::new(SoftSpring::frequency(2.0, 0.7)?)?
            .with_suspension_limits(Limits::new(-0.3, 0.2)?);
        if driven {
            // Spinning about −z rolls the car towards +x; at most 600 N·m per wheel.
            kind = kind.with_motor(Motor::new(-12.0, 600.0)?);
        }
        let joint = Joint::new(kind)
            .with_local_anchors(mount, Vec3::ZERO)?
            .with_local_axes(Vec3::Z, Vec3::Z)?;
        app.world_mut()
            .spawn(PhysicsJoint::new(joint, chassis, wheel).with_contacts_enabled(false));
    }
    app.insert_resource(Chassis(chassis));
    println!("drive target: 12 rad/s × 0.4 m wheels = 4.8 m/s");
    Ok(app.run())
}

/// Prints the chassis' position and speed every second; ends the app after [`FRAMES`].
fn report(
    chassis: Res<'_, Chassis>,
    bodies: Query<'_, '_, (&Transform, &Velocity)>,
    mut frame: Local<'_, u32>,
    mut max_tilt: Local<'_, f32>,
    mut exit: MessageWriter<'_, AppExit>,
) {
    *frame += 1;
    let Ok((transform, velocity)) = bodies.get(chassis.0) else {
        return;
    };
    *max_tilt = max_tilt.max((transform.rotation * Vec3::Y).angle_between(Vec3::Y));
    if frame.is_multiple_of(64) {
        println!(
            "t = {:.0} s: chassis at x = {:6.2} m, y = {:.2} m, speed {:.2} m/s",
            *frame as f32 / 64.0,
            transform.translation.x,
            transform.translation.y,
            velocity.linear.length()
        );
    }
    if *frame >= FRAMES {
        println!("largest chassis tilt {:.1}°", max_tilt.to_degrees());
        exit.write(AppExit::Success);
    }
}
