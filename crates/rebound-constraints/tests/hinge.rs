//! Hinge joints (course item 6): a physical pendulum keeps its axis and pivot and swings with the period
//! 2π√(I_p/(m·g·d)); angle limits hold within 1°; a motor spins a disk up at τ/I to its target speed; an
//! angular spring oscillates with the period 2π√(I/k).

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use core::f64::consts::TAU;
use rebound_constraints::{
    HingeJoint, Joint, JointSpring, Motor, SoftSpring, basis_from_axis, twist_angle,
};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::{Pose, Quat, Vec3};
use support::Harness;

const DT: f32 = 1.0 / 60.0;

/// A box of `mass` and half extents `half` (principal inertia m/3·(b² + c²), …).
fn cuboid(mass: f32, half: Vec3) -> MassProperties {
    let h2 = half * half;
    let inertia = Vec3::new(h2.y + h2.z, h2.x + h2.z, h2.x + h2.y) * (mass / 3.0);
    MassProperties::new(mass, Vec3::ZERO, inertia).unwrap()
}

const HALF: Vec3 = Vec3::new(0.05, 0.5, 0.05);
const PIVOT: Vec3 = Vec3::new(0.0, 2.0, 0.0);

/// A 2 kg bar hanging from a hinge about z at its top end, turned by `angle` about the pivot, with `joint`'s
/// frame at the hanging pose so that the hinge angle is 0 when the bar hangs straight down.
fn pendulum(hinge: HingeJoint, angle: f32, spin: Vec3) -> (Harness, usize, usize) {
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let rotation = Quat::from_rotation_z(angle);
    let center = PIVOT + rotation * Vec3::new(0.0, -HALF.y, 0.0);
    // Spinning about the pivot: v = ω × (c − pivot).
    let bar = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(2.0, HALF))
            .with_position(center)
            .with_rotation(rotation)
            .with_angular_velocity(spin)
            .with_linear_velocity(spin.cross(center - PIVOT)),
    );
    // The frame is defined at the hanging pose (angle 0), then the bar is turned.
    let hanging = Pose::new(PIVOT + Vec3::new(0.0, -HALF.y, 0.0), Quat::IDENTITY);
    let basis = basis_from_axis(Vec3::Z).unwrap();
    let joint = Joint::from_world(hinge, Pose::IDENTITY, hanging, PIVOT, PIVOT, basis).unwrap();
    let j = h.join(joint, world, bar);
    (h, bar, j)
}

fn hinge_angle(h: &Harness, bar: usize, j: usize) -> f32 {
    let joint = &h.joints[j];
    twist_angle(
        joint.local_basis_a(),
        h.bodies[bar].rotation() * joint.local_basis_b(),
    )
}

/// Times of upward zero crossings of x(t), linearly interpolated.
fn upward_crossings(samples: &[(f64, f64)]) -> Vec<f64> {
    samples
        .windows(2)
        .filter(|w| w[0].1 < 0.0 && w[1].1 >= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (-w[0].1) / (w[1].1 - w[0].1))
        .collect()
}

fn period(samples: &[(f64, f64)]) -> f64 {
    let c = upward_crossings(samples);
    assert!(c.len() >= 3, "only {} crossings", c.len());
    (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64
}

#[test]
fn a_hinged_bar_keeps_its_axis_and_pivot_and_swings_with_the_physical_pendulum_period() {
    // Released from 10° with a disturbing spin about x and y that the hinge must remove.
    let (mut h, bar, j) = pendulum(
        HingeJoint::new(),
        10f32.to_radians(),
        Vec3::new(0.4, -0.3, 0.0),
    );
    let (m, d, g) = (2.0f64, f64::from(HALF.y), 9.81f64);
    let i_pivot = m / 3.0 * f64::from(HALF.x * HALF.x + HALF.y * HALF.y) + m * d * d;
    let expected = TAU * (i_pivot / (m * g * d)).sqrt();
    let local_pivot = h.joints[j].local_anchor_b();
    let (mut worst_gap, mut worst_axis) = (0.0f32, 0.0f32);
    let mut samples = Vec::new();
    for step in 1..=480 {
        h.step(DT);
        let body = &h.bodies[bar];
        let gap = (body.pose().transform_point(local_pivot) - PIVOT).length();
        let axis = body.rotation() * Vec3::Z;
        let axis_error = axis.cross(Vec3::Z).length().atan2(axis.dot(Vec3::Z));
        worst_gap = worst_gap.max(gap);
        worst_axis = worst_axis.max(axis_error);
        samples.push((
            f64::from(step) * f64::from(DT),
            f64::from(hinge_angle(&h, bar, j)),
        ));
    }
    let measured = period(&samples);
    println!(
        "hinged bar: period {measured:.4} s vs 2π√(I/(mgd)) = {expected:.4} s; pivot gap ≤ {worst_gap:.2e} m, axis error ≤ {worst_axis:.2e} rad"
    );
    assert!(
        (measured - expected).abs() < 0.015 * expected,
        "period {measured} vs {expected}"
    );
    assert!(worst_gap < 1e-3, "pivot gap {worst_gap} m");
    assert!(worst_axis < 2e-3, "axis error {worst_axis} rad");
}

#[test]
fn hinge_limits_hold_within_one_degree() {
    // Kicked at 6 rad/s about the pivot (12 J, while reaching 30° takes 1.3 J) into limits of ±30°.
    let limit = 30f32.to_radians();
    let (mut h, bar, j) = pendulum(
        HingeJoint::new().with_limits(-limit, limit).unwrap(),
        0.0,
        Vec3::new(0.0, 0.0, 6.0),
    );
    let (mut low, mut high) = (0.0f32, 0.0f32);
    for _ in 0..300 {
        h.step(DT);
        let angle = hinge_angle(&h, bar, j);
        low = low.min(angle);
        high = high.max(angle);
    }
    println!(
        "limits ±30°: angle stayed in [{:.3}°, {:.3}°]",
        low.to_degrees(),
        high.to_degrees()
    );
    assert!(
        high > limit - 1f32.to_radians(),
        "never reached the upper limit: {high}"
    );
    assert!(
        high < limit + 1f32.to_radians(),
        "upper limit exceeded: {}°",
        high.to_degrees()
    );
    assert!(
        low > -limit - 1f32.to_radians(),
        "lower limit exceeded: {}°",
        low.to_degrees()
    );
}

/// A 4 kg disk of radius 0.5 m (I = ½·m·r² = 0.5 kg·m² about z) on a hinge about z through its centre.
fn disk(hinge: HingeJoint, spin: f32) -> (Harness, usize) {
    let mut h = Harness::new(SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    });
    let world = h.world_anchor();
    let (m, r) = (4.0f32, 0.5f32);
    let inertia = Vec3::new(m * r * r / 4.0, m * r * r / 4.0, m * r * r / 2.0);
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(m, Vec3::ZERO, inertia).unwrap())
            .with_position(Vec3::new(1.0, 1.0, 0.0))
            .with_angular_velocity(Vec3::new(0.0, 0.0, spin)),
    );
    let joint = Joint::new(hinge)
        .with_local_anchors(Vec3::new(1.0, 1.0, 0.0), Vec3::ZERO)
        .unwrap()
        .with_local_axes(Vec3::Z, Vec3::Z)
        .unwrap();
    h.join(joint, world, b);
    (h, b)
}

#[test]
fn a_hinge_motor_spins_a_disk_up_at_torque_over_inertia_to_its_target_speed() {
    // τ = 2 N·m on I = 0.5 kg·m²: ω = 4 rad/s² · t until the 5 rad/s target at t = 1.25 s.
    let (target, torque, inertia) = (5.0f32, 2.0f32, 0.5f32);
    let (mut h, b) = disk(
        HingeJoint::new().with_motor(Motor::new(target, torque).unwrap()),
        0.0,
    );
    for step in 1..=120 {
        h.step(DT);
        let t = step as f32 * DT;
        let expected = (torque / inertia * t).min(target);
        let omega = h.bodies[b].angular_velocity();
        assert!(
            (omega.z - expected).abs() < 1e-3 * target,
            "t = {t:.3} s: ω = {} rad/s, expected {expected}",
            omega.z
        );
        assert!(
            omega.truncate().length() < 1e-5,
            "spin off the axis: {omega}"
        );
    }
    // The motor's torque is reported: at the target it carries none.
    assert!(
        h.states[0].reaction_torque < 1e-2,
        "{}",
        h.states[0].reaction_torque
    );
}

#[test]
fn a_hinge_spring_oscillates_with_period_two_pi_root_i_over_k() {
    // k = 8 N·m/rad on I = 0.5 kg·m²: T = 2π√(I/k) = 1.5708 s.
    let (k, inertia) = (8.0f64, 0.5f64);
    let spring = JointSpring::new(0.0, SoftSpring::stiffness(k as f32, 0.0).unwrap()).unwrap();
    let (mut h, b) = disk(HingeJoint::new().with_spring(spring), 1.0);
    let mut samples = Vec::new();
    for step in 1..=360 {
        h.step(DT);
        let angle = twist_angle(
            h.joints[0].local_basis_a(),
            h.bodies[b].rotation() * h.joints[0].local_basis_b(),
        );
        samples.push((f64::from(step) * f64::from(DT), f64::from(angle)));
    }
    let expected = TAU * (inertia / k).sqrt();
    let measured = period(&samples);
    println!("hinge spring: period {measured:.4} s vs 2π√(I/k) = {expected:.4} s");
    assert!((measured - expected).abs() < 0.01 * expected);
}
