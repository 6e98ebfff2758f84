//! A ball entity falls onto a ground entity exactly as the facade's ball does: the same calls give the same
//! world, and the state digests agree bit for bit at every step, bounce and rest included.

use crate::support::{app, bits, dt, physics};
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider};

#[test]
fn ball_entity_matches_facade_ball_bit_for_bit() {
    let mut app = app();
    let ground_pose = Vec3::new(0.0, -0.5, 0.0);
    let start = Vec3::new(0.3, 4.0, -0.2);
    let ground_desc = ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0));
    let ball_desc = ColliderDesc::ball(0.5).with_restitution(0.5);
    app.world_mut().spawn((
        Body::fixed(),
        Collider::new(ground_desc.clone()),
        Transform::from_translation(ground_pose),
    ));
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::new(ball_desc.clone()),
            Transform::from_translation(start),
        ))
        .id();

    // The facade world built with the calls the plugin makes: bodies in entity order, then colliders.
    let mut facade = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground_body = facade
        .insert_body(BodyDesc::fixed().with_position(ground_pose))
        .unwrap();
    let ball_body = facade
        .insert_body(BodyDesc::dynamic().with_position(start))
        .unwrap();
    facade.insert_collider(ground_desc, ground_body).unwrap();
    facade.insert_collider(ball_desc, ball_body).unwrap();

    let dt = dt(&app);
    assert_eq!(
        dt.to_bits(),
        (1.0f32 / 64.0).to_bits(),
        "Bevy's default fixed timestep"
    );
    let mut touched = false;
    for frame in 1..=400 {
        app.update();
        facade.step(dt);
        assert_eq!(
            physics(&app).world().step_count(),
            frame,
            "one step per frame"
        );
        assert_eq!(
            physics(&app).state_digest(),
            facade.state_digest(),
            "digests differ at step {frame}"
        );
        let transform = app.world().get::<Transform>(ball).unwrap();
        let body = facade.body(ball_body).unwrap();
        assert_eq!(
            bits(transform.translation.to_array()),
            bits(body.position().to_array())
        );
        assert_eq!(
            bits(transform.rotation.to_array()),
            bits(body.rotation().to_array())
        );
        touched |= !facade.contacts().is_empty();
    }
    assert!(touched, "the ball reached the ground");
    let y = app.world().get::<Transform>(ball).unwrap().translation.y;
    assert!(
        (y - 0.5).abs() < 0.02,
        "resting on the ground (top at y = 0): {y}"
    );
}
