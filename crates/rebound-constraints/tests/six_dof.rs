//! The 6-DOF joint: free along X alone it steps as the prismatic joint does (same trajectory to 1e-4 m);
//! a velocity drive reaches its target speed and a position drive its target; a limited axis holds its
//! range, linear and angular; locked axes hold; bad fields are refused by name.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use rebound_constraints::{
    Axis, AxisDrive, AxisMotion, ConstraintError, Joint, JointKind, Limits, PrismaticJoint,
    SixDofJoint, SoftSpring, basis_from_axis,
};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::{Pose, Quat, Vec3};
use support::Harness;

const DT: f32 = 1.0 / 60.0;

fn cuboid(mass: f32, half: Vec3) -> MassProperties {
    let h2 = half * half;
    let inertia = Vec3::new(h2.y + h2.z, h2.x + h2.z, h2.x + h2.y) * (mass / 3.0);
    MassProperties::new(mass, Vec3::ZERO, inertia).unwrap()
}

/// A 1.5 kg box joined to the world by `kind` with the joint frame's X along `axis`, at `start`, moving at
/// `velocity` and spinning at `spin`.
fn rig(
    kind: impl Into<JointKind>,
    axis: Vec3,
    start: Vec3,
    velocity: Vec3,
    spin: Vec3,
) -> (Harness, usize) {
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let rotation = Quat::from_rotation_y(0.3);
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(1.5, Vec3::new(0.2, 0.1, 0.3)))
            .with_position(start)
            .with_rotation(rotation)
            .with_linear_velocity(velocity)
            .with_angular_velocity(spin),
    );
    let basis = basis_from_axis(axis).unwrap();
    let joint = Joint::from_world(
        kind,
        Pose::IDENTITY,
        Pose::new(start, rotation),
        start,
        start,
        basis,
    )
    .unwrap();
    h.join(joint, world, b);
    (h, b)
}

fn free_along(axes: &[Axis]) -> SixDofJoint {
    axes.iter().fold(SixDofJoint::locked(), |j, &a| {
        j.with_motion(a, AxisMotion::Free).unwrap()
    })
}

#[test]
fn free_along_x_alone_it_follows_the_prismatic_joint_to_1e_4_m() {
    let axis = Vec3::new(1.0, 1.0, 0.3).normalize();
    let start = Vec3::new(0.0, 3.0, 0.0);
    // Pushed across the axis and spun, so the locks work.
    let (velocity, spin) = (Vec3::new(-1.0, 0.5, 2.0), Vec3::new(0.5, -1.0, 2.0));
    let (mut p, bp) = rig(PrismaticJoint::new(), axis, start, velocity, spin);
    let (mut s, bs) = rig(free_along(&[Axis::LinearX]), axis, start, velocity, spin);
    let mut worst = 0.0f32;
    for _ in 0..180 {
        p.step(DT);
        s.step(DT);
        worst = worst.max((p.bodies[bp].position() - s.bodies[bs].position()).length());
    }
    // It did slide (gravity along the axis over 3 s).
    assert!((p.bodies[bp].position() - start).length() > 5.0);
    assert!(worst < 1e-4, "trajectories {worst} m apart");
}

#[test]
fn a_velocity_drive_reaches_its_target_speed_linear_and_angular() {
    // Linear: 0.8 m/s up a 45° slide with 100 N (weight along it 10.4 N).
    let axis = Vec3::new(1.0, 1.0, 0.0).normalize();
    let drive = AxisDrive::Velocity {
        target_speed: 0.8,
        max_force: 100.0,
    };
    let joint = free_along(&[Axis::LinearX])
        .with_drive(Axis::LinearX, Some(drive))
        .unwrap();
    let (mut h, b) = rig(
        joint,
        axis,
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::ZERO,
        Vec3::ZERO,
    );
    for _ in 0..30 {
        h.step(DT);
    }
    let speed = h.bodies[b].linear_velocity().dot(axis);
    assert!((speed - 0.8).abs() < 1e-3, "{speed} m/s");
    // Angular: the twist about X driven at 3 rad/s with the other rotations locked and the point held.
    let drive = AxisDrive::Velocity {
        target_speed: 3.0,
        max_force: 50.0,
    };
    let joint = free_along(&[Axis::AngularX])
        .with_drive(Axis::AngularX, Some(drive))
        .unwrap();
    let (mut h, b) = rig(
        joint,
        Vec3::Z,
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::ZERO,
        Vec3::ZERO,
    );
    for _ in 0..30 {
        h.step(DT);
    }
    let spin = h.bodies[b].angular_velocity();
    assert!((spin.z - 3.0).abs() < 1e-2, "{spin:?} rad/s");
    assert!(spin.truncate().length() < 1e-2, "{spin:?}");
}

#[test]
fn a_velocity_drive_accelerates_at_its_force_cap() {
    // 3 N against 1.5 kg in zero gravity: 2 m/s² — after 0.5 s, 1 m/s of a 10 m/s target.
    let drive = AxisDrive::Velocity {
        target_speed: 10.0,
        max_force: 3.0,
    };
    let joint = free_along(&[Axis::LinearX])
        .with_drive(Axis::LinearX, Some(drive))
        .unwrap();
    let mut h = Harness::zero_gravity();
    let world = h.world_anchor();
    let b = h.add(&BodyDesc::dynamic().with_mass_properties(cuboid(1.5, Vec3::splat(0.2))));
    h.join(Joint::new(joint), world, b);
    for _ in 0..30 {
        h.step(DT);
    }
    let speed = h.bodies[b].linear_velocity().x;
    assert!((speed - 1.0).abs() < 1e-3, "{speed} m/s");
}

#[test]
fn a_position_drive_brings_the_axis_to_its_target() {
    let drive = AxisDrive::Position {
        target: 0.4,
        spring: SoftSpring::frequency(3.0, 1.0).unwrap(),
        max_force: f32::INFINITY,
    };
    let joint = free_along(&[Axis::AngularY])
        .with_drive(Axis::AngularY, Some(drive))
        .unwrap();
    let mut h = Harness::zero_gravity();
    let world = h.world_anchor();
    let b = h.add(&BodyDesc::dynamic().with_mass_properties(cuboid(1.5, Vec3::splat(0.2))));
    h.join(Joint::new(joint), world, b);
    for _ in 0..180 {
        h.step(DT);
    }
    // A turn of 0.4 rad about y and nothing else.
    let angle = h.bodies[b]
        .rotation()
        .angle_between(Quat::from_rotation_y(0.4));
    assert!(angle < 1e-3, "{angle} rad from the target");
}

#[test]
fn a_limited_axis_holds_its_range() {
    // Linear: the 45° slide limited to [−1, 0.5] m, released moving down it at 2 m/s.
    let axis = Vec3::new(1.0, 1.0, 0.0).normalize();
    let start = Vec3::new(0.0, 3.0, 0.0);
    let limited = SixDofJoint::locked()
        .with_motion(
            Axis::LinearX,
            AxisMotion::Limited(Limits::new(-1.0, 0.5).unwrap()),
        )
        .unwrap();
    let (mut h, b) = rig(limited, axis, start, axis * -2.0, Vec3::ZERO);
    let mut lowest = f32::MAX;
    for _ in 0..120 {
        h.step(DT);
        lowest = lowest.min((h.bodies[b].position() - start).dot(axis));
    }
    assert!(lowest > -1.0 - 0.01, "passed the lower limit: {lowest} m");
    assert!(lowest < -0.99, "never reached the limit: {lowest} m");
    // Angular: a box hanging 0.5 m below a pivot, its swing about Z limited to ±0.3 rad, released swinging.
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let pivot = Vec3::new(0.0, 2.0, 0.0);
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(1.0, Vec3::new(0.05, 0.25, 0.05)))
            .with_position(pivot - Vec3::Y * 0.5)
            .with_angular_velocity(Vec3::Z * 4.0)
            .with_linear_velocity(Vec3::new(2.0, 0.0, 0.0)),
    );
    let swinging = SixDofJoint::locked()
        .with_motion(
            Axis::AngularZ,
            AxisMotion::Limited(Limits::new(-0.3, 0.3).unwrap()),
        )
        .unwrap();
    let joint = Joint::new(swinging)
        .with_local_anchors(pivot, Vec3::Y * 0.5)
        .unwrap();
    h.join(joint, world, b);
    let mut worst = 0.0f32;
    for _ in 0..180 {
        h.step(DT);
        let (axis, angle) = h.bodies[b].rotation().to_axis_angle();
        worst = worst.max((axis.z * angle).abs());
    }
    assert!(worst < 0.3 + 0.01, "swung to {worst} rad");
    assert!(worst > 0.29, "never reached the limit: {worst} rad");
}

#[test]
fn bad_axis_settings_are_refused_naming_the_axis_and_field() {
    let err = SixDofJoint::new()
        .with_motion(
            Axis::AngularY,
            AxisMotion::Limited(Limits::new(-4.0, 0.0).unwrap()),
        )
        .unwrap_err();
    assert!(
        matches!(
            err,
            ConstraintError::OutOfRange {
                field: "angular_y.lower",
                ..
            }
        ),
        "{err}"
    );
    let drive = AxisDrive::Velocity {
        target_speed: 1.0,
        max_force: -1.0,
    };
    let err = SixDofJoint::new()
        .with_drive(Axis::LinearZ, Some(drive))
        .unwrap_err();
    assert!(err.to_string().contains("linear_z.max_force"), "{err}");
    let drive = AxisDrive::Position {
        target: f32::INFINITY,
        spring: SoftSpring::default(),
        max_force: 1.0,
    };
    let err = SixDofJoint::new()
        .with_drive(Axis::LinearX, Some(drive))
        .unwrap_err();
    assert!(err.to_string().contains("linear_x.target"), "{err}");
    // A failing setter changes nothing.
    let mut joint = SixDofJoint::locked();
    let before = joint;
    assert!(joint.set_drive(Axis::AngularZ, Some(drive)).is_err());
    assert_eq!(joint, before);
}
