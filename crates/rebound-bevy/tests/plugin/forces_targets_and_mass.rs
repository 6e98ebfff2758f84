//! Forces, impulses, kinematic targets, mass overrides and sleep control reach the world with the effect
//! their closed forms give: `Δv = J/m` for an impulse, `v = n·h·F/m` under a held force (symplectic Euler is
//! exact for constant acceleration), a kinematic body at its target after one step, an override's mass in
//! place of the colliders', and `Sleeping` putting a body to sleep and waking it.

use crate::support::{app_with, body, dt, physics};
use bevy_ecs::hierarchy::ChildOf;
use bevy_transform::components::Transform;
use rebound::prelude::*;
use rebound_bevy::prelude::{
    Body, Collider, ExternalForce, ExternalImpulse, KinematicTarget, MassOverride, Sleeping,
    Velocity,
};

fn weightless() -> WorldSettings {
    WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    }
}

#[test]
fn impulse_changes_velocity_by_j_over_m_once() {
    let mut app = app_with(weightless());
    let ball = app
        .world_mut()
        .spawn((Body::dynamic(), Collider::ball(0.5)))
        .id();
    app.update();
    let mass = body(&app, ball).unwrap().mass_properties().mass();
    let expected_mass = 4.0 / 3.0 * core::f32::consts::PI * 0.125;
    assert!(
        (mass - expected_mass).abs() < 1e-5,
        "1 kg/m³ ball of radius 0.5: {mass}"
    );
    let j = Vec3::new(2.0, 0.0, -1.0);
    app.world_mut()
        .entity_mut(ball)
        .insert(ExternalImpulse::new(j));
    app.update();
    let v = app.world().get::<Velocity>(ball).unwrap().linear;
    assert!(v.distance(j / mass) < 1e-5, "Δv = J/m: {v} vs {}", j / mass);
    assert_eq!(
        *app.world().get::<ExternalImpulse>(ball).unwrap(),
        ExternalImpulse::default()
    );
    app.update();
    let again = app.world().get::<Velocity>(ball).unwrap().linear;
    assert!(again.distance(v) < 1e-6, "applied once: {again}");
}

#[test]
fn held_force_accelerates_at_f_over_m() {
    let mut app = app_with(weightless());
    let force = Vec3::new(0.0, 3.0, 0.0);
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            ExternalForce::new(force),
        ))
        .id();
    let steps = 32;
    for _ in 0..steps {
        app.update();
    }
    let mass = body(&app, ball).unwrap().mass_properties().mass();
    let v = app.world().get::<Velocity>(ball).unwrap().linear;
    let expected = force / mass * (steps as f32 * dt(&app));
    assert!(v.distance(expected) < 1e-4, "v = t·F/m: {v} vs {expected}");
}

#[test]
fn kinematic_body_reaches_its_target_in_one_step() {
    let mut app = app_with(weightless());
    let platform = app
        .world_mut()
        .spawn((
            Body::kinematic(),
            Collider::cuboid(Vec3::new(2.0, 0.1, 2.0)),
        ))
        .id();
    app.update();
    let target = KinematicTarget::new(Vec3::new(0.5, 1.0, 0.0), Quat::from_rotation_y(0.3));
    app.world_mut().entity_mut(platform).insert(target);
    app.update();
    let t = app.world().get::<Transform>(platform).unwrap();
    assert!(
        t.translation.distance(target.position) < 1e-5,
        "{}",
        t.translation
    );
    assert!(t.rotation.angle_between(target.rotation) < 1e-4);
    let v = app.world().get::<Velocity>(platform).unwrap().linear;
    assert!(
        v.distance(target.position / dt(&app)) < 1e-3,
        "moved by its velocity: {v}"
    );
}

#[test]
fn mass_override_replaces_the_colliders_mass() {
    let mut app = app_with(weightless());
    let heavy = MassProperties::ball(1.0, 0.5).unwrap();
    let override_mass = MassProperties::new(10.0, Vec3::ZERO, Vec3::splat(1.0)).unwrap();
    let ball = app
        .world_mut()
        .spawn((
            Body::dynamic(),
            Collider::ball(0.5),
            MassOverride(override_mass),
        ))
        .id();
    app.update();
    let mass = body(&app, ball).unwrap().mass_properties().mass();
    assert!((mass - 10.0).abs() < 1e-6, "the override: {mass}");
    // Another collider on a child keeps the override.
    app.world_mut().spawn((
        Collider::ball(0.5),
        Transform::from_xyz(1.0, 0.0, 0.0),
        ChildOf(ball),
    ));
    app.update();
    let mass = body(&app, ball).unwrap().mass_properties().mass();
    assert!((mass - 10.0).abs() < 1e-6, "still the override: {mass}");
    // Without it, the two colliders' mass.
    app.world_mut().entity_mut(ball).remove::<MassOverride>();
    app.update();
    let mass = body(&app, ball).unwrap().mass_properties().mass();
    assert!(
        (mass - 2.0 * heavy.mass()).abs() < 1e-5,
        "two balls' mass: {mass}"
    );
}

#[test]
fn sleeping_component_puts_to_sleep_and_wakes() {
    let mut app = app_with(weightless());
    let ball = app
        .world_mut()
        .spawn((Body::dynamic(), Collider::ball(0.5)))
        .id();
    app.update();
    let handle = physics(&app).body_handle(ball).unwrap();
    assert_eq!(physics(&app).world().is_sleeping(handle), Some(false));
    app.world_mut().get_mut::<Sleeping>(ball).unwrap().0 = true;
    app.update();
    assert_eq!(physics(&app).world().is_sleeping(handle), Some(true));
    app.world_mut().get_mut::<Sleeping>(ball).unwrap().0 = false;
    app.update();
    assert_eq!(physics(&app).world().is_sleeping(handle), Some(false));
}

#[test]
fn child_collider_follows_its_transform() {
    let mut app = app_with(weightless());
    let body_entity = app.world_mut().spawn(Body::dynamic()).id();
    let part = app
        .world_mut()
        .spawn((
            Collider::ball(0.2),
            Transform::from_xyz(1.0, 0.0, 0.0),
            ChildOf(body_entity),
        ))
        .id();
    app.update();
    app.world_mut()
        .get_mut::<Transform>(part)
        .unwrap()
        .translation = Vec3::new(0.0, 2.0, 0.0);
    app.update();
    let handle = physics(&app).collider_handle(part).unwrap();
    let local = physics(&app).world().collider(handle).unwrap().local_pose();
    assert_eq!(
        local.position,
        Vec3::new(0.0, 2.0, 0.0),
        "moved on its body"
    );
}
