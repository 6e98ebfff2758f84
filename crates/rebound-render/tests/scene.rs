//! A live world's scene: what is drawn, where, and in which colour.

use rebound::prelude::*;
use rebound_render::{FIXED_COLOUR, PALETTE, RenderScene, SLEEPING_SHADE, body_colour};

#[test]
fn a_world_scene_holds_the_solid_colliders_at_their_poses_with_the_contacts() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).expect("settings");
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .expect("body");
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(5.0, 0.5, 5.0)), ground)
        .expect("collider");
    let ball = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(1.0, 0.5, 0.0)))
        .expect("body");
    let offset = Vec3::new(0.0, 0.0, 0.25);
    world
        .insert_collider(ColliderDesc::ball(0.5), ball)
        .expect("collider");
    // A sensor and a disabled collider are not drawn.
    world
        .insert_collider(ColliderDesc::ball(2.0).with_sensor(true), ball)
        .expect("collider");
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.2))
                .with_position(offset)
                .with_enabled(false),
            ball,
        )
        .expect("collider");
    for _ in 0..30 {
        world.step(1.0 / 60.0);
    }
    // The ball touches the ground: its contact points lie on the ground's top face under the ball.
    let awake = RenderScene::from_world(&world).expect("scene");
    assert!(!awake.contacts.is_empty());
    for contact in &awake.contacts {
        assert!(
            (contact.point - Vec3::new(1.0, 0.0, 0.0)).length() < 0.02,
            "{contact:?}"
        );
        assert!(contact.normal.y.abs() > 0.999);
    }
    for _ in 0..300 {
        world.step(1.0 / 60.0);
    }
    assert_eq!(
        world.is_sleeping(ball),
        Some(true),
        "the ball rests and sleeps"
    );
    let scene = RenderScene::from_world(&world).expect("scene");
    assert_eq!(scene.objects.len(), 2);
    let body = world.body(ball).expect("ball");
    let drawn = scene
        .objects
        .iter()
        .find(|o| o.colour != FIXED_COLOUR)
        .expect("the ball");
    assert!((drawn.pose.position - body.position()).length() < 1e-6);
    let (index, _) = ball.into_raw_parts();
    let expected = PALETTE[index as usize % PALETTE.len()].scaled(SLEEPING_SHADE);
    assert_eq!(drawn.colour, expected);
    assert_eq!(body_colour(index, true, true), expected);
}
