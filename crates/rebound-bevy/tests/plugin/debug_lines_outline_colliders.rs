//! The debug-render resource holds the world's debug lines after each step while enabled: a box's twelve
//! edges at the box's pose after the step, nothing while disabled.

use crate::support::{app_with, body};
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider, PhysicsDebugRender};
use rebound_bevy::rebound_debug::Layer;

#[test]
fn debug_lines_outline_the_colliders_at_their_poses() {
    let mut app = app_with(WorldSettings::default());
    let half = Vec3::new(0.5, 0.25, 1.0);
    let crate_box = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::cuboid(half),
            Transform::from_xyz(1.0, 3.0, 0.0),
        ))
        .id();
    app.update();
    assert!(
        app.world()
            .resource::<PhysicsDebugRender>()
            .draw
            .lines
            .is_empty(),
        "disabled by default"
    );
    app.world_mut().resource_mut::<PhysicsDebugRender>().enabled = true;
    app.update();
    let debug = app.world().resource::<PhysicsDebugRender>();
    let edges: Vec<_> = debug.draw.lines_of(Layer::Shape).collect();
    assert_eq!(edges.len(), 12, "a box has twelve edges");
    let pose = body(&app, crate_box).unwrap().pose();
    for edge in edges {
        for end in [edge.a, edge.b] {
            let local = pose.inverse_transform_point(end).abs();
            assert!(
                (local - half).abs().max_element() < 1e-4,
                "a corner of the box: {local}"
            );
        }
    }
    app.world_mut().resource_mut::<PhysicsDebugRender>().enabled = false;
    app.update();
    assert!(
        app.world()
            .resource::<PhysicsDebugRender>()
            .draw
            .lines
            .is_empty()
    );
}
