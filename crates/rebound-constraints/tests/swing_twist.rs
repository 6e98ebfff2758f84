//! Swing–twist limits and the orientation motor of the ball joint: a pendulum on a 30° cone never swings
//! past 30.5°; a twist range of ±20° holds to ±20.5° under a driving torque; an elliptical cone of (30°, 60°)
//! holds each half-angle and reaches it; the motor brings the relative rotation to its target; a soft limit
//! gives way and returns; a bouncing limit sends the swing back.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use rebound_constraints::{
    BallJoint, Joint, OrientationMotor, SoftSpring, SwingTwistLimits, basis_from_axis,
};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::{Pose, Quat, Vec3};
use support::Harness;

const DT: f32 = 1.0 / 60.0;
const HALF: Vec3 = Vec3::new(0.05, 0.5, 0.05);
const PIVOT: Vec3 = Vec3::new(0.0, 2.0, 0.0);

fn cuboid(mass: f32, half: Vec3) -> MassProperties {
    let h2 = half * half;
    let inertia = Vec3::new(h2.y + h2.z, h2.x + h2.z, h2.x + h2.y) * (mass / 3.0);
    MassProperties::new(mass, Vec3::ZERO, inertia).unwrap()
}

/// A 2 kg bar hanging from a ball joint at its top end, its joint axis (frame X) along the bar, pointing
/// down; the frame's Y is world z, its Z is world −x (so a swing about the frame's Y turns the bar in the
/// x–y plane, one about its Z in the z–y plane). The bar starts turned by `rotation` about the pivot and
/// spinning at `spin` (rad/s, world) about it.
fn pendulum(
    ball: BallJoint,
    rotation: Quat,
    spin: Vec3,
    settings: SolverSettings,
) -> (Harness, usize, usize) {
    let mut h = Harness::new(settings);
    let world = h.world_anchor();
    let center = PIVOT + rotation * Vec3::new(0.0, -HALF.y, 0.0);
    let bar = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(2.0, HALF))
            .with_position(center)
            .with_rotation(rotation)
            .with_angular_velocity(spin)
            .with_linear_velocity(spin.cross(center - PIVOT)),
    );
    let hanging = Pose::new(PIVOT + Vec3::new(0.0, -HALF.y, 0.0), Quat::IDENTITY);
    // X down the bar, Y = world z, Z = world −x (right-handed).
    let basis = Quat::from_mat3(&rebound_math::Mat3::from_cols(-Vec3::Y, Vec3::Z, -Vec3::X));
    let joint = Joint::from_world(ball, Pose::IDENTITY, hanging, PIVOT, PIVOT, basis).unwrap();
    let j = h.join(joint, world, bar);
    (h, bar, j)
}

/// The swing (angle between the two frames' X axes, rad) and the twist of the pendulum's joint.
fn swing_and_twist(h: &Harness, bar: usize, j: usize) -> rebound_constraints::part::SwingTwist {
    let joint = &h.joints[j];
    rebound_constraints::part::SwingTwist::new(
        joint.local_basis_a(),
        h.bodies[bar].rotation() * joint.local_basis_b(),
    )
}

fn pivot_gap(h: &Harness, bar: usize, j: usize) -> f32 {
    (h.world_point(bar, h.joints[j].local_anchor_b()) - PIVOT).length()
}

fn limited(cone: (f32, f32)) -> BallJoint {
    BallJoint::new().with_limits(SwingTwistLimits::new().with_cone(cone.0, cone.1).unwrap())
}

#[test]
fn a_pendulum_on_a_30_degree_cone_never_swings_past_30_5_degrees() {
    let limit = 30f32.to_radians();
    // Released at 20° about z with 5 rad/s about z and 2 rad/s about x: without the cone it would swing to
    // about 90°, and the two components make it swing around the cone's rim too.
    let (mut h, bar, j) = pendulum(
        limited((limit, limit)),
        Quat::from_rotation_z(20f32.to_radians()),
        Vec3::new(2.0, 0.0, 5.0),
        SolverSettings::default(),
    );
    let mut worst = 0.0f32;
    for _ in 0..300 {
        h.step(DT);
        worst = worst.max(swing_and_twist(&h, bar, j).swing);
        // The pivot is solved directly (the joint is a path of one), and the limit rows act about it.
        assert!(
            pivot_gap(&h, bar, j) < 2e-4,
            "pivot gap {}",
            pivot_gap(&h, bar, j)
        );
    }
    assert!(
        worst.to_degrees() < 30.5,
        "swung to {}°",
        worst.to_degrees()
    );
    assert!(
        worst.to_degrees() > 29.0,
        "never reached the cone: {}°",
        worst.to_degrees()
    );
}

#[test]
fn a_twist_range_of_20_degrees_holds_under_a_driving_torque() {
    let limit = 20f32.to_radians();
    let ball =
        BallJoint::new().with_limits(SwingTwistLimits::new().with_twist(-limit, limit).unwrap());
    let (mut h, bar, j) = pendulum(ball, Quat::IDENTITY, Vec3::ZERO, SolverSettings::default());
    // A torque about the bar's axis (world y) that would spin it up at τ/I = 2/0.00333 = 600 rad/s²,
    // reversed every second.
    let mut worst = 0.0f32;
    let mut reached = [false; 2];
    for step in 0..240 {
        let sign = if (step / 60) % 2 == 0 { 1.0 } else { -1.0 };
        h.bodies[bar].apply_torque(Vec3::Y * (2.0 * sign)).unwrap();
        h.step(DT);
        let twist = swing_and_twist(&h, bar, j).twist;
        worst = worst.max(twist.abs());
        reached[usize::from(twist > 0.0)] |= twist.abs().to_degrees() > 19.5;
    }
    assert!(
        worst.to_degrees() < 20.5,
        "twisted to {}°",
        worst.to_degrees()
    );
    assert!(
        reached[0] && reached[1],
        "the torque never drove it to both limits"
    );
}

#[test]
fn an_elliptical_cone_holds_each_half_angle() {
    let (small, large) = (30f32.to_radians(), 60f32.to_radians());
    // Swinging about the frame's Y (world z) meets the 30° half-angle; about its Z (world x) the 60° one.
    for (spin, limit) in [(Vec3::Z * 6.0, small), (Vec3::X * 6.0, large)] {
        let (mut h, bar, j) = pendulum(
            limited((small, large)),
            Quat::IDENTITY,
            spin,
            SolverSettings::default(),
        );
        let mut worst = 0.0f32;
        for _ in 0..180 {
            h.step(DT);
            worst = worst.max(swing_and_twist(&h, bar, j).swing);
        }
        let (worst, limit) = (worst.to_degrees(), limit.to_degrees());
        assert!(worst < limit + 0.5, "swung to {worst}° against {limit}°");
        assert!(worst > limit - 1.0, "never reached {limit}°: {worst}°");
    }
}

#[test]
fn the_orientation_motor_brings_the_relative_rotation_to_its_target() {
    let target = Quat::from_axis_angle(Vec3::new(0.3, 1.0, -0.5).normalize(), 1.0);
    let motor = OrientationMotor::new(
        target,
        SoftSpring::frequency(3.0, 1.0).unwrap(),
        f32::INFINITY,
    )
    .unwrap();
    let zero_g = SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    };
    let (mut h, bar, j) = pendulum(
        BallJoint::new().with_motor(motor),
        Quat::IDENTITY,
        Vec3::ZERO,
        zero_g,
    );
    for _ in 0..180 {
        h.step(DT);
    }
    let joint = &h.joints[j];
    let relative =
        joint.local_basis_a().conjugate() * h.bodies[bar].rotation() * joint.local_basis_b();
    let error = relative.angle_between(target);
    assert!(error < 1e-3, "{error} rad from the target after 3 s");
    assert!(pivot_gap(&h, bar, j) < 1e-4);
}

#[test]
fn the_orientation_motor_torque_is_capped() {
    // 0.01 N·m on the bar about its long axis (I = 2/3·(0.05² + 0.05²) = 0.00333 kg·m²): at most
    // 3 rad/s² — after 0.5 s at most 1.5 rad/s.
    let target = Quat::from_rotation_x(2.0);
    let motor =
        OrientationMotor::new(target, SoftSpring::frequency(10.0, 1.0).unwrap(), 0.01).unwrap();
    let zero_g = SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    };
    let (mut h, bar, _) = pendulum(
        BallJoint::new().with_motor(motor),
        Quat::IDENTITY,
        Vec3::ZERO,
        zero_g,
    );
    for _ in 0..30 {
        h.step(DT);
    }
    let spin = h.bodies[bar].angular_velocity().length();
    let inertia = 2.0 / 3.0 * (0.05f32 * 0.05 + 0.05 * 0.05);
    let bound = 0.01 / inertia * 0.5;
    assert!(spin <= bound * 1.01, "{spin} rad/s > {bound}");
    assert!(
        spin > bound * 0.9,
        "{spin} rad/s: the motor did not push at its cap {bound}"
    );
}

#[test]
fn a_soft_cone_gives_way_and_returns() {
    let limit = 30f32.to_radians();
    let soft = SwingTwistLimits::new()
        .with_cone(limit, limit)
        .unwrap()
        .with_softness(SoftSpring::frequency(2.0, 0.5).unwrap())
        .unwrap();
    let (mut h, bar, j) = pendulum(
        BallJoint::new().with_limits(soft),
        Quat::IDENTITY,
        Vec3::Z * 6.0,
        SolverSettings::default(),
    );
    let mut worst = 0.0f32;
    for _ in 0..120 {
        h.step(DT);
        worst = worst.max(swing_and_twist(&h, bar, j).swing);
    }
    // Free, 6 rad/s would swing it to ~80°; the 2 Hz spring lets it past 30° but stops it well short.
    assert!(
        worst.to_degrees() > 31.0 && worst.to_degrees() < 70.0,
        "{}°",
        worst.to_degrees()
    );
}

#[test]
fn a_bouncing_cone_sends_the_swing_back() {
    let limit = 30f32.to_radians();
    let swing_after_hit = |e: f32| {
        let limits = SwingTwistLimits::new()
            .with_cone(limit, limit)
            .unwrap()
            .with_restitution(e)
            .unwrap();
        let zero_g = SolverSettings {
            gravity: Vec3::ZERO,
            ..SolverSettings::default()
        };
        let (mut h, bar, j) = pendulum(
            BallJoint::new().with_limits(limits),
            Quat::IDENTITY,
            Vec3::Z * 3.0,
            zero_g,
        );
        // 30° at 3 rad/s: hit after 0.17 s; measure the rate 0.1 s later.
        for _ in 0..16 {
            h.step(DT);
        }
        let before = swing_and_twist(&h, bar, j).swing;
        h.step(DT);
        let after = swing_and_twist(&h, bar, j).swing;
        (after - before) / DT
    };
    let dead = swing_after_hit(0.0);
    let bounced = swing_after_hit(0.5);
    assert!(
        dead.abs() < 0.05,
        "without restitution the swing stops: {dead} rad/s"
    );
    // Bounced back at about half the approach speed (3 rad/s).
    assert!((bounced + 1.5).abs() < 0.3, "{bounced} rad/s");
}

#[test]
fn bad_limits_and_motors_are_refused_naming_the_field() {
    use rebound_constraints::ConstraintError;
    let err = SwingTwistLimits::new()
        .with_cone(f32::NAN, 0.5)
        .unwrap_err();
    assert!(err.to_string().contains("half_angle_y"), "{err}");
    let err = SwingTwistLimits::new().with_cone(0.5, 4.0).unwrap_err();
    assert!(
        matches!(
            err,
            ConstraintError::OutOfRange {
                field: "half_angle_z",
                ..
            }
        ),
        "{err}"
    );
    assert!(SwingTwistLimits::new().with_twist(0.5, -0.5).is_err());
    assert!(SwingTwistLimits::new().with_twist(-4.0, 0.5).is_err());
    assert!(SwingTwistLimits::new().with_restitution(1.5).is_err());
    let err = OrientationMotor::new(Quat::IDENTITY, SoftSpring::default(), -1.0).unwrap_err();
    assert!(err.to_string().contains("max_torque"), "{err}");
    assert!(
        OrientationMotor::new(
            Quat::from_xyzw(f32::INFINITY, 0.0, 0.0, 1.0),
            SoftSpring::default(),
            1.0
        )
        .is_err()
    );
    let _ = basis_from_axis(Vec3::X).unwrap();
}
