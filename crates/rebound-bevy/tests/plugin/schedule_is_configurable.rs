//! The world can step in another schedule, and user systems order against the physics sets: a system after
//! `PhysicsSystems::Writeback` sees the pose of the step just taken.

use bevy_app::{App, PostUpdate};
use bevy_ecs::resource::Resource;
use bevy_ecs::schedule::IntoScheduleConfigs;
use bevy_ecs::system::{Query, ResMut};
use bevy_time::{TimePlugin, TimeUpdateStrategy};
use bevy_transform::components::Transform;
use rebound_bevy::prelude::{Body, Collider, Physics, PhysicsSystems, ReboundPlugin};

#[derive(Resource, Default)]
struct Seen(Vec<f32>);

fn record(
    bodies: Query<'_, '_, &Transform, bevy_ecs::query::With<Body>>,
    mut seen: ResMut<'_, Seen>,
) {
    seen.0.extend(bodies.iter().map(|t| t.translation.y));
}

#[test]
fn world_steps_in_the_chosen_schedule_and_sets_order_systems() {
    let mut app = App::new();
    app.add_plugins((TimePlugin, ReboundPlugin::new(PostUpdate)));
    app.insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    app.init_resource::<Seen>();
    app.add_systems(PostUpdate, record.after(PhysicsSystems::Writeback));
    app.update();
    app.world_mut().spawn((
        Body::dynamic(),
        Collider::ball(0.5),
        Transform::from_xyz(0.0, 5.0, 0.0),
    ));
    for _ in 0..3 {
        app.update();
    }
    let physics = app.world().resource::<Physics>();
    assert_eq!(
        physics.world().step_count(),
        3,
        "one step per update in PostUpdate"
    );
    let y = physics
        .world()
        .bodies()
        .iter()
        .map(|(_, b)| b.position().y)
        .next()
        .unwrap();
    let seen = &app.world().resource::<Seen>().0;
    assert_eq!(seen.len(), 3);
    assert_eq!(
        seen[2].to_bits(),
        y.to_bits(),
        "the system saw the step's pose"
    );
    assert!(seen[0] > seen[1] && seen[1] > seen[2], "falling: {seen:?}");
}
