//! With `TransformInterpolation`, a frame that ends halfway between two fixed steps (overstep fraction 0.5)
//! shows the midpoint of the body's last two physics poses: the mean position and the half-way rotation.

use crate::support::{app_with, bits, body};
use bevy_time::{Fixed, Time, TimeUpdateStrategy};
use bevy_transform::components::Transform;
use rebound::RigidBody;
use rebound::prelude::*;
use rebound_bevy::interpolate_pose;
use rebound_bevy::prelude::{Body, Collider, TransformInterpolation, Velocity};

#[test]
fn interpolated_transform_at_half_a_step_is_the_midpoint_pose() {
    let mut app = app_with(WorldSettings::default());
    let timestep = app.world().resource::<Time<Fixed>>().timestep();
    // Frames of 1.5 timesteps: the overstep fraction goes 0.5, 0, 0.5, 0, ...
    app.insert_resource(TimeUpdateStrategy::ManualDuration(timestep * 3 / 2));
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            Velocity::new(Vec3::new(3.0, 2.0, 0.0), Vec3::new(0.0, 4.0, 1.0)),
            Transform::from_xyz(0.0, 10.0, 0.0),
            TransformInterpolation,
        ))
        .id();
    let mut previous: Option<Pose> = None;
    let mut current: Option<Pose> = None;
    let mut steps = 0;
    let mut checked = 0;
    for _ in 0..12 {
        app.update();
        let count = crate::support::physics(&app).world().step_count();
        if count > steps {
            // The test sees only the pose after the frame's last step; with one or two steps per frame, keep
            // the pose of the step before from the last frame only when exactly one step ran.
            previous = if count == steps + 1 { current } else { None };
            current = body(&app, ball).map(RigidBody::pose);
            steps = count;
        }
        let alpha = app.world().resource::<Time<Fixed>>().overstep_fraction();
        let (Some(previous), Some(current)) = (previous, current) else {
            continue;
        };
        if (alpha - 0.5).abs() > 1e-6 {
            continue;
        }
        let shown = app.world().get::<Transform>(ball).unwrap();
        let expected = interpolate_pose(previous, current, 0.5);
        assert_eq!(
            bits(shown.translation.to_array()),
            bits(expected.position.to_array())
        );
        assert_eq!(
            bits(shown.rotation.to_array()),
            bits(expected.rotation.to_array())
        );
        let mean = (previous.position + current.position) * 0.5;
        assert!(shown.translation.distance(mean) < 1e-5, "the mean position");
        let to_previous = shown.rotation.angle_between(previous.rotation);
        let to_current = shown.rotation.angle_between(current.rotation);
        assert!(to_previous > 0.01, "the rotation moved between the steps");
        assert!((to_previous - to_current).abs() < 1e-4, "half-way rotation");
        checked += 1;
    }
    assert!(checked >= 3, "frames checked at alpha = 0.5: {checked}");
}
