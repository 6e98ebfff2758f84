//! Rolling back: a snapshot taken mid-run and restored later makes the app replay the same frames bit for bit
//! — the same state digests and the same `Transform`s — through contacts, a joint and a pile of boxes.

use crate::support::{app, bits, physics};
use bevy_ecs::entity::Entity;
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider, PhysicsJoint};

fn transforms(app: &bevy_app::App, entities: &[Entity]) -> Vec<[u32; 7]> {
    entities
        .iter()
        .map(|&e| {
            let t = app.world().get::<Transform>(e).expect("a body entity");
            let (p, q) = (t.translation, t.rotation);
            bits([p.x, p.y, p.z, q.x, q.y, q.z, q.w])
        })
        .collect()
}

#[test]
fn restore_replays_bit_identically() {
    let mut app = app();
    app.world_mut().spawn((
        Body::fixed(),
        Collider::cuboid(Vec3::new(10.0, 0.5, 10.0)),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
    let mut boxes = Vec::new();
    for i in 0..6 {
        let x = (i % 2) as f32 * 0.3;
        let id = app
            .world_mut()
            .spawn((
                Body::dynamic(),
                Collider::cuboid(Vec3::splat(0.4)),
                Transform::from_xyz(x, 0.5 + i as f32 * 0.9, 0.0)
                    .with_rotation(Quat::from_rotation_y(0.2 * i as f32)),
            ))
            .id();
        boxes.push(id);
    }
    app.world_mut().spawn(PhysicsJoint::new(
        Rope::new(2.0).unwrap(),
        boxes[0],
        boxes[5],
    ));
    for _ in 0..30 {
        app.update();
    }
    let state = physics(&app).snapshot();
    let mut digests = Vec::new();
    let mut poses = Vec::new();
    for _ in 0..40 {
        app.update();
        digests.push(physics(&app).state_digest());
        poses.push(transforms(&app, &boxes));
    }
    app.world_mut()
        .resource_mut::<rebound_bevy::Physics>()
        .restore(&state)
        .unwrap();
    for frame in 0..40 {
        app.update();
        assert_eq!(
            physics(&app).state_digest(),
            digests[frame],
            "frame {frame}"
        );
        assert_eq!(transforms(&app, &boxes), poses[frame], "frame {frame}");
    }
    assert_ne!(digests[0], digests[39], "the boxes moved in between");
}
