//! Despawning a body entity removes its body, the colliders on it and on its children, and its joints; a
//! despawned collider or joint entity takes only its own part with it.

use crate::support::{app, physics};
use bevy_ecs::hierarchy::ChildOf;
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider, PhysicsJoint};

fn counts(app: &bevy_app::App) -> (usize, usize, usize) {
    let world = physics(app).world();
    (
        world.bodies().len(),
        world.colliders().len(),
        world.world().joints().count(),
    )
}

#[test]
fn despawning_a_body_removes_its_colliders_and_joints() {
    let mut app = app();
    let anchor = app
        .world_mut()
        .spawn((Body::fixed(), Collider::ball(0.2)))
        .id();
    let car = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::cuboid(Vec3::new(1.0, 0.2, 0.5)),
            Transform::from_xyz(0.0, 2.0, 0.0),
        ))
        .id();
    let child = app
        .world_mut()
        .spawn((
            Collider::ball(0.3),
            Transform::from_xyz(1.0, 0.0, 0.0),
            ChildOf(car),
        ))
        .id();
    let joint = app
        .world_mut()
        .spawn(PhysicsJoint::new(
            Joint::new(Rope::new(3.0).unwrap()),
            anchor,
            car,
        ))
        .id();
    app.update();
    assert_eq!(
        counts(&app),
        (2, 3, 1),
        "two bodies, three colliders, a joint"
    );
    let handle = physics(&app).collider_handle(child).unwrap();
    let on = physics(&app).world().collider(handle).unwrap();
    assert_eq!(
        Some(on.body()),
        physics(&app).body_handle(car),
        "child collider on the parent's body"
    );
    assert_eq!(on.local_pose().position, Vec3::new(1.0, 0.0, 0.0));

    app.world_mut().despawn(car);
    app.update();
    assert_eq!(
        counts(&app),
        (1, 1, 0),
        "the car's body, both its colliders and the joint are gone"
    );
    let physics = physics(&app);
    assert_eq!(physics.body_handle(car), None);
    assert_eq!(physics.collider_handle(child), None);
    assert_eq!(physics.joint_handle(joint), None);
    assert!(physics.body_handle(anchor).is_some());
}

#[test]
fn despawning_a_collider_or_joint_entity_removes_only_it() {
    let mut app = app();
    let a = app
        .world_mut()
        .spawn((Body::fixed(), Collider::ball(0.2)))
        .id();
    let b = app
        .world_mut()
        .spawn((Body::dynamic(), Transform::from_xyz(0.0, -1.0, 0.0)))
        .id();
    let part = app
        .world_mut()
        .spawn((Collider::ball(0.3), Transform::default(), ChildOf(b)))
        .id();
    let joint = app
        .world_mut()
        .spawn(PhysicsJoint::new(Rod::new(1.0).unwrap(), a, b))
        .id();
    app.update();
    assert_eq!(counts(&app), (2, 2, 1));
    app.world_mut().despawn(joint);
    app.update();
    assert_eq!(counts(&app), (2, 2, 0), "only the joint went");
    app.world_mut().despawn(part);
    app.update();
    assert_eq!(counts(&app), (2, 1, 0), "only the child collider went");
}
