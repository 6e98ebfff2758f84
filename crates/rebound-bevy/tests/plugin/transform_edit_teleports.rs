//! A user's edit of a body's `Transform` teleports the body: the world then moves exactly as a facade world
//! whose body was given the same pose between the same steps, and the next writeback starts from there.

use crate::support::{app, bits, body, dt, physics};
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider, Velocity};

#[test]
fn transform_edit_teleports_the_body() {
    let mut app = app();
    let start = Vec3::new(0.0, 10.0, 0.0);
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            Transform::from_translation(start),
        ))
        .id();
    let mut facade = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let handle = facade
        .insert_body(BodyDesc::dynamic().with_position(start))
        .unwrap();
    facade
        .insert_collider(ColliderDesc::ball(0.5), handle)
        .unwrap();
    let dt = dt(&app);
    for _ in 0..10 {
        app.update();
        facade.step(dt);
    }
    let falling = app.world().get::<Velocity>(ball).unwrap().linear.y;
    assert!(falling < -1.0, "falling before the teleport: {falling} m/s");

    let target = Pose::new(Vec3::new(5.0, 20.0, -3.0), Quat::from_rotation_z(0.7));
    {
        let mut transform = app.world_mut().get_mut::<Transform>(ball).unwrap();
        transform.translation = target.position;
        transform.rotation = target.rotation;
    }
    facade.body_mut(handle).unwrap().set_pose(target).unwrap();
    app.update();
    facade.step(dt);
    assert_eq!(physics(&app).state_digest(), facade.state_digest());

    // One step after the teleport: at the target, moved by the kept velocity and a step of gravity.
    let moved = body(&app, ball).unwrap().position();
    assert!(moved.distance(target.position) < 0.1, "teleported: {moved}");
    let transform = app.world().get::<Transform>(ball).unwrap();
    assert_eq!(
        bits(transform.translation.to_array()),
        bits(moved.to_array()),
        "written back"
    );
    for _ in 0..5 {
        app.update();
        facade.step(dt);
    }
    assert_eq!(physics(&app).state_digest(), facade.state_digest());
}

#[test]
fn velocity_edit_sets_the_velocity() {
    let mut app = app();
    let ball = app
        .world_mut()
        .spawn((
            Body::new(BodyDesc::dynamic().with_gravity_scale(0.0)),
            Collider::ball(0.5),
        ))
        .id();
    app.update();
    app.world_mut().get_mut::<Velocity>(ball).unwrap().linear = Vec3::new(2.0, 0.0, 0.0);
    app.update();
    let x = body(&app, ball).unwrap().position().x;
    let expected = 2.0 * dt(&app);
    assert!(
        (x - expected).abs() < 1e-6,
        "x = v·dt without gravity: {x} vs {expected}"
    );
}
