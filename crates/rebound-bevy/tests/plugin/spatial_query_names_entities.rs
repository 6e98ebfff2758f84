//! `SpatialQuery` in a system answers with entities: a ray straight down from above a ball hits the ball's
//! entity at the distance the geometry gives (10 − 0.5 − 2 m), the ground's when the ball is excluded; an
//! overlap, a point projection, a shape cast and a pick name the same entities.

use crate::support::app;
use bevy_app::Update;
use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;
use bevy_ecs::system::{Res, ResMut};
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider, PhysicsSettings, SpatialQuery, SpatialQueryFilter};

/// The entities of the scene.
#[derive(Resource, Clone, Copy)]
struct Scene {
    ground: Entity,
    ball: Entity,
}

/// What the system found.
#[derive(Resource, Default, Debug)]
struct Found {
    ray: Option<(Entity, Entity, f32)>,
    ray_excluding_ball: Option<Entity>,
    overlap: Vec<Entity>,
    point: Option<(Entity, f32)>,
    shape: Option<(Entity, f32)>,
    pick: Option<Entity>,
}

fn ask(query: SpatialQuery<'_>, scene: Res<'_, Scene>, mut found: ResMut<'_, Found>) {
    let down = -Vec3::Y;
    let top = Vec3::new(0.0, 10.0, 0.0);
    let all = SpatialQueryFilter::default();
    found.ray = query
        .cast_ray(top, down, 100.0, &all)
        .ok()
        .flatten()
        .map(|hit| (hit.collider, hit.body, hit.hit.distance));
    found.ray_excluding_ball = query
        .cast_ray(top, down, 100.0, &all.excluding_body(scene.ball))
        .ok()
        .flatten()
        .map(|hit| hit.body);
    found.overlap = query
        .intersect_shape(
            &ColliderShape::Ball { radius: 0.1 },
            Pose::from_position(Vec3::new(0.0, 2.0, 0.0)),
            &all,
        )
        .unwrap_or_default();
    found.point = query
        .project_point(
            Vec3::new(3.0, 2.0, 0.0),
            f32::INFINITY,
            &all.excluding_body(scene.ground),
        )
        .ok()
        .flatten()
        .map(|hit| (hit.collider, hit.hit.distance));
    found.shape = query
        .cast_shape(
            &ColliderShape::Ball { radius: 0.25 },
            Pose::from_position(Vec3::new(-5.0, 2.0, 0.0)),
            Vec3::X,
            20.0,
            &all,
        )
        .ok()
        .flatten()
        .map(|hit| (hit.body, hit.hit.distance));
    found.pick = query
        .pick(top, down, 100.0)
        .ok()
        .flatten()
        .map(|hit| hit.body);
}

#[test]
fn queries_return_the_entities_hit() {
    let mut app = app();
    let ground = app
        .world_mut()
        .spawn((
            Body::fixed(),
            Collider::cuboid(Vec3::new(10.0, 0.5, 10.0)),
            Transform::from_xyz(0.0, -0.5, 0.0),
        ))
        .id();
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            Transform::from_xyz(0.0, 2.0, 0.0),
        ))
        .id();
    app.insert_resource(Scene { ground, ball });
    app.init_resource::<Found>();
    app.add_systems(Update, ask);
    app.world_mut().resource_mut::<PhysicsSettings>().paused = true;
    app.update();
    app.update();
    let found = app.world().resource::<Found>();
    let (collider, body, distance) = found.ray.unwrap();
    assert_eq!((collider, body), (ball, ball), "{found:?}");
    assert!(
        (distance - 7.5).abs() < 1e-4,
        "top of the ball at y = 2.5: {distance}"
    );
    assert_eq!(found.ray_excluding_ball, Some(ground));
    assert_eq!(found.overlap, [ball]);
    let (entity, distance) = found.point.unwrap();
    assert_eq!(entity, ball);
    assert!(
        (distance - 2.5).abs() < 1e-4,
        "3 m from the centre, 2.5 from the surface: {distance}"
    );
    let (entity, distance) = found.shape.unwrap();
    assert_eq!(entity, ball);
    assert!(
        (distance - 4.25).abs() < 1e-3,
        "5 − 0.5 − 0.25 m: {distance}"
    );
    assert_eq!(found.pick, Some(ball));
}
