//! Validation at the facade's doors: a deserialised collider description is checked as
//! [`PhysicsWorld::insert_collider`] checks it; a snapshot whose colliders, own masses or joints without
//! contacts refer to nothing in it, or whose world part is invalid, is refused whole with a typed error
//! naming the item, and the world is unchanged; settings above their bounds and too short a step are refused
//! or skipped here too.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

mod support;

use rebound::prelude::*;
use rebound::{MathError, StepSkipped};
use serde_json::{Value, json};
use support::{ball, fixed_box};

const DT: f32 = 1.0 / 60.0;

/// A ball on a fixed box, a second ball held to the first by a rope, both balls with their own mass.
fn scene() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    fixed_box(&mut world, Vec3::ZERO, Vec3::new(5.0, 0.5, 5.0));
    let ball = ball(
        &mut world,
        Vec3::new(0.0, 1.0, 0.0),
        0.5,
        Vec3::ZERO,
        Vec3::ZERO,
    );
    let other = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(2.0, 1.0, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.5).with_density(0.0), other)
        .unwrap();
    world
        .set_body_mass_properties(other, MassProperties::ball(500.0, 0.5).unwrap())
        .unwrap();
    world
        .insert_joint(Rope::new(3.0).unwrap(), ball, other)
        .unwrap();
    for _ in 0..10 {
        world.step(DT);
    }
    world
}

/// The digest and the JSON of the full snapshot: what "nothing changed" compares.
fn state(world: &PhysicsWorld) -> (u64, String) {
    (
        world.state_digest(),
        serde_json::to_string(&world.snapshot()).unwrap(),
    )
}

#[test]
fn a_deserialised_collider_description_is_checked_as_insertion_checks_it() {
    let good = serde_json::to_value(ColliderDesc::ball(0.5)).unwrap();
    for (field, bad, message) in [
        ("friction", json!(-1.0), "`friction` must be >= 0, got -1"),
        ("density", json!(1e39), "`density` must be finite"),
        ("restitution", json!(2.0), "`restitution`"),
        (
            "rolling_friction",
            json!(-0.5),
            "`rolling_friction` must be >= 0",
        ),
    ] {
        let mut value = good.clone();
        value[field] = bad;
        let error = serde_json::from_value::<ColliderDesc>(value).unwrap_err();
        assert!(error.to_string().contains(message), "{field}: {error}");
    }
    let mut value = good.clone();
    value["local_pose"]["rotation"] = json!([0.0, 0.0, 0.0, 2.0]);
    let error = serde_json::from_value::<ColliderDesc>(value).unwrap_err();
    assert!(error.to_string().contains("`local_pose`"), "{error}");
    assert_eq!(
        serde_json::from_value::<ColliderDesc>(good).unwrap(),
        ColliderDesc::ball(0.5)
    );
}

/// The snapshot of `world` as JSON, edited by `edit`, read back.
fn edited(world: &PhysicsWorld, edit: impl FnOnce(&mut Value)) -> PhysicsSnapshot {
    let mut value = serde_json::to_value(world.snapshot()).unwrap();
    edit(&mut value);
    serde_json::from_value(value).unwrap()
}

/// The first occupied slot's value of a serialised arena.
fn first_occupied(arena: &mut Value) -> &mut Value {
    let slots = arena["slots"].as_array_mut().unwrap();
    let slot = slots
        .iter_mut()
        .find(|s| s.get("Occupied").is_some())
        .unwrap();
    &mut slot["Occupied"]["value"]
}

#[test]
fn restore_refuses_a_snapshot_that_refers_to_nothing_and_changes_nothing() {
    let mut world = scene();
    let before = state(&world);
    let nowhere = json!({"index": 99, "generation": 3});

    // A collider on a body that does not exist.
    let snapshot = edited(&world, |v| {
        first_occupied(&mut v["colliders"])["body"] = nowhere.clone();
    });
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        matches!(&error, Error::InvalidSnapshot { item, source }
            if item == "collider 0" && matches!(**source, Error::World(WorldError::StaleBody(_)))),
        "{error:?}"
    );
    assert!(
        error
            .to_string()
            .contains("collider 0: stale or foreign body handle"),
        "{error}"
    );

    // Own mass properties of a body that does not exist.
    let snapshot = edited(&world, |v| v["own_mass"][0][0] = nowhere.clone());
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        matches!(&error, Error::InvalidSnapshot { item, .. } if item == "own mass properties"),
        "{error:?}"
    );

    // A collider with a negative radius: the shape is checked where it is built.
    let snapshot = edited(&world, |v| {
        let desc = &mut first_occupied(&mut v["colliders"])["desc"];
        desc["shape"] = json!({"Ball": {"radius": -0.3}});
    });
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        matches!(&error, Error::InvalidSnapshot { item, source }
            if item == "collider 0" && matches!(**source, Error::Shape(ShapeError::Math(MathError::NotPositive { field: "radius", .. })))),
        "{error:?}"
    );

    // The world's own part: a manifold point with an infinite impulse.
    let snapshot = edited(&world, |v| {
        v["world"]["state"]["manifolds"][0]["points"][0]["normal_impulse"] = json!(1e39);
    });
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        matches!(&error, Error::World(WorldError::InvalidSnapshot { item, .. }) if item == "manifold 0, point 0"),
        "{error:?}"
    );
    // A negative accumulator.
    let snapshot = edited(&world, |v| v["accumulator"] = json!(-1.0));
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        error.to_string().contains("`accumulator` must be >= 0"),
        "{error}"
    );

    assert!(
        state(&world) == before,
        "no refused snapshot changed the world"
    );
    // A good one still restores.
    world.restore(&world.snapshot()).unwrap();
    world.step(DT);
}

#[test]
fn a_snapshot_with_an_unusable_mass_does_not_load() {
    let world = scene();
    let mut value = serde_json::to_value(world.snapshot()).unwrap();
    value["own_mass"][0][1]["mass"] = json!(0.0);
    let error = serde_json::from_value::<PhysicsSnapshot>(value).unwrap_err();
    assert!(
        error.to_string().contains("`mass` must be > 0, got 0"),
        "{error}"
    );
}

#[test]
fn settings_bounds_and_the_shortest_step_hold_at_the_facade() {
    let mut world = scene();
    let before = state(&world);
    for settings in [
        WorldSettings {
            substep_count: u32::MAX,
            ..WorldSettings::default()
        },
        WorldSettings {
            max_steps_per_advance: u32::MAX,
            fixed_dt: 1e-30,
            ..WorldSettings::default()
        },
    ] {
        assert!(PhysicsWorld::new(settings).is_err());
        assert!(matches!(
            world.set_settings(settings),
            Err(Error::World(
                WorldError::SettingOutOfRange { .. } | WorldError::StepTooShort { .. }
            ))
        ));
    }
    let report = world.step(1e-38);
    assert_eq!(report.skipped, Some(StepSkipped::DtTooSmall(1e-38)));
    assert!(state(&world) == before);
}
