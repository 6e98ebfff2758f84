//! A recorded frame draws as the live world it was taken from: the same segments and triangles, in the
//! same colours, to rounding.

use rebound::prelude::*;
use rebound_debug::{DebugDraw, DebugSettings, draw_frame, draw_world};
use rebound_record::{Recorder, Recording};

fn scene() -> Result<PhysicsWorld, Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let ground = world.insert_body(BodyDesc::fixed())?;
    world.insert_collider(
        ColliderDesc::cuboid(Vec3::new(5.0, 0.5, 5.0)).with_position(Vec3::new(0.0, -0.5, 0.0)),
        ground,
    )?;
    let shapes = [
        ColliderDesc::ball(0.4),
        ColliderDesc::cuboid(Vec3::new(0.3, 0.2, 0.4)).with_rotation(Quat::from_rotation_x(0.4)),
        ColliderDesc::capsule(0.2, 0.3),
        ColliderDesc::cone(0.3, 0.3),
    ];
    for (i, shape) in shapes.into_iter().enumerate() {
        let body = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(
            i as f32 - 1.5,
            1.0,
            0.0,
        )))?;
        world.insert_collider(shape, body)?;
    }
    let bob = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(3.0, 3.0, 0.0)))?;
    world.insert_collider(ColliderDesc::ball(0.1), bob)?;
    let hinge = Joint::new(HingeJoint::new().with_limits(-0.7, 0.7)?)
        .with_local_anchors(Vec3::new(2.0, 3.0, 0.0), Vec3::ZERO)?
        .with_local_axes(Vec3::Z, Vec3::Z)?;
    world.insert_world_joint(hinge, bob)?;
    let slider = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(-3.0, 2.0, 0.0)))?;
    world.insert_collider(ColliderDesc::cuboid(Vec3::splat(0.1)), slider)?;
    let slide = Joint::new(PrismaticJoint::new().with_limits(Limits::new(-1.0, 0.5)?))
        .with_local_anchors(Vec3::new(-3.0, 2.0, 0.0), Vec3::ZERO)?
        .with_local_axes(Vec3::Y, Vec3::Y)?;
    world.insert_world_joint(slide, slider)?;
    Ok(world)
}

/// Every item of `a` has one within `eps` in `b` (same colour and layer), and the counts agree.
fn same_drawing(a: &DebugDraw, b: &DebugDraw, eps: f32) {
    assert_eq!(a.lines.len(), b.lines.len());
    assert_eq!(a.triangles.len(), b.triangles.len());
    for l in &a.lines {
        let found = b.lines.iter().any(|m| {
            m.color == l.color
                && m.layer == l.layer
                && m.a.distance(l.a) < eps
                && m.b.distance(l.b) < eps
        });
        assert!(found, "{l:?} not in the recorded drawing");
    }
    for t in &a.triangles {
        let found = b.triangles.iter().any(|u| {
            u.color == t.color
                && u.vertices
                    .iter()
                    .zip(&t.vertices)
                    .all(|(p, q)| p.distance(*q) < eps)
        });
        assert!(found, "{t:?} not in the recorded drawing");
    }
}

#[test]
fn a_recorded_frame_draws_as_the_live_world() {
    let mut world = scene().unwrap();
    let mut recorder = Recorder::new(&world, Vec::new()).unwrap();
    recorder.record(&world).unwrap();
    for _ in 0..40 {
        recorder.step(&mut world, 1.0 / 60.0).unwrap();
    }
    let recording = Recording::read(recorder.finish().unwrap().as_slice()).unwrap();
    let last = recording.frames().len() - 1;
    let catalog = recording.catalog_at(last).unwrap();
    let settings = DebugSettings::all();
    let live = draw_world(&world, &settings);
    let recorded = draw_frame(&catalog, &recording.frames()[last], &settings);
    assert!(!live.lines.is_empty() && !live.triangles.is_empty());
    assert!(live.lines_of(rebound_debug::Layer::Contact).count() > 0);
    assert!(live.lines_of(rebound_debug::Layer::Joint).count() > 0);
    same_drawing(&live, &recorded, 1e-5);
}
