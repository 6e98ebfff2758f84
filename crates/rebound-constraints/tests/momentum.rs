//! Conservation (course item 9): the impulses of every joint kind conserve the linear momentum of the pair and
//! its angular momentum about the origin when neither body is fixed — property-tested over random bodies,
//! velocities, anchors and parameters, through every solver stage that applies impulses (apply forces, warm
//! start, solve, relax, restitution).

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use rebound_constraints::{
    BallJoint, FixedJoint, HingeJoint, Joint, JointBodies, JointKind, JointSolver, JointState,
    Limits, Motor, PrismaticJoint, Rod, Rope, SoftSpring, Spring, SpringModel, WheelJoint,
};
use rebound_dynamics::contact::Bias;
use rebound_dynamics::{
    BodyDesc, BodyParams, MassProperties, RigidBody, SolverBody, SolverSettings, StepContext,
};
use rebound_math::{Pose, Quat, Vec3};

fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn rotation() -> impl Strategy<Value = Quat> {
    (vec3(1.0), 0.0f32..3.0).prop_map(|(axis, angle)| {
        axis.try_normalize()
            .map_or(Quat::IDENTITY, |a| Quat::from_axis_angle(a, angle))
    })
}

#[derive(Debug, Clone)]
struct Body {
    mass: f32,
    inertia: Vec3,
    pose: Pose,
    velocity: Vec3,
    spin: Vec3,
}

fn body() -> impl Strategy<Value = Body> {
    (
        0.2f32..5.0,
        vec3(1.0),
        vec3(3.0),
        rotation(),
        vec3(4.0),
        vec3(3.0),
    )
        .prop_map(|(mass, inertia, position, rotation, velocity, spin)| Body {
            mass,
            inertia: inertia.abs() * mass + Vec3::splat(0.05 * mass),
            pose: Pose::new(position, rotation),
            velocity,
            spin,
        })
}

/// A joint kind with random parameters, and whether its anchors must coincide at the start (the point joints,
/// whose linear impulse acts at two different points otherwise).
fn kind() -> impl Strategy<Value = (JointKind, bool)> {
    prop_oneof![
        (0.0f32..3.0, 1.0f32..500.0, 0.0f32..5.0).prop_map(|(l, k, c)| (
            Spring::new(l, SpringModel::soft_stiffness(k, c).unwrap())
                .unwrap()
                .into(),
            false
        )),
        (0.0f32..3.0, 1.0f32..500.0, 0.0f32..5.0).prop_map(|(l, k, c)| (
            Spring::new(l, SpringModel::force(k, c).unwrap())
                .unwrap()
                .into(),
            false
        )),
        (0.1f32..3.0, 0.0f32..1.0).prop_map(|(l, e)| (
            Rope::new(l).unwrap().with_restitution(e).unwrap().into(),
            false
        )),
        (0.1f32..3.0).prop_map(|l| (Rod::new(l).unwrap().into(), false)),
        Just((BallJoint::new().into(), true)),
        (-1.0f32..0.0, 0.0f32..1.0, -3.0f32..3.0, 0.0f32..20.0).prop_map(
            |(lo, hi, speed, torque)| (
                HingeJoint::new()
                    .with_limits(lo, hi)
                    .unwrap()
                    .with_motor(Motor::new(speed, torque).unwrap())
                    .into(),
                true
            )
        ),
        Just((FixedJoint::new().into(), true)),
        (-0.5f32..0.0, 0.0f32..0.5, -3.0f32..3.0, 0.0f32..20.0).prop_map(
            |(lo, hi, speed, force)| (
                PrismaticJoint::new()
                    .with_limits(Limits::new(lo, hi).unwrap())
                    .with_motor(Motor::new(speed, force).unwrap())
                    .into(),
                false
            )
        ),
        (1.0f32..10.0, -3.0f32..3.0).prop_map(|(hz, speed)| (
            WheelJoint::new(SoftSpring::frequency(hz, 0.5).unwrap())
                .unwrap()
                .with_motor(Motor::new(speed, 10.0).unwrap())
                .into(),
            false
        )),
    ]
}

fn rigid(b: &Body) -> RigidBody {
    RigidBody::new(
        &BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(b.mass, Vec3::ZERO, b.inertia).unwrap())
            .with_position(b.pose.position)
            .with_rotation(b.pose.rotation)
            .with_linear_velocity(b.velocity)
            .with_angular_velocity(b.spin),
    )
    .unwrap()
}

/// Linear momentum and angular momentum about the origin of the solver bodies, with the start-of-step world
/// inertia the solver uses (`I = (I⁻¹_world)⁻¹`).
fn momenta(states: &[SolverBody], params: &[BodyParams]) -> (Vec3, Vec3) {
    let mut linear = Vec3::ZERO;
    let mut angular = Vec3::ZERO;
    for (s, p) in states.iter().zip(params) {
        let m = 1.0 / p.inv_mass;
        let center = p.center_of_mass + s.delta_position;
        linear += s.linear_velocity * m;
        angular += center.cross(s.linear_velocity * m)
            + p.inv_inertia_world.inverse() * s.angular_velocity;
    }
    (linear, angular)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 400,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource("proptest-regressions"))),
        ..ProptestConfig::default()
    })]
    #[test]
    fn joint_impulses_conserve_linear_and_angular_momentum(
        a in body(),
        b in body(),
        (kind, coincide) in kind(),
        anchor_a in vec3(0.6),
        anchor_b in vec3(0.6),
        basis in rotation(),
        warm in (-2.0f32..2.0, -2.0f32..2.0),
    ) {
        let bodies = [rigid(&a), rigid(&b)];
        let world_anchor_a = a.pose.transform_point(anchor_a);
        let world_anchor_b = if coincide { world_anchor_a } else { b.pose.transform_point(anchor_b) };
        let joint = Joint::from_world(kind, a.pose, b.pose, world_anchor_a, world_anchor_b, basis).unwrap();
        // Some warm-start impulses, within each row's sign (rope ≤ 0, lower limit ≥ 0).
        let state = JointState {
            linear_impulse: Vec3::new(warm.0, warm.1, 0.0) * 0.1,
            angular_impulse: Vec3::new(warm.1, warm.0, 0.0) * 0.05,
            axial_impulse: warm.0 * 0.1,
            lower_impulse: warm.1.abs() * 0.1,
            upper_impulse: -warm.0.abs() * 0.1,
            motor_impulse: warm.1 * 0.1,
            ..JointState::default()
        };
        let ctx = StepContext::new(1.0 / 60.0, &SolverSettings { gravity: Vec3::ZERO, ..SolverSettings::default() });
        let mut states: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
        let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
        let mut solver = JointSolver::new();
        let skipped = solver.prepare(&[joint], &[state], &[JointBodies { a: 0, b: 1 }], &states, &params, &ctx);
        prop_assert_eq!(skipped, 0);
        let (p0, l0) = momenta(&states, &params);
        solver.apply_forces(&mut states, &ctx);
        solver.warm_start(&mut states);
        solver.solve(&mut states, &ctx, Bias::On);
        solver.solve(&mut states, &ctx, Bias::Off);
        solver.apply_restitution(&mut states, &ctx);
        let (p1, l1) = momenta(&states, &params);
        // Scale: the momenta involved, including the change the joint made.
        let scale = 1.0 + p0.length() + l0.length() + momenta_change(&states, &bodies, &params);
        prop_assert!((p1 - p0).length() < 1e-4 * scale, "linear momentum {} → {} ({:?})", p0, p1, joint.kind());
        prop_assert!((l1 - l0).length() < 2e-4 * scale, "angular momentum {} → {} ({:?})", l0, l1, joint.kind());
    }
}

/// How much the solver changed the bodies' momenta (kg·m/s), to scale the tolerance.
fn momenta_change(states: &[SolverBody], bodies: &[RigidBody], params: &[BodyParams]) -> f32 {
    states
        .iter()
        .zip(bodies)
        .zip(params)
        .map(|((s, b), p)| {
            (s.linear_velocity - b.linear_velocity()).length() / p.inv_mass
                + (p.inv_inertia_world.inverse() * (s.angular_velocity - b.angular_velocity()))
                    .length()
        })
        .sum()
}
