//! Validation at every door: a value that a constructor would refuse is refused the same way when it comes
//! in through a setter, an insertion, a deserialised description or a restored snapshot — a typed error that
//! names the field and the value, and a world whose state digest and snapshot are unchanged. Settings have
//! upper bounds, a step too short for `f32` is skipped, and the infinite defaults (unbreakable joints,
//! uncapped springs and motors, rigid springs) survive JSON.

#![cfg(feature = "serde")]
#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_constraints::{
    BallJoint, ConstraintError, FixedJoint, HingeJoint, Joint, JointState, Limits,
    MAX_JOINT_ITERATIONS, Motor, PrismaticJoint, Rod, Rope, SoftSpring, Spring, SpringModel,
    WheelJoint,
};
use rebound_dynamics::{BodyDesc, DynamicsError, MassProperties, RigidBody};
use rebound_math::{MathError, Pose, Quat, Vec3};
use rebound_world::testing::SimpleBackend;
use rebound_world::{
    BodyHandle, MAX_STEPS_PER_ADVANCE, MAX_SUBSTEPS, MIN_STEP_DT, StepSkipped, World, WorldError,
    WorldSettings, WorldSnapshot,
};
use serde_json::{Value, json};

const DT: f32 = 1.0 / 60.0;

/// A ball resting on the ground (so the snapshot holds a manifold with impulses), a second ball roped to it.
fn world() -> (World<SimpleBackend>, BodyHandle) {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let ground = world.insert_body(&BodyDesc::fixed()).unwrap();
    world
        .backend_mut()
        .add_half_space(ground, Vec3::Y, 0.5, 0.0);
    let ball = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    world.backend_mut().add_sphere(ball, 0.5, 0.5, 0.0);
    let other = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(2.0, 0.5, 0.0)))
        .unwrap();
    world.backend_mut().add_sphere(other, 0.5, 0.5, 0.0);
    world
        .insert_joint(Joint::new(Rope::new(3.0).unwrap()), ball, other)
        .unwrap();
    for _ in 0..5 {
        world.step(DT);
    }
    assert!(
        world
            .contacts()
            .iter()
            .any(|m| m.points().iter().any(|p| p.normal_impulse > 0.0)),
        "the scene holds a manifold with an impulse"
    );
    (world, ball)
}

/// The state digest and the whole snapshot: what "nothing changed" compares.
fn state(world: &World<SimpleBackend>) -> (u64, WorldSnapshot) {
    (world.state_digest(), world.snapshot())
}

/// Replaces the value of the first `key` met in a depth-first walk of `value` (object keys in order).
fn set_first(value: &mut Value, key: &str, new: &Value) -> bool {
    match value {
        Value::Object(map) => {
            if let Some(slot) = map.get_mut(key) {
                *slot = new.clone();
                return true;
            }
            map.values_mut().any(|v| set_first(v, key, new))
        }
        Value::Array(items) => items.iter_mut().any(|v| set_first(v, key, new)),
        _ => false,
    }
}

/// `1e39` in JSON is a finite number to the parser and +∞ as an `f32`: how a file smuggles in an infinity.
fn overflowing() -> Value {
    json!(1e39)
}

// ---- joints ----

#[test]
fn a_deserialised_joint_is_checked_as_its_constructor_checks_it() {
    let rope = serde_json::to_value(Joint::new(Rope::new(2.0).unwrap())).unwrap();
    // (the field to spoil, its new value, what the error must name)
    let cases = [
        ("max_length", json!(-5.0), "max_length"),
        ("restitution", json!(2.0), "restitution"),
        ("local_anchor_a", json!([0.0, 1e39, 0.0]), "local_anchor_a"),
        (
            "local_basis_b",
            json!([0.0, 0.0, 0.0, 2.0]),
            "local_basis_b",
        ),
        ("break_force", json!(-1.0), "break_force"),
        ("break_torque", json!(0.0), "break_torque"),
    ];
    for (field, bad, named) in cases {
        let mut value = rope.clone();
        assert!(set_first(&mut value, field, &bad), "{field}");
        let error = serde_json::from_value::<Joint>(value).unwrap_err();
        assert!(error.to_string().contains(named), "{field}: {error}");
    }
    // A kind on its own is checked too: a JSON rope of −5 m never becomes a `Rope`.
    let error = serde_json::from_value::<Rope>(json!({"max_length": -5.0, "restitution": 0.0}));
    assert!(
        error
            .unwrap_err()
            .to_string()
            .contains("`max_length` must be >= 0, got -5")
    );
}

#[test]
fn every_joint_kind_refuses_bad_limits_motors_and_springs_from_json() {
    let soft = SoftSpring::frequency(2.0, 0.5).unwrap();
    let motor = Motor::new(1.0, 10.0).unwrap();
    let limits = Limits::new(-0.5, 0.5).unwrap();
    let spring = rebound_constraints::JointSpring::new(0.0, soft).unwrap();
    // (a valid joint, the field to spoil, its new value, what the error must name)
    let cases: Vec<(Joint, &str, Value, &str)> = vec![
        (
            Spring::new(1.0, SpringModel::Soft(soft)).unwrap().into(),
            "rest_length",
            json!(-1.0),
            "rest_length",
        ),
        (
            Spring::new(1.0, SpringModel::Soft(soft)).unwrap().into(),
            "frequency_hz",
            json!(0.0),
            "frequency_hz",
        ),
        (
            Spring::new(1.0, SpringModel::force(10.0, 1.0).unwrap())
                .unwrap()
                .into(),
            "damping",
            json!(-3.0),
            "damping",
        ),
        (
            Spring::new(1.0, SpringModel::Soft(soft)).unwrap().into(),
            "min_force",
            json!("inf"),
            "min_force",
        ),
        (
            Spring::new(1.0, SpringModel::Soft(soft)).unwrap().into(),
            "max_force",
            json!("-inf"),
            "max_force",
        ),
        (
            Spring::new(1.0, SpringModel::Soft(soft))
                .unwrap()
                .with_force_range(-5.0, 5.0)
                .unwrap()
                .into(),
            "max_force",
            json!(-6.0),
            "must not exceed `max_force`",
        ),
        (
            Rod::new(1.0).unwrap().into(),
            "length",
            json!(0.0),
            "length",
        ),
        (
            HingeJoint::new().with_limits(-0.5, 0.5).unwrap().into(),
            "upper",
            json!(4.0),
            "upper",
        ),
        (
            HingeJoint::new().with_motor(motor).into(),
            "target_speed",
            overflowing(),
            "target_speed",
        ),
        (
            HingeJoint::new().with_spring(spring).into(),
            "target",
            overflowing(),
            "target",
        ),
        (
            PrismaticJoint::new().with_limits(limits).into(),
            "lower",
            json!(1.0),
            "lower",
        ),
        (
            PrismaticJoint::new().with_motor(motor).into(),
            "max_force",
            json!(-2.0),
            "max_force",
        ),
        (
            WheelJoint::new(soft).unwrap().into(),
            "damping_ratio",
            json!(-0.1),
            "damping_ratio",
        ),
        (
            WheelJoint::new(SoftSpring::stiffness(1e4, 1e2).unwrap())
                .unwrap()
                .into(),
            "stiffness",
            json!(-1.0),
            "stiffness",
        ),
        (
            BallJoint::new().into(),
            "local_anchor_b",
            json!([1e39, 0.0, 0.0]),
            "local_anchor_b",
        ),
        (
            FixedJoint::new().into(),
            "local_basis_a",
            json!([0.0, 0.0, 0.0, 0.0]),
            "local_basis_a",
        ),
    ];
    for (joint, field, bad, named) in cases {
        let mut value = serde_json::to_value(joint).unwrap();
        assert_eq!(
            serde_json::from_value::<Joint>(value.clone()).unwrap(),
            joint
        );
        assert!(set_first(&mut value, field, &bad), "{field} in {value}");
        let error = serde_json::from_value::<Joint>(value).unwrap_err();
        assert!(error.to_string().contains(named), "{field}: {error}");
    }
}

#[test]
fn a_deserialised_joint_state_with_an_infinite_impulse_is_refused() {
    let mut value = serde_json::to_value(JointState::default()).unwrap();
    assert!(set_first(&mut value, "motor_impulse", &overflowing()));
    let error = serde_json::from_value::<JointState>(value).unwrap_err();
    assert!(
        error.to_string().contains("`motor_impulse` must be finite"),
        "{error}"
    );
}

// ---- bodies and mass properties ----

#[test]
fn bad_mass_properties_are_refused_wherever_they_are_made() {
    let ball = MassProperties::ball(1000.0, 0.5).unwrap();
    // Deserialised: mass 0, mass −1, an infinite or negative inertia, a NaN (here: overflowing) centre.
    let good = serde_json::to_value(ball).unwrap();
    let cases = [
        ("mass", json!(0.0), "`mass` must be > 0, got 0"),
        ("mass", json!(-1.0), "`mass` must be > 0, got -1"),
        ("mass", json!(1e-40), "so that its inverse is finite"),
        (
            "local_inertia",
            json!([1e39, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]),
            "`inertia` must be a symmetric positive semi-definite",
        ),
        (
            "local_inertia",
            json!([-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]),
            "`inertia` must be a symmetric positive semi-definite",
        ),
        (
            "local_center_of_mass",
            json!([0.0, 1e39, 0.0]),
            "`local_center_of_mass` must be finite",
        ),
    ];
    for (field, bad, message) in cases {
        let mut value = good.clone();
        assert!(set_first(&mut value, field, &bad));
        let error = serde_json::from_value::<MassProperties>(value.clone()).unwrap_err();
        assert!(error.to_string().contains(message), "{field}: {error}");
        // Inside a body description the same value is refused the same way.
        let desc = json!({ "mass_properties": value });
        let error = serde_json::from_value::<BodyDesc>(desc).unwrap_err();
        assert!(
            error.to_string().contains(message),
            "{field} in a BodyDesc: {error}"
        );
    }
    // Placed at a pose that is not one, or so far out that the centre overflows.
    let nan_pose = Pose::from_position(Vec3::new(f32::NAN, 0.0, 0.0));
    assert!(matches!(
        ball.transformed(nan_pose),
        Err(DynamicsError::Math(MathError::NonFiniteVector {
            field: "position",
            ..
        }))
    ));
    let tilted = Pose::new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 2.0));
    assert!(matches!(
        ball.transformed(tilted),
        Err(DynamicsError::Math(MathError::NonUnitQuat {
            field: "rotation",
            ..
        }))
    ));
    let far = MassProperties::new(1.0, Vec3::splat(3e38), Vec3::ONE).unwrap();
    assert!(matches!(
        far.transformed(Pose::from_position(Vec3::splat(3e38))),
        Err(DynamicsError::Math(MathError::NonFiniteVector {
            field: "local_center_of_mass",
            ..
        }))
    ));
    // Combined: a total mass beyond f32, or a centre m·c that overflows.
    let heavy = MassProperties::new(3e38, Vec3::ZERO, Vec3::ONE).unwrap();
    assert!(matches!(
        MassProperties::combine(&[heavy, heavy]),
        Err(DynamicsError::NoMass { count: 2, .. })
    ));
    let spread = MassProperties::new(1e30, Vec3::new(1e10, 0.0, 0.0), Vec3::ONE).unwrap();
    assert!(MassProperties::combine(&[spread, ball]).is_err());
}

#[test]
fn a_deserialised_body_is_checked_field_by_field() {
    let (world, ball) = world();
    let good = serde_json::to_value(world.body(ball).unwrap()).unwrap();
    for (field, bad) in [
        ("force", json!([1e39, 0.0, 0.0])),
        ("torque", json!([0.0, 0.0, 1e39])),
        ("linear_velocity", json!([0.0, 1e39, 0.0])),
        ("gravity_scale", overflowing()),
        ("linear_damping", json!(-1.0)),
        ("mass", json!(-1.0)),
    ] {
        let mut value = good.clone();
        assert!(set_first(&mut value, field, &bad), "{field}");
        let error = serde_json::from_value::<RigidBody>(value).unwrap_err();
        assert!(
            error.to_string().contains(&format!("`{field}`")),
            "{field}: {error}"
        );
    }
}

// ---- accumulated forces ----

#[test]
fn forces_and_torques_are_checked_as_sums() {
    let (mut world, ball) = world();
    let body = world.body_mut(ball).unwrap();
    body.apply_force(Vec3::new(f32::MAX, 0.0, 0.0)).unwrap();
    body.apply_torque(Vec3::new(0.0, f32::MAX, 0.0)).unwrap();
    let before = state(&world);
    let body = world.body_mut(ball).unwrap();
    let error = body.apply_force(Vec3::new(f32::MAX, 0.0, 0.0)).unwrap_err();
    let DynamicsError::AccumulatedNotFinite {
        field: "force",
        accumulated,
        added,
    } = error
    else {
        panic!("{error:?}");
    };
    assert_eq!(
        (accumulated, added),
        (Vec3::new(f32::MAX, 0.0, 0.0), Vec3::new(f32::MAX, 0.0, 0.0))
    );
    assert!(error.to_string().contains("accumulated `force`"), "{error}");
    let error = body
        .apply_torque(Vec3::new(0.0, f32::MAX, 0.0))
        .unwrap_err();
    assert!(matches!(
        error,
        DynamicsError::AccumulatedNotFinite {
            field: "torque",
            ..
        }
    ));
    // At a point: the force sum, or the torque (p − c) × F it adds.
    let error = body
        .apply_force_at_point(Vec3::new(f32::MAX, 0.0, 0.0), Vec3::ZERO)
        .unwrap_err();
    assert!(matches!(
        error,
        DynamicsError::AccumulatedNotFinite { field: "force", .. }
    ));
    let error = body
        .apply_force_at_point(Vec3::new(0.0, 0.0, 1e30), Vec3::new(1e30, 0.0, 0.0))
        .unwrap_err();
    assert!(matches!(
        error,
        DynamicsError::AccumulatedNotFinite {
            field: "torque",
            ..
        }
    ));
    assert_eq!(
        body.force(),
        Vec3::new(f32::MAX, 0.0, 0.0),
        "nothing was added"
    );
    assert!(state(&world) == before, "no refused call changed the world");
}

// ---- settings ----

#[test]
fn counts_and_rates_have_upper_bounds_at_every_door() {
    let (mut world, _) = world();
    let before = state(&world);
    let good = *world.settings();
    let mut joints = good.joints;
    joints.solve_iterations = u32::MAX;
    let cases: Vec<(WorldSettings, &str)> = vec![
        (
            WorldSettings {
                substep_count: u32::MAX,
                ..good
            },
            "substep_count",
        ),
        (
            WorldSettings {
                substep_count: MAX_SUBSTEPS + 1,
                ..good
            },
            "substep_count",
        ),
        (
            WorldSettings {
                max_steps_per_advance: u32::MAX,
                ..good
            },
            "max_steps_per_advance",
        ),
        (
            WorldSettings {
                max_steps_per_advance: MAX_STEPS_PER_ADVANCE + 1,
                ..good
            },
            "max_steps_per_advance",
        ),
        (
            WorldSettings {
                fixed_dt: 1e-30,
                ..good
            },
            "fixed_dt",
        ),
        (WorldSettings { joints, ..good }, "solve_iterations"),
    ];
    for (settings, field) in cases {
        // set_settings
        let error = world.set_settings(settings).unwrap_err();
        assert!(error.to_string().contains(field), "{field}: {error}");
        // World::new
        assert!(World::new(settings).is_err(), "{field}");
        // a settings file
        let text = serde_json::to_string(&settings).unwrap();
        let error = serde_json::from_str::<WorldSettings>(&text).unwrap_err();
        assert!(error.to_string().contains(field), "{field}: {error}");
    }
    let error = world
        .set_settings(WorldSettings {
            substep_count: u32::MAX,
            ..good
        })
        .unwrap_err();
    let WorldError::SettingOutOfRange {
        field: "substep_count",
        value,
        min,
        max,
    } = error
    else {
        panic!("{error:?}");
    };
    assert_eq!(
        (value, min, max),
        (u32::MAX as f32, 1.0, MAX_SUBSTEPS as f32)
    );
    assert!(matches!(
        world.set_settings(WorldSettings {
            fixed_dt: 1e-38,
            ..good
        }),
        Err(WorldError::StepTooShort {
            field: "fixed_dt",
            ..
        })
    ));
    let mut joints = good.joints;
    joints.relax_iterations = MAX_JOINT_ITERATIONS + 1;
    assert!(matches!(
        world.set_settings(WorldSettings { joints, ..good }),
        Err(WorldError::Constraint(ConstraintError::OutOfRange {
            field: "relax_iterations",
            ..
        }))
    ));
    // The bounds themselves are accepted.
    let mut joints = good.joints;
    joints.solve_iterations = MAX_JOINT_ITERATIONS;
    let edge = WorldSettings {
        substep_count: MAX_SUBSTEPS,
        max_steps_per_advance: MAX_STEPS_PER_ADVANCE,
        fixed_dt: MIN_STEP_DT,
        joints,
        ..good
    };
    assert!(World::new(edge).is_ok());
    assert!(state(&world) == before);
}

#[test]
fn a_step_too_short_for_f32_is_skipped_not_run() {
    let (mut world, _) = world();
    let before = state(&world);
    for dt in [1e-38, 1e-30, MIN_STEP_DT * 0.5] {
        let report = world.step(dt);
        assert_eq!(report.skipped, Some(StepSkipped::DtTooSmall(dt)));
        assert_eq!(report.body_count, 3);
    }
    assert!(state(&world) == before, "a skipped step moves nothing");
    let report = world.step(MIN_STEP_DT);
    assert_eq!(report.skipped, None, "the shortest step runs");
    assert!(world.bodies().iter().all(|(_, b)| b.position().is_finite()));
}

// ---- snapshots ----

/// The snapshot of `world` as JSON with the first `key` under `state.<part>` set to `bad`, read back (if it
/// reads).
fn spoiled(
    world: &World<SimpleBackend>,
    part: &str,
    key: &str,
    bad: &Value,
) -> Result<WorldSnapshot, String> {
    let mut value = serde_json::to_value(world.snapshot()).unwrap();
    assert!(
        set_first(&mut value["state"][part], key, bad),
        "{part}.{key}"
    );
    serde_json::from_value(value).map_err(|e| e.to_string())
}

#[test]
fn a_snapshot_with_a_bad_body_or_joint_state_does_not_even_load() {
    let (world, _) = world();
    for (part, key, bad, named) in [
        (
            "bodies",
            "force",
            json!([1e39, 0.0, 0.0]),
            "`force` must be finite",
        ),
        ("bodies", "mass", json!(-1.0), "`mass` must be > 0"),
        (
            "bodies",
            "local_center_of_mass",
            json!([1e39, 0.0, 0.0]),
            "`local_center_of_mass`",
        ),
        (
            "bodies",
            "local_inertia",
            json!([-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]),
            "`inertia`",
        ),
        (
            "joints",
            "upper_impulse",
            overflowing(),
            "`upper_impulse` must be finite",
        ),
        (
            "joints",
            "max_length",
            json!(-5.0),
            "`max_length` must be >= 0",
        ),
        (
            "settings",
            "substep_count",
            json!(1_000_000),
            "`substep_count`",
        ),
    ] {
        let error = spoiled(&world, part, key, &bad).unwrap_err();
        assert!(error.contains(named), "{key}: {error}");
    }
}

#[test]
fn restore_refuses_the_whole_snapshot_naming_the_first_bad_item() {
    let (mut world, _) = world();
    let before = state(&world);
    // A manifold point with an infinite impulse (warm starting would feed it back).
    let snapshot = spoiled(&world, "manifolds", "normal_impulse", &overflowing()).unwrap();
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        matches!(&error, WorldError::InvalidSnapshot { item, source }
            if item == "manifold 0, point 0"
            && matches!(**source, WorldError::Math(MathError::NonFinite { field: "normal_impulse", .. }))),
        "{error:?}"
    );
    assert!(
        error
            .to_string()
            .contains("manifold 0, point 0: `normal_impulse` must be finite, got inf")
    );
    // A manifold whose normal is not unit.
    let snapshot = spoiled(&world, "manifolds", "normal", &json!([0.0, 2.0, 0.0])).unwrap();
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        error.to_string().contains("`normal` must be unit length"),
        "{error}"
    );
    // A joint on a body that does not exist.
    let nowhere = json!({"index": 99, "generation": 7});
    let snapshot = spoiled(&world, "joints", "body_b", &nowhere).unwrap();
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        matches!(&error, WorldError::InvalidSnapshot { item, source }
            if item == "joint 0" && matches!(**source, WorldError::StaleBody(_))),
        "{error:?}"
    );
    // A negative sleep timer and an advance accumulator of −1 s.
    let snapshot = spoiled(&world, "bodies", "sleep_time", &json!(-1.0)).unwrap();
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("body 0: `sleep_time` must be >= 0, got -1"),
        "{error}"
    );
    let mut value = serde_json::to_value(world.snapshot()).unwrap();
    value["state"]["accumulator"] = json!(-1.0);
    let snapshot: WorldSnapshot = serde_json::from_value(value).unwrap();
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        error.to_string().contains("`accumulator` must be >= 0"),
        "{error}"
    );
    // A manifold between a body and itself.
    let mut value = serde_json::to_value(world.snapshot()).unwrap();
    let body_a = value["state"]["manifolds"][0]["body_a"].clone();
    assert_ne!(body_a, Value::Null);
    value["state"]["manifolds"][0]["body_b"] = body_a;
    let snapshot: WorldSnapshot = serde_json::from_value(value).unwrap();
    let error = world.restore(&snapshot).unwrap_err();
    assert!(
        matches!(&error, WorldError::InvalidSnapshot { item, source }
            if item == "manifold 0" && matches!(**source, WorldError::SameBody(_))),
        "{error:?}"
    );
    assert!(
        state(&world) == before,
        "every refused snapshot left the world as it was"
    );
    world.step(DT);
}

// ---- infinite defaults through JSON ----

/// Whether a bound that may be infinite is written as `null` anywhere in `value`.
fn bound_is_null(value: &Value) -> bool {
    const BOUNDS: [&str; 5] = [
        "break_force",
        "break_torque",
        "min_force",
        "max_force",
        "stiffness",
    ];
    match value {
        Value::Object(map) => map
            .iter()
            .any(|(k, v)| (BOUNDS.contains(&k.as_str()) && v.is_null()) || bound_is_null(v)),
        Value::Array(items) => items.iter().any(bound_is_null),
        _ => false,
    }
}

#[test]
fn every_description_with_its_defaults_round_trips_through_json() {
    let soft = SoftSpring::default();
    let rigid = SoftSpring::stiffness(f32::INFINITY, 0.0).unwrap();
    let uncapped_motor = Motor::new(2.0, f32::INFINITY).unwrap();
    let joints: Vec<Joint> = vec![
        Spring::new(1.0, SpringModel::Soft(soft)).unwrap().into(),
        Spring::new(0.0, SpringModel::Soft(rigid)).unwrap().into(),
        Spring::new(1.0, SpringModel::force(10.0, 0.0).unwrap())
            .unwrap()
            .with_force_range(f32::NEG_INFINITY, 0.0)
            .unwrap()
            .into(),
        Rope::new(2.0).unwrap().into(),
        Rod::new(1.0).unwrap().into(),
        BallJoint::new().into(),
        HingeJoint::default().into(),
        HingeJoint::new().with_motor(uncapped_motor).into(),
        FixedJoint::new().into(),
        PrismaticJoint::default().with_motor(uncapped_motor).into(),
        WheelJoint::default().into(),
        WheelJoint::new(rigid)
            .unwrap()
            .with_motor(uncapped_motor)
            .into(),
    ];
    for joint in joints {
        assert!(joint.break_force().is_infinite() && joint.break_torque().is_infinite());
        let text = serde_json::to_string(&joint).unwrap();
        let value: Value = serde_json::from_str(&text).unwrap();
        assert!(
            !bound_is_null(&value),
            "no infinity is written as null: {text}"
        );
        assert!(text.contains(r#""break_force":"inf""#), "{text}");
        let back: Joint = serde_json::from_str(&text).unwrap();
        assert_eq!(back, joint, "{text}");
        assert_eq!(serde_json::to_string(&back).unwrap(), text);
    }
    let spring = Spring::new(1.0, SpringModel::Soft(soft)).unwrap();
    let text = serde_json::to_string(&spring).unwrap();
    assert!(
        text.contains(r#""min_force":"-inf","max_force":"inf""#),
        "{text}"
    );
    // Files that wrote an infinity as `null` (serde_json's own choice) or left it out still load.
    let old = json!({"rest_length": 1.0, "model": {"Soft": {"Frequency": {"frequency_hz": 5.0, "damping_ratio": 0.7}}},
        "min_force": null, "max_force": null});
    assert_eq!(serde_json::from_value::<Spring>(old).unwrap(), spring);
    let missing = json!({"rest_length": 1.0, "model": {"Soft": {"Frequency": {"frequency_hz": 5.0, "damping_ratio": 0.7}}}});
    assert_eq!(serde_json::from_value::<Spring>(missing).unwrap(), spring);
    // Settings and bodies with their defaults, too.
    let settings = WorldSettings::default();
    let text = serde_json::to_string(&settings).unwrap();
    assert_eq!(
        serde_json::from_str::<WorldSettings>(&text).unwrap(),
        settings
    );
    for desc in [
        BodyDesc::dynamic(),
        BodyDesc::fixed(),
        BodyDesc::kinematic(),
    ] {
        let text = serde_json::to_string(&desc).unwrap();
        assert_eq!(serde_json::from_str::<BodyDesc>(&text).unwrap(), desc);
    }
}

#[test]
fn a_world_of_unbreakable_joints_restores_from_json_bit_for_bit() {
    let (mut world, ball) = world();
    let other = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(-2.0, 0.5, 0.0)))
        .unwrap();
    let spring = Spring::new(2.0, SpringModel::Soft(SoftSpring::default())).unwrap();
    world.insert_joint(spring.into(), ball, other).unwrap();
    world.step(DT);
    let text = serde_json::to_string(&world.snapshot()).unwrap();
    let snapshot: WorldSnapshot = serde_json::from_str(&text).unwrap();
    let mut restored = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    restored.restore(&snapshot).unwrap();
    assert_eq!(restored.state_digest(), world.state_digest());
    assert_eq!(serde_json::to_string(&restored.snapshot()).unwrap(), text);
}
