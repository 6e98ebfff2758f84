//! The solver interface: malformed input is skipped and counted, never a panic; break limits disable a joint
//! and report it; the reported reaction force is the load the joint carries; coinciding anchors give no NaN;
//! the same calls give the same bits.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use rebound_constraints::{
    BallJoint, FixedJoint, HingeJoint, Joint, JointBodies, JointSolver, JointState, Motor, Rod,
    Rope, Spring, SpringModel,
};
use rebound_dynamics::contact::Bias;
use rebound_dynamics::{
    BodyDesc, BodyParams, MassProperties, RigidBody, SolverBody, SolverSettings, StepContext,
};
use rebound_math::Vec3;
use support::Harness;

const DT: f32 = 1.0 / 60.0;

fn heavy_ball(position: Vec3) -> BodyDesc {
    BodyDesc::dynamic()
        .with_mass_properties(MassProperties::new(10.0, Vec3::ZERO, Vec3::splat(0.1)).unwrap())
        .with_position(position)
}

#[test]
fn prepare_skips_and_counts_malformed_joints_and_no_stage_panics() {
    let bodies = [
        RigidBody::new(&BodyDesc::fixed()).unwrap(),
        RigidBody::new(&BodyDesc::dynamic().with_position(Vec3::new(0.0, -1.0, 0.0))).unwrap(),
    ];
    let states: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
    let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
    let rope = Joint::new(Rope::new(1.0).unwrap());
    let joints = [rope; 6];
    let broken = JointState {
        broken: true,
        ..JointState::default()
    };
    // Five states for six joints: the sixth has none.
    let joint_states = [
        JointState::default(),
        JointState::default(),
        JointState::default(),
        JointState::default(),
        broken,
    ];
    let pairs = [
        JointBodies { a: 0, b: 1 }, // valid
        JointBodies { a: 1, b: 1 }, // the same body twice
        JointBodies { a: 2, b: 1 }, // out of range
        JointBodies {
            a: 0,
            b: usize::MAX,
        },
        JointBodies { a: 0, b: 1 }, // broken
        JointBodies { a: 0, b: 1 }, // no state
    ];
    let ctx = StepContext::new(DT, &SolverSettings::default());
    let mut solver = JointSolver::new();
    let skipped = solver.prepare(&joints, &joint_states, &pairs, &states, &params, &ctx);
    assert_eq!(skipped, 5);
    assert_eq!(solver.len(), 1);
    // Fewer pairs than joints, and params shorter than the solver bodies: counted, not a panic.
    assert_eq!(
        solver.prepare(
            &joints,
            &joint_states,
            &pairs[..2],
            &states,
            &params[..1],
            &ctx
        ),
        6
    );
    assert!(solver.is_empty());

    // Stages called with slices other than the prepared ones: out-of-range bodies are skipped.
    solver.prepare(
        &joints[..1],
        &joint_states[..1],
        &pairs[..1],
        &states,
        &params,
        &ctx,
    );
    let mut empty: Vec<SolverBody> = Vec::new();
    solver.apply_forces(&mut empty, &ctx);
    solver.warm_start(&mut empty);
    solver.solve(&mut empty, &ctx, Bias::On);
    solver.solve(&mut empty, &ctx, Bias::Off);
    solver.apply_restitution(&mut empty, &ctx);
    let mut no_states: Vec<JointState> = Vec::new();
    let mut broken_list = Vec::new();
    solver.store_impulses(&mut no_states, &mut broken_list);
    assert!(broken_list.is_empty());
}

#[test]
fn the_reaction_force_is_the_load_and_a_joint_over_its_break_force_breaks() {
    // A 10 kg ball at rest on a 1 m rope: the rope carries m·g = 98.1 N.
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let b = h.add(&heavy_ball(Vec3::new(0.0, -1.0, 0.0)));
    let rope = h.join(Joint::new(Rope::new(1.0).unwrap()), world, b);
    for _ in 0..30 {
        assert_eq!(h.step(DT), 0);
    }
    let force = h.states[rope].reaction_force;
    assert!((force - 98.1).abs() < 0.01 * 98.1, "rope force {force} N");
    assert!(h.broken.is_empty());

    // The same with a 50 N break force: it breaks in the first step, is reported once, then skipped, and the
    // ball falls freely (Δv = g·dt per step).
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let b = h.add(&heavy_ball(Vec3::new(0.0, -1.0, 0.0)));
    h.join(
        Joint::new(Rope::new(1.0).unwrap())
            .with_break_force(50.0)
            .unwrap(),
        world,
        b,
    );
    h.step(DT);
    assert_eq!(h.broken, vec![0]);
    assert!(h.states[0].broken && h.states[0].reaction_force > 50.0);
    let mut v = h.bodies[b].linear_velocity().y;
    for _ in 0..10 {
        assert_eq!(h.step(DT), 1, "the broken joint is skipped");
        let v1 = h.bodies[b].linear_velocity().y;
        assert!(
            (v1 - v + 9.81 * DT).abs() < 1e-4,
            "not in free fall: Δv = {}",
            v1 - v
        );
        v = v1;
    }
    assert_eq!(h.broken, vec![0], "reported once");

    // A break torque: a motor holding a hinge against 20 N·m with a 10 N·m break torque.
    let mut h = Harness::new(SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    });
    let world = h.world_anchor();
    let b = h.add(&BodyDesc::dynamic().with_angular_velocity(Vec3::new(0.0, 0.0, 50.0)));
    h.join(
        Joint::new(HingeJoint::new().with_motor(Motor::new(0.0, 100.0).unwrap()))
            .with_local_axes(Vec3::Z, Vec3::Z)
            .unwrap()
            .with_break_torque(10.0)
            .unwrap(),
        world,
        b,
    );
    h.step(DT);
    assert_eq!(h.broken, vec![0]);
    assert!(h.states[0].reaction_torque > 10.0);
}

#[test]
fn coinciding_anchors_give_no_nan() {
    // Every distance-type joint and a ball joint with both anchors on the same point, pulled about.
    let kinds: [Joint; 5] = [
        Joint::new(Spring::new(0.0, SpringModel::soft_frequency(5.0, 0.5).unwrap()).unwrap()),
        Joint::new(Spring::new(0.0, SpringModel::force(50.0, 1.0).unwrap()).unwrap()),
        Joint::new(Rope::new(0.0).unwrap()),
        Joint::new(Rod::new(0.5).unwrap()),
        Joint::new(BallJoint::new()),
    ];
    for joint in kinds {
        let mut h = Harness::new(SolverSettings::default());
        let a = h.add(&BodyDesc::dynamic().with_angular_velocity(Vec3::new(1.0, 2.0, 3.0)));
        let b = h.add(&BodyDesc::dynamic().with_linear_velocity(Vec3::new(0.0, 0.0, 1e-3)));
        h.join(joint, a, b);
        for _ in 0..60 {
            h.step(DT);
        }
        for body in &h.bodies {
            assert!(
                body.position().is_finite() && body.linear_velocity().is_finite(),
                "{joint:?}"
            );
        }
        let s = h.states[0];
        assert!(
            s.linear_impulse.is_finite()
                && s.axial_impulse.is_finite()
                && s.upper_impulse.is_finite()
        );
    }
}

#[test]
fn the_same_calls_give_the_same_bits() {
    let run = || {
        let mut h = Harness::new(SolverSettings::default());
        let world = h.world_anchor();
        let mut previous = world;
        for i in 0..8 {
            let b = h.add(
                &BodyDesc::dynamic()
                    .with_position(Vec3::new(0.3 * (i + 1) as f32, -0.1 * i as f32, 0.0))
                    .with_angular_velocity(Vec3::new(0.1, 0.0, 0.2 * i as f32)),
            );
            let joint = match i % 4 {
                0 => Joint::new(Rope::new(0.3).unwrap()),
                1 => Joint::new(BallJoint::new())
                    .with_local_anchors(Vec3::new(0.15, 0.0, 0.0), Vec3::new(-0.15, 0.0, 0.0))
                    .unwrap(),
                2 => Joint::new(HingeJoint::new())
                    .with_local_anchors(Vec3::new(0.15, 0.0, 0.0), Vec3::new(-0.15, 0.0, 0.0))
                    .unwrap(),
                _ => Joint::new(FixedJoint::new())
                    .with_local_anchors(Vec3::new(0.15, 0.0, 0.0), Vec3::new(-0.15, 0.0, 0.0))
                    .unwrap(),
            };
            h.join(joint, previous, b);
            previous = b;
        }
        for _ in 0..120 {
            h.step(DT);
        }
        h.bodies
            .iter()
            .flat_map(|b| {
                let mut bits = b.position().to_array().map(f32::to_bits).to_vec();
                bits.extend(b.rotation().to_array().map(f32::to_bits));
                bits
            })
            .collect::<Vec<u32>>()
    };
    assert_eq!(run(), run());
}

#[test]
fn a_world_anchor_given_as_body_params_world_works_like_a_fixed_body_at_the_origin() {
    // The world's way of expressing a world-point anchor: `SolverBody::STATIC` with `BodyParams::WORLD`, so
    // that `local_anchor_a` is the world point. Same bits as a fixed body at the origin in the harness.
    let pivot = Vec3::new(0.5, 3.0, -1.0);
    let joint = Joint::new(Rope::new(2.0).unwrap())
        .with_local_anchors(pivot, Vec3::new(0.1, 0.0, 0.0))
        .unwrap();
    let start = BodyDesc::dynamic()
        .with_position(pivot + Vec3::new(1.5, -1.2, 0.3))
        .with_angular_velocity(Vec3::new(0.0, 1.0, 0.5));

    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let b = h.add(&start);
    h.join(joint, world, b);

    let settings = SolverSettings::default();
    let mut body = RigidBody::new(&start).unwrap();
    let mut states = [JointState::default()];
    let mut solver = JointSolver::new();
    let mut broken = Vec::new();
    for step in 0..120 {
        h.step(DT);
        let ctx = StepContext::new(DT, &settings);
        let mut solver_bodies = vec![SolverBody::STATIC, SolverBody::from_body(&body)];
        let params = [BodyParams::WORLD, BodyParams::from_body(&body)];
        let skipped = solver.prepare(
            &[joint],
            &states,
            &[JointBodies { a: 0, b: 1 }],
            &solver_bodies,
            &params,
            &ctx,
        );
        assert_eq!(skipped, 0);
        for _ in 0..ctx.substep_count {
            rebound_dynamics::integrate::integrate_velocities(&mut solver_bodies, &params, &ctx);
            solver.apply_forces(&mut solver_bodies, &ctx);
            solver.warm_start(&mut solver_bodies);
            solver.solve(&mut solver_bodies, &ctx, Bias::On);
            rebound_dynamics::integrate::integrate_positions(&mut solver_bodies, &params, &ctx);
            solver.solve(&mut solver_bodies, &ctx, Bias::Off);
        }
        solver.project_positions(&mut solver_bodies, &ctx);
        solver.apply_restitution(&mut solver_bodies, &ctx);
        solver.store_impulses(&mut states, &mut broken);
        assert!(params[1].write_back(&solver_bodies[1], &mut body));
        assert_eq!(
            solver_bodies[0],
            SolverBody::STATIC,
            "the world anchor moved"
        );
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        assert_eq!(
            bits(body.position()),
            bits(h.bodies[b].position()),
            "step {step}"
        );
        assert_eq!(
            bits(body.linear_velocity()),
            bits(h.bodies[b].linear_velocity()),
            "step {step}"
        );
    }
    // And the rope held: the anchor on the body stays within the rope's length of the world point.
    let tip = body.pose().transform_point(Vec3::new(0.1, 0.0, 0.0));
    assert!((tip - pivot).length() <= 2.0 * 1.005);
}
