//! Bad component values are typed errors, not panics, and the world keeps what it had: a NaN position, a
//! negative radius, a joint naming an entity without a body, a NaN velocity edit, a non-unit rotation.
//! Settings past their upper bounds are refused too. The world is paused while the bad edits arrive, so
//! "unchanged" is checked with the state digest.

use crate::support::{app, physics, take_errors};
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{
    Body, Collider, PhysicsError, PhysicsJoint, PhysicsSettings, Velocity,
};

#[test]
fn refused_values_are_reported_and_change_nothing() {
    let mut app = app();
    let good = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            Transform::from_xyz(0.0, 3.0, 0.0),
        ))
        .id();
    app.update();
    app.world_mut().resource_mut::<PhysicsSettings>().paused = true;
    app.update();
    take_errors(&mut app);
    let digest = physics(&app).state_digest();
    let counts = |app: &bevy_app::App| {
        let world = physics(app).world();
        (
            world.bodies().len(),
            world.colliders().len(),
            world.world().joints().count(),
        )
    };
    assert_eq!(counts(&app), (1, 1, 0));

    // A body at a NaN position.
    let nan_body = app
        .world_mut()
        .spawn((Body::dynamic(), Transform::from_xyz(f32::NAN, 0.0, 0.0)))
        .id();
    // A ball of negative radius on the good body.
    app.world_mut()
        .entity_mut(good)
        .insert(Collider::ball(-1.0));
    // A joint to an entity that has no body.
    let nobody = app.world_mut().spawn(Transform::default()).id();
    let joint = app
        .world_mut()
        .spawn(PhysicsJoint::new(Rope::new(1.0).unwrap(), good, nobody))
        .id();
    app.update();
    let errors = take_errors(&mut app);
    assert!(
        errors.iter().any(|e| matches!(e,
            PhysicsError::Refused { entity, component: "Body", .. } if *entity == nan_body)),
        "{errors:?}"
    );
    assert!(
        errors.iter().any(|e| matches!(e,
            PhysicsError::Refused { entity, component: "Collider", .. } if *entity == good)),
        "{errors:?}"
    );
    assert!(
        errors.contains(&PhysicsError::NotABody {
            entity: joint,
            field: "body_b",
            target: nobody
        }),
        "{errors:?}"
    );
    assert_eq!(
        counts(&app),
        (1, 1, 0),
        "nothing added, the old collider kept"
    );
    assert_eq!(physics(&app).state_digest(), digest);
    let message = errors[0].to_string();
    assert!(
        message.contains("position") || message.contains("radius"),
        "{message}"
    );

    // Edits of the good body: a NaN velocity, then a non-unit rotation.
    app.world_mut().get_mut::<Velocity>(good).unwrap().linear = Vec3::new(0.0, f32::NAN, 0.0);
    app.update();
    app.world_mut().get_mut::<Transform>(good).unwrap().rotation =
        Quat::from_xyzw(0.0, 0.0, 0.0, 2.0);
    app.update();
    let errors = take_errors(&mut app);
    let components: Vec<&str> = errors
        .iter()
        .filter_map(|e| match e {
            PhysicsError::Refused { component, .. } => Some(*component),
            _ => None,
        })
        .collect();
    assert_eq!(components, ["Velocity", "Transform"], "{errors:?}");
    assert_eq!(
        physics(&app).state_digest(),
        digest,
        "the world is unchanged"
    );
    // Refused once, not at every step.
    app.update();
    assert!(take_errors(&mut app).is_empty());

    // Invalid world settings are refused too; the old ones stay.
    let before = *physics(&app).world().settings();
    app.world_mut()
        .resource_mut::<PhysicsSettings>()
        .world
        .substep_count = 0;
    app.update();
    let errors = take_errors(&mut app);
    assert!(
        matches!(errors.as_slice(), [PhysicsError::Settings(_)]),
        "{errors:?}"
    );
    assert_eq!(*physics(&app).world().settings(), before);

    // So are counts and rates past their upper bounds, which would make one step never return.
    let mut joints = before.joints;
    joints.solve_iterations = u32::MAX;
    for world in [
        WorldSettings {
            substep_count: u32::MAX,
            ..before
        },
        WorldSettings { joints, ..before },
        WorldSettings {
            fixed_dt: 1e-30,
            max_steps_per_advance: u32::MAX,
            ..before
        },
    ] {
        app.world_mut().resource_mut::<PhysicsSettings>().world = world;
        app.update();
        let errors = take_errors(&mut app);
        assert!(
            matches!(errors.as_slice(), [PhysicsError::Settings(_)]),
            "{errors:?}"
        );
        assert_eq!(*physics(&app).world().settings(), before);
    }
    assert_eq!(
        physics(&app).state_digest(),
        digest,
        "the world is unchanged"
    );
}

/// A `Body` whose description sets what another component gives (here the position, which is the
/// `Transform`'s) is refused at the door, naming the field, its value and that component; nothing is
/// inserted. Its integrator and locked axes, which only the description gives, reach the world.
#[test]
fn a_body_description_that_sets_a_pose_is_refused_naming_the_field() {
    let mut app = app();
    let posed = app
        .world_mut()
        .spawn(Body::new(
            BodyDesc::dynamic().with_position(Vec3::new(1.0, 2.0, 3.0)),
        ))
        .id();
    app.update();
    let errors = take_errors(&mut app);
    assert!(
        errors.iter().any(|e| matches!(e,
            PhysicsError::BodyField { entity, field: "position", component: "Transform", value }
                if *entity == posed && value.contains('2'))),
        "{errors:?}"
    );
    assert_eq!(physics(&app).world().bodies().len(), 0);
    let locked = LockedAxes::ALL_ROTATION;
    let upright = app
        .world_mut()
        .spawn(Body::new(
            BodyDesc::dynamic()
                .with_locked_axes(locked)
                .with_integrator(rebound::Integrator::ExplicitEuler),
        ))
        .id();
    app.update();
    assert!(take_errors(&mut app).is_empty());
    let handle = physics(&app).body_handle(upright).unwrap();
    let body = physics(&app).world().body(handle).unwrap();
    assert_eq!(body.locked_axes(), locked);
    assert_eq!(body.integrator(), rebound::Integrator::ExplicitEuler);
}
