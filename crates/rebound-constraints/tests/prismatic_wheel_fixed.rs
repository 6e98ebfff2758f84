//! Prismatic, wheel and fixed joints: a box sliding down an inclined prismatic axis follows the closed form
//! of its integrator and stays on the axis; limits stop it and a motor drives it at its speed; a wheel settles
//! at the static deflection m·g/k of its suspension and spins at its motor speed on a straight axle; welded
//! bodies keep their relative pose and their momentum.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use rebound_constraints::{
    FixedJoint, Joint, Limits, Motor, PrismaticJoint, SoftSpring, WheelJoint, basis_from_axes,
    basis_from_axis,
};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::{Pose, Quat, Vec3};
use support::Harness;

const DT: f32 = 1.0 / 60.0;
const SUBSTEPS: u32 = 4;

fn cuboid(mass: f32, half: Vec3) -> MassProperties {
    let h2 = half * half;
    let inertia = Vec3::new(h2.y + h2.z, h2.x + h2.z, h2.x + h2.y) * (mass / 3.0);
    MassProperties::new(mass, Vec3::ZERO, inertia).unwrap()
}

/// Angle between two vectors, accurate near 0 (rad).
fn angle(a: Vec3, b: Vec3) -> f32 {
    a.cross(b).length().atan2(a.dot(b))
}

/// A 1.5 kg box on a prismatic joint to the world along `axis` through `start`.
fn slider(joint: PrismaticJoint, axis: Vec3, start: Vec3, velocity: Vec3) -> (Harness, usize) {
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let rotation = Quat::from_rotation_y(0.3);
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(1.5, Vec3::new(0.2, 0.1, 0.3)))
            .with_position(start)
            .with_rotation(rotation)
            .with_linear_velocity(velocity),
    );
    let basis = basis_from_axis(axis).unwrap();
    let joint = Joint::from_world(
        joint,
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

#[test]
fn a_prismatic_slider_follows_gravity_along_its_axis_and_stays_on_it() {
    let axis = Vec3::new(1.0, 1.0, 0.0).normalize();
    let start = Vec3::new(0.5, 3.0, -1.0);
    let (mut h, b) = slider(PrismaticJoint::new(), axis, start, Vec3::ZERO);
    // Semi-implicit Euler under the axial component a = g·n: s = a·h²·n(n+1)/2 after n substeps.
    let a = f64::from(Vec3::new(0.0, -9.81, 0.0).dot(axis));
    let sub_h = f64::from(DT) / f64::from(SUBSTEPS);
    let rotation0 = h.bodies[b].rotation();
    let (mut worst_off, mut worst_turn) = (0.0f32, 0.0f32);
    for step in 1..=60u32 {
        h.step(DT);
        let n = f64::from(step * SUBSTEPS);
        let expected = a * sub_h * sub_h * n * (n + 1.0) / 2.0;
        let d = h.bodies[b].position() - start;
        let s = f64::from(d.dot(axis));
        assert!(
            (s - expected).abs() < 1e-4 * expected.abs().max(1.0),
            "step {step}: slid {s} m, closed form {expected} m"
        );
        worst_off = worst_off.max((d - axis * d.dot(axis)).length());
        worst_turn = worst_turn.max(rebound_math::quat::angle_between(
            rotation0,
            h.bodies[b].rotation(),
        ));
    }
    println!("prismatic: off the axis ≤ {worst_off:.2e} m, turned ≤ {worst_turn:.2e} rad");
    assert!(worst_off < 1e-4, "left the axis by {worst_off} m");
    assert!(worst_turn < 1e-4, "turned by {worst_turn} rad");
}

#[test]
fn prismatic_limits_stop_the_slider_and_a_motor_drives_it() {
    let axis = Vec3::new(1.0, 1.0, 0.0).normalize();
    let start = Vec3::new(0.0, 3.0, 0.0);
    let limits = Limits::new(-1.0, 0.5).unwrap();
    let (mut h, b) = slider(
        PrismaticJoint::new().with_limits(limits),
        axis,
        start,
        axis * -2.0,
    );
    let mut lowest = f32::MAX;
    for _ in 0..120 {
        h.step(DT);
        lowest = lowest.min((h.bodies[b].position() - start).dot(axis));
    }
    let rest = (h.bodies[b].position() - start).dot(axis);
    println!("prismatic limit −1 m: lowest {lowest:.5} m, at rest {rest:.6} m");
    assert!(lowest > -1.0 - 0.01, "passed the lower limit: {lowest} m");
    assert!(
        (rest + 1.0).abs() < 1e-3,
        "rests at {rest} m, not on the limit"
    );
    assert!(h.bodies[b].linear_velocity().length() < 1e-3);
    // The lower limit carries the weight's axial component m·g·sin 45° = 10.4 N.
    let weight_along = 1.5 * 9.81 * core::f32::consts::FRAC_1_SQRT_2;
    let limit_force = h.states[0].lower_impulse * SUBSTEPS as f32 / DT;
    assert!(
        (limit_force - weight_along).abs() < 0.01 * weight_along,
        "limit force {limit_force} N"
    );

    // A motor at 0.5 m/s up the axis with 100 N (> 10.4 N) drives it there, then the upper limit stops it.
    h.joints[0]
        .set_motor(Some(Motor::new(0.5, 100.0).unwrap()))
        .unwrap();
    for step in 0..60 {
        h.step(DT);
        let speed = h.bodies[b].linear_velocity().dot(axis);
        if step > 0 {
            assert!((speed - 0.5).abs() < 1e-3, "motor speed {speed} m/s");
        }
    }
    for _ in 0..240 {
        h.step(DT);
    }
    let top = (h.bodies[b].position() - start).dot(axis);
    assert!(
        (top - 0.5).abs() < 0.01,
        "the motor pushed it to {top} m against the 0.5 m limit"
    );
}

#[test]
fn a_wheel_settles_at_the_static_deflection_of_its_suspension_and_spins_at_its_motor_speed() {
    // A 10 kg wheel (r = 0.3 m) on a fixed chassis: suspension k = 2e4 N/m, c = 1e3 N·s/m, up = +y, axle z.
    let (m, r, k) = (10.0f32, 0.3f32, 2.0e4f32);
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let mount = Vec3::new(0.0, 1.0, 0.0);
    let inertia = Vec3::new(
        m * (3.0 * r * r + 0.04) / 12.0,
        m * (3.0 * r * r + 0.04) / 12.0,
        m * r * r / 2.0,
    );
    let wheel = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(m, Vec3::ZERO, inertia).unwrap())
            .with_position(mount),
    );
    let basis = basis_from_axes(Vec3::Z, Vec3::Y).unwrap();
    let joint = Joint::from_world(
        WheelJoint::new(SoftSpring::stiffness(k, 1.0e3).unwrap()).unwrap(),
        Pose::IDENTITY,
        Pose::from_position(mount),
        mount,
        mount,
        basis,
    )
    .unwrap();
    h.join(joint, world, wheel);
    for _ in 0..180 {
        h.step(DT);
    }
    let deflection = h.bodies[wheel].position().y - mount.y;
    let expected = -m * 9.81 / k;
    println!(
        "wheel: deflection {:.4} mm vs −m·g/k = {:.4} mm",
        deflection * 1e3,
        expected * 1e3
    );
    assert!(
        (deflection - expected).abs() < 0.005 * expected.abs(),
        "deflection {deflection} m vs {expected} m"
    );

    h.joints[0]
        .set_motor(Some(Motor::new(10.0, 50.0).unwrap()))
        .unwrap();
    // I_z = 0.45 kg·m², τ = 50 N·m: 10 rad/s after 0.09 s.
    let (mut worst_axle, mut worst_off) = (0.0f32, 0.0f32);
    for _ in 0..120 {
        h.step(DT);
        let body = &h.bodies[wheel];
        worst_axle = worst_axle.max(angle(body.rotation() * Vec3::Z, Vec3::Z));
        let p = body.position() - mount;
        worst_off = worst_off.max(Vec3::new(p.x, 0.0, p.z).length());
    }
    let spin = h.bodies[wheel].angular_velocity();
    println!(
        "wheel motor: ω = {spin}, axle error ≤ {worst_axle:.2e} rad, off the suspension line ≤ {worst_off:.2e} m"
    );
    assert!(
        (spin.z - 10.0).abs() < 1e-3,
        "wheel spins at {} rad/s",
        spin.z
    );
    assert!(spin.truncate().length() < 1e-3);
    assert!(worst_axle < 1e-3 && worst_off < 1e-4);
    let deflection = h.bodies[wheel].position().y - mount.y;
    assert!(
        (deflection - expected).abs() < 0.005 * expected.abs(),
        "deflection while driving {deflection} m"
    );
}

#[test]
fn welded_bodies_keep_their_relative_pose_and_their_momentum() {
    let mut h = Harness::new(SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    });
    let (ma, mb) = (2.0f32, 1.0f32);
    let pose_a = Pose::new(Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY);
    let pose_b = Pose::new(Vec3::new(1.0, 1.2, 0.0), Quat::from_rotation_y(0.5));
    let a = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(ma, Vec3::splat(0.3)))
            .with_position(pose_a.position)
            .with_linear_velocity(Vec3::new(1.0, 0.0, 0.0))
            .with_angular_velocity(Vec3::new(0.0, 2.0, 0.5)),
    );
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(mb, Vec3::new(0.4, 0.1, 0.2)))
            .with_position(pose_b.position)
            .with_rotation(pose_b.rotation)
            .with_linear_velocity(Vec3::new(-0.5, 0.3, 0.0)),
    );
    let weld = Vec3::new(0.5, 1.1, 0.0);
    let joint = Joint::from_world(
        FixedJoint::new(),
        pose_a,
        pose_b,
        weld,
        weld,
        Quat::IDENTITY,
    )
    .unwrap();
    h.join(joint, a, b);
    let relative = |h: &Harness| h.bodies[a].pose().inverse().mul_pose(&h.bodies[b].pose());
    let relative0 = relative(&h);
    let momentum =
        |h: &Harness| h.bodies[a].linear_velocity() * ma + h.bodies[b].linear_velocity() * mb;
    let momentum0 = momentum(&h);
    let (mut worst_offset, mut worst_turn) = (0.0f32, 0.0f32);
    for step in 1..=240 {
        h.step(DT);
        let p = momentum(&h);
        assert!(
            (p - momentum0).length() < 1e-4,
            "step {step}: momentum {p} vs {momentum0}"
        );
        if step > 10 {
            let r = relative(&h);
            worst_offset = worst_offset.max((r.position - relative0.position).length());
            worst_turn = worst_turn.max(rebound_math::quat::angle_between(
                relative0.rotation,
                r.rotation,
            ));
        }
    }
    println!(
        "weld: relative pose error ≤ {worst_offset:.2e} m, {worst_turn:.2e} rad after the first 10 steps"
    );
    assert!(worst_offset < 1e-3 && worst_turn < 1e-3);
}

#[test]
fn a_welded_cantilever_sags_by_less_than_a_millimetre() {
    // A 1 kg, 1 m long box welded at one end to the world: the soft joint's static error is the load over
    // its stiffness, m·g/(m_eff·ω²) ≈ 0.3 mm and (m·g·d)/(I·ω²) ≈ 0.4 mrad at 60 Hz.
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let half = Vec3::new(0.5, 0.1, 0.1);
    let center = Vec3::new(0.5, 2.0, 0.0);
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(1.0, half))
            .with_position(center),
    );
    let root = Vec3::new(0.0, 2.0, 0.0);
    let joint = Joint::from_world(
        FixedJoint::new(),
        Pose::IDENTITY,
        Pose::from_position(center),
        root,
        root,
        Quat::IDENTITY,
    )
    .unwrap();
    h.join(joint, world, b);
    for _ in 0..120 {
        h.step(DT);
    }
    let body = &h.bodies[b];
    let sag = (body.position() - center).length();
    let turn = rebound_math::quat::angle_between(Quat::IDENTITY, body.rotation());
    println!(
        "cantilever: sag {:.3} mm, turn {:.3} mrad",
        sag * 1e3,
        turn * 1e3
    );
    assert!(sag < 1e-3 && turn < 1e-3);
    assert!(body.linear_velocity().length() < 1e-3, "still moving");
}
