//! Bad input (`docs/architecture.md`, "Errors"): every constructor and setter rejects NaN, infinities where they make
//! no sense, negative lengths and stiffnesses, inverted ranges and zero axes with a typed error naming the field — and
//! a setter that fails changes nothing.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

use rebound_constraints::{
    BallJoint, ConstraintError, HingeJoint, Joint, JointSettings, JointSolver, JointSpring, Limits,
    Motor, PrismaticJoint, Rod, Rope, SoftSpring, Spring, SpringModel, WheelJoint, basis_from_axes,
    basis_from_axis,
};
use rebound_math::{MathError, Pose, Quat, Vec3};

const NAN: f32 = f32::NAN;
const INF: f32 = f32::INFINITY;

/// The field an error names (`None` for errors without one).
fn field(e: &ConstraintError) -> Option<&'static str> {
    match e {
        ConstraintError::Math(
            MathError::NonFinite { field, .. }
            | MathError::NotPositive { field, .. }
            | MathError::Negative { field, .. }
            | MathError::NonFiniteVector { field, .. }
            | MathError::ZeroLength { field, .. }
            | MathError::NonUnitVector { field, .. }
            | MathError::NonFiniteQuat { field, .. }
            | MathError::NonUnitQuat { field, .. },
        )
        | ConstraintError::NotANumber { field }
        | ConstraintError::OutOfRange { field, .. }
        | ConstraintError::ParallelAxes { field }
        | ConstraintError::InvertedRange {
            lower_field: field, ..
        } => Some(field),
        _ => None,
    }
}

/// Runs a table of `(description, result, expected field)`: every entry must fail naming that field, and
/// its message must name it too.
fn expect_errors(table: Vec<(&str, Result<(), ConstraintError>, &str)>) {
    for (what, result, expected) in table {
        let err = result.expect_err(what);
        assert_eq!(field(&err), Some(expected), "{what}: {err}");
        assert!(
            err.to_string().contains(expected),
            "{what}: message `{err}` does not name `{expected}`"
        );
    }
}

fn ok<T>(r: Result<T, ConstraintError>) -> Result<(), ConstraintError> {
    r.map(|_| ())
}

#[test]
fn spring_and_soft_spring_constructors_reject_bad_numbers() {
    expect_errors(vec![
        (
            "negative frequency",
            ok(SoftSpring::frequency(-1.0, 0.5)),
            "frequency_hz",
        ),
        (
            "zero frequency",
            ok(SoftSpring::frequency(0.0, 0.5)),
            "frequency_hz",
        ),
        (
            "NaN frequency",
            ok(SoftSpring::frequency(NAN, 0.5)),
            "frequency_hz",
        ),
        (
            "infinite frequency",
            ok(SoftSpring::frequency(INF, 0.5)),
            "frequency_hz",
        ),
        (
            "negative ζ",
            ok(SoftSpring::frequency(1.0, -0.1)),
            "damping_ratio",
        ),
        (
            "NaN ζ",
            ok(SoftSpring::frequency(1.0, NAN)),
            "damping_ratio",
        ),
        (
            "negative k",
            ok(SoftSpring::stiffness(-1.0, 0.0)),
            "stiffness",
        ),
        ("NaN k", ok(SoftSpring::stiffness(NAN, 0.0)), "stiffness"),
        ("−∞ k", ok(SoftSpring::stiffness(-INF, 0.0)), "stiffness"),
        (
            "negative c",
            ok(SoftSpring::stiffness(1.0, -2.0)),
            "damping",
        ),
        ("infinite c", ok(SoftSpring::stiffness(1.0, INF)), "damping"),
        (
            "force: negative k",
            ok(SpringModel::force(-1.0, 0.0)),
            "stiffness",
        ),
        (
            "force: infinite k",
            ok(SpringModel::force(INF, 0.0)),
            "stiffness",
        ),
        ("force: NaN c", ok(SpringModel::force(1.0, NAN)), "damping"),
        (
            "hand-built soft model",
            ok(SpringModel::Soft(SoftSpring::Frequency {
                frequency_hz: NAN,
                damping_ratio: 0.0,
            })
            .validated()),
            "frequency_hz",
        ),
        (
            "negative rest length",
            ok(Spring::new(-0.1, SpringModel::force(1.0, 0.0).unwrap())),
            "rest_length",
        ),
        (
            "NaN rest length",
            ok(Spring::new(NAN, SpringModel::force(1.0, 0.0).unwrap())),
            "rest_length",
        ),
        (
            "model checked by Spring::new",
            ok(Spring::new(
                1.0,
                SpringModel::Force {
                    stiffness: -5.0,
                    damping: 0.0,
                },
            )),
            "stiffness",
        ),
        (
            "max force < min force",
            ok(spring().with_force_range(1.0, -1.0)),
            "min_force",
        ),
        (
            "NaN min force",
            ok(spring().with_force_range(NAN, 0.0)),
            "min_force",
        ),
        (
            "NaN max force",
            ok(spring().with_force_range(0.0, NAN)),
            "max_force",
        ),
        (
            "joint spring NaN target",
            ok(JointSpring::new(NAN, SoftSpring::default())),
            "target",
        ),
    ]);
    // Infinite caps and an infinite stiffness are accepted (no cap; rigid).
    assert!(spring().with_force_range(-INF, INF).is_ok());
    assert!(SoftSpring::stiffness(INF, 0.0).is_ok());
    assert!(Spring::new(0.0, SpringModel::force(0.0, 0.0).unwrap()).is_ok());
}

fn spring() -> Spring {
    Spring::new(1.0, SpringModel::soft_frequency(2.0, 0.5).unwrap()).unwrap()
}

#[test]
fn rope_rod_limits_motor_and_joint_constructors_reject_bad_numbers() {
    expect_errors(vec![
        ("negative rope length", ok(Rope::new(-1.0)), "max_length"),
        ("infinite rope length", ok(Rope::new(INF)), "max_length"),
        (
            "restitution > 1",
            ok(Rope::new(1.0).unwrap().with_restitution(1.5)),
            "restitution",
        ),
        (
            "negative restitution",
            ok(Rope::new(1.0).unwrap().with_restitution(-0.5)),
            "restitution",
        ),
        (
            "NaN restitution",
            ok(Rope::new(1.0).unwrap().with_restitution(NAN)),
            "restitution",
        ),
        ("zero rod", ok(Rod::new(0.0)), "length"),
        ("negative rod", ok(Rod::new(-2.0)), "length"),
        ("NaN rod", ok(Rod::new(NAN)), "length"),
        ("inverted limits", ok(Limits::new(1.0, -1.0)), "lower"),
        ("NaN lower limit", ok(Limits::new(NAN, 1.0)), "lower"),
        ("infinite upper limit", ok(Limits::new(0.0, INF)), "upper"),
        (
            "hinge limit beyond π",
            ok(HingeJoint::new().with_limits(-4.0, 1.0)),
            "lower",
        ),
        (
            "hinge limit beyond π",
            ok(HingeJoint::new().with_limits(0.0, 3.5)),
            "upper",
        ),
        (
            "inverted hinge limits",
            ok(HingeJoint::new().with_limits(0.5, -0.5)),
            "lower",
        ),
        ("NaN motor speed", ok(Motor::new(NAN, 1.0)), "target_speed"),
        (
            "negative motor force",
            ok(Motor::new(1.0, -1.0)),
            "max_force",
        ),
        ("NaN motor force", ok(Motor::new(1.0, NAN)), "max_force"),
        (
            "bad wheel suspension",
            ok(WheelJoint::new(SoftSpring::Stiffness {
                stiffness: -1.0,
                damping: 0.0,
            })),
            "stiffness",
        ),
        ("zero axis", ok(basis_from_axis(Vec3::ZERO)), "axis"),
        (
            "NaN axis",
            ok(basis_from_axis(Vec3::new(NAN, 0.0, 0.0))),
            "axis",
        ),
        (
            "parallel axes",
            ok(basis_from_axes(Vec3::X, Vec3::X * 3.0)),
            "y_axis",
        ),
        (
            "antiparallel axes",
            ok(basis_from_axes(Vec3::X, -Vec3::X)),
            "y_axis",
        ),
        (
            "zero secondary axis",
            ok(basis_from_axes(Vec3::X, Vec3::ZERO)),
            "y_axis",
        ),
        (
            "NaN anchor",
            ok(Joint::new(BallJoint::new()).with_local_anchors(Vec3::NAN, Vec3::ZERO)),
            "local_anchor_a",
        ),
        (
            "infinite anchor",
            ok(Joint::new(BallJoint::new()).with_local_anchors(Vec3::ZERO, Vec3::INFINITY)),
            "local_anchor_b",
        ),
        (
            "zero joint axis",
            ok(Joint::new(HingeJoint::new()).with_local_axes(Vec3::ZERO, Vec3::Z)),
            "axis_a",
        ),
        (
            "NaN joint axis",
            ok(Joint::new(HingeJoint::new()).with_local_axes(Vec3::Z, Vec3::NAN)),
            "axis_b",
        ),
        (
            "non-unit basis",
            ok(Joint::new(HingeJoint::new())
                .with_local_bases(Quat::from_xyzw(0.0, 0.0, 0.0, 2.0), Quat::IDENTITY)),
            "local_basis_a",
        ),
        (
            "NaN basis",
            ok(Joint::new(HingeJoint::new()).with_local_bases(Quat::IDENTITY, Quat::NAN)),
            "local_basis_b",
        ),
        (
            "zero break force",
            ok(Joint::new(BallJoint::new()).with_break_force(0.0)),
            "break_force",
        ),
        (
            "negative break force",
            ok(Joint::new(BallJoint::new()).with_break_force(-1.0)),
            "break_force",
        ),
        (
            "NaN break torque",
            ok(Joint::new(BallJoint::new()).with_break_torque(NAN)),
            "break_torque",
        ),
        (
            "from_world: NaN anchor",
            ok(Joint::from_world(
                BallJoint::new(),
                Pose::IDENTITY,
                Pose::IDENTITY,
                Vec3::NAN,
                Vec3::ZERO,
                Quat::IDENTITY,
            )),
            "world_anchor_a",
        ),
        (
            "from_world: bad basis",
            ok(Joint::from_world(
                BallJoint::new(),
                Pose::IDENTITY,
                Pose::IDENTITY,
                Vec3::ZERO,
                Vec3::ZERO,
                Quat::from_xyzw(0.0, 0.0, 0.0, 0.5),
            )),
            "world_basis",
        ),
        (
            "from_world: bad pose",
            ok(Joint::from_world(
                BallJoint::new(),
                Pose::new(Vec3::ZERO, Quat::from_xyzw(1.0, 1.0, 0.0, 0.0)),
                Pose::IDENTITY,
                Vec3::ZERO,
                Vec3::ZERO,
                Quat::IDENTITY,
            )),
            "rotation",
        ),
        (
            "settings: zero frequency",
            ok(JointSolver::with_settings(JointSettings {
                frequency_hz: 0.0,
                ..JointSettings::default()
            })),
            "frequency_hz",
        ),
        (
            "settings: negative ζ",
            ok(JointSolver::with_settings(JointSettings {
                damping_ratio: -1.0,
                ..JointSettings::default()
            })),
            "damping_ratio",
        ),
        (
            "settings: NaN ratio",
            ok(JointSolver::with_settings(JointSettings {
                max_frequency_ratio: NAN,
                ..JointSettings::default()
            })),
            "max_frequency_ratio",
        ),
    ]);
    // Infinite break limits mean unbreakable; a zero-length rope is allowed.
    assert!(Joint::new(BallJoint::new()).with_break_force(INF).is_ok());
    assert!(Rope::new(0.0).is_ok());
}

#[test]
fn failing_setters_change_nothing() {
    // Kind setters.
    let mut s = spring();
    let before = s;
    assert!(s.set_rest_length(-1.0).is_err());
    assert!(
        s.set_model(SpringModel::Force {
            stiffness: NAN,
            damping: 0.0
        })
        .is_err()
    );
    assert!(s.set_force_range(2.0, 1.0).is_err());
    assert_eq!(s, before);

    let mut rope = Rope::new(2.0).unwrap();
    assert!(rope.set_max_length(NAN).is_err() && rope.set_restitution(2.0).is_err());
    assert_eq!(rope, Rope::new(2.0).unwrap());

    let mut rod = Rod::new(1.0).unwrap();
    assert!(rod.set_length(0.0).is_err());
    assert_eq!(rod, Rod::new(1.0).unwrap());

    let mut motor = Motor::new(1.0, 2.0).unwrap();
    assert!(motor.set_target_speed(INF).is_err() && motor.set_max_force(-3.0).is_err());
    assert_eq!(motor, Motor::new(1.0, 2.0).unwrap());

    let mut hinge = HingeJoint::new().with_limits(-1.0, 1.0).unwrap();
    let before = hinge;
    assert!(
        hinge
            .set_limits(Some(Limits::new(-4.0, 0.0).unwrap()))
            .is_err()
    );
    assert_eq!(hinge, before);

    let mut wheel = WheelJoint::default();
    let before = wheel;
    assert!(
        wheel
            .set_suspension(SoftSpring::Frequency {
                frequency_hz: -1.0,
                damping_ratio: 0.0
            })
            .is_err()
    );
    assert_eq!(wheel, before);

    // Joint setters, including the runtime ones and kinds without the feature.
    let mut joint = Joint::new(HingeJoint::new().with_motor(Motor::new(1.0, 5.0).unwrap()))
        .with_local_anchors(Vec3::X, Vec3::Y)
        .unwrap();
    let before = joint;
    assert!(joint.set_local_anchors(Vec3::ZERO, Vec3::NAN).is_err());
    assert!(joint.set_local_axes(Vec3::X, Vec3::ZERO).is_err());
    assert!(joint.set_local_bases(Quat::NAN, Quat::IDENTITY).is_err());
    assert!(joint.set_break_force(-1.0).is_err() && joint.set_break_torque(0.0).is_err());
    assert!(joint.set_motor_speed(NAN).is_err());
    assert!(
        joint
            .set_limits(Some(Limits::new(-1.0, 3.5).unwrap()))
            .is_err()
    );
    assert!(
        joint
            .set_spring(SoftSpring::Stiffness {
                stiffness: 1.0,
                damping: -1.0
            })
            .is_err()
    );
    assert!(joint.set_length(1.0).is_err());
    assert_eq!(joint, before);

    let mut ball = Joint::new(BallJoint::new());
    let before = ball;
    for err in [
        ball.set_motor(Some(Motor::new(1.0, 1.0).unwrap()))
            .unwrap_err(),
        ball.set_motor_speed(1.0).unwrap_err(),
        ball.set_limits(None).unwrap_err(),
        ball.set_spring(SoftSpring::default()).unwrap_err(),
        ball.set_length(1.0).unwrap_err(),
    ] {
        assert!(
            matches!(err, ConstraintError::Unsupported { kind: "ball", .. }),
            "{err}"
        );
    }
    assert_eq!(ball, before);
    // A hinge without a motor has no motor speed to set.
    let mut free = Joint::new(HingeJoint::new());
    assert!(matches!(
        free.set_motor_speed(1.0),
        Err(ConstraintError::Unsupported {
            feature: "motor",
            ..
        })
    ));

    let mut solver = JointSolver::new();
    assert!(
        solver
            .set_settings(JointSettings {
                frequency_hz: -1.0,
                ..JointSettings::default()
            })
            .is_err()
    );
    assert_eq!(*solver.settings(), JointSettings::default());
}

#[test]
fn valid_runtime_setters_take_effect() {
    let mut joint = Joint::new(PrismaticJoint::new().with_motor(Motor::new(0.0, 10.0).unwrap()));
    joint.set_motor_speed(2.5).unwrap();
    joint
        .set_limits(Some(Limits::new(-1.0, 1.0).unwrap()))
        .unwrap();
    joint
        .set_spring(SoftSpring::stiffness(100.0, 1.0).unwrap())
        .unwrap();
    let rebound_constraints::JointKind::Prismatic(p) = joint.kind() else {
        panic!("kind changed");
    };
    assert_eq!(p.motor().map(|m| m.target_speed()), Some(2.5));
    assert_eq!(p.limits(), Some(Limits::new(-1.0, 1.0).unwrap()));
    assert_eq!(
        p.spring().map(|s| s.spring()),
        Some(SoftSpring::stiffness(100.0, 1.0).unwrap())
    );

    let mut rope = Joint::new(Rope::new(1.0).unwrap());
    rope.set_length(3.0).unwrap();
    assert!(
        matches!(rope.kind(), rebound_constraints::JointKind::Rope(r) if (r.max_length() - 3.0).abs() < f32::EPSILON)
    );
}

#[test]
fn validated_rechecks_every_field_of_a_joint() {
    let good = Joint::new(
        HingeJoint::new()
            .with_limits(-1.0, 1.0)
            .unwrap()
            .with_motor(Motor::new(1.0, 2.0).unwrap()),
    )
    .with_break_force(10.0)
    .unwrap();
    assert_eq!(good.validated(), Ok(good));
    for kind in [
        rebound_constraints::JointKind::Spring(spring()),
        Rope::new(1.0).unwrap().into(),
        Rod::new(1.0).unwrap().into(),
        BallJoint::new().into(),
        PrismaticJoint::new().into(),
        WheelJoint::default().into(),
    ] {
        assert!(Joint::new(kind).validated().is_ok(), "{kind:?}");
    }
    // Invalid values cannot be built through the public API; only deserialization (feature `serde`) can
    // produce them, which is what `validated` is for.
}
