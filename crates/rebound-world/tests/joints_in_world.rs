//! Joints stepped by the world: a rope pendulum matches the constraints crate driven directly (bit for bit)
//! and the closed-form period; removing a body removes its joints and says so; a joint that breaks is
//! reported and disabled.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_constraints::{Joint, JointBodies, JointSolver, JointState, Rope};
use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};
use rebound_dynamics::{BodyDesc, BodyParams, MassProperties, RigidBody, SolverBody, StepContext};
use rebound_math::Vec3;
use rebound_world::{Event, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const LENGTH: f32 = 2.0;

fn pendulum_start() -> Vec3 {
    let angle = 10f32.to_radians();
    Vec3::new(LENGTH * angle.sin(), -LENGTH * angle.cos(), 0.0)
}

fn ball() -> BodyDesc {
    BodyDesc::dynamic()
        .with_position(pendulum_start())
        .with_mass_properties(MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.004)).unwrap())
}

fn rope() -> Joint {
    // Anchor A: the world origin; anchor B: the ball's centre.
    Joint::new(Rope::new(LENGTH).unwrap())
}

#[test]
fn a_rope_pendulum_in_the_world_matches_the_constraints_crate_and_the_closed_form() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let ball_handle = world.insert_body(&ball()).unwrap();
    world.insert_world_joint(rope(), ball_handle).unwrap();

    // The constraints crate driven by hand through the same stages, with a world anchor at index 0.
    let settings = WorldSettings::default();
    let mut body = RigidBody::new(&ball()).unwrap();
    let joints = [rope()];
    let mut states = [JointState::default()];
    let pairs = [JointBodies { a: 1, b: 0 }];
    let mut solver = JointSolver::new();
    let mut broken = Vec::new();

    let mut crossings = Vec::new();
    let mut previous_x = pendulum_start().x;
    let mut max_length = 0.0f32;
    for step in 0..600 {
        world.step(DT);
        // By hand:
        let ctx = StepContext::new(DT, &settings.solver_settings());
        let mut bodies = vec![SolverBody::from_body(&body), SolverBody::STATIC];
        let params = vec![BodyParams::from_body(&body), BodyParams::WORLD];
        assert_eq!(
            solver.prepare(&joints, &states, &pairs, &bodies, &params, &ctx),
            0
        );
        for _ in 0..ctx.substep_count {
            integrate_velocities(&mut bodies, &params, &ctx);
            solver.apply_forces(&mut bodies, &ctx);
            solver.warm_start(&mut bodies);
            solver.solve(&mut bodies, &ctx, Bias::On);
            integrate_positions(&mut bodies, &params, &ctx);
            solver.solve(&mut bodies, &ctx, Bias::Off);
        }
        solver.project_positions(&mut bodies, &ctx);
        solver.apply_restitution(&mut bodies, &ctx);
        solver.store_impulses(&mut states, &mut broken);
        assert!(params[0].write_back(&bodies[0], &mut body));

        let in_world = world.body(ball_handle).unwrap();
        assert_eq!(
            in_world.position(),
            body.position(),
            "world and constraints crate differ at step {step}"
        );
        assert_eq!(in_world.linear_velocity(), body.linear_velocity());

        let p = in_world.position();
        max_length = max_length.max(p.length());
        if previous_x > 0.0 && p.x <= 0.0 {
            // Linear interpolation of the crossing time.
            let t = (step as f32 + previous_x / (previous_x - p.x)) * DT;
            crossings.push(t);
        }
        previous_x = p.x;
    }
    assert!(
        max_length <= LENGTH * 1.005,
        "rope stretched to {max_length} m"
    );
    // Crossings of x = 0 in the same direction are one period apart.
    assert!(crossings.len() >= 3, "crossings {crossings:?}");
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f32;
    let expected = core::f32::consts::TAU * (LENGTH / 9.81).sqrt();
    // The small-angle period is exceeded by about 0.2 % at 10° (the finite-amplitude correction θ₀²/16).
    assert!(
        (period - expected).abs() < 0.015 * expected,
        "period {period} s vs 2π√(L/g) = {expected} s"
    );
}

#[test]
fn removing_a_body_removes_its_joints_and_says_so() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let a = world.insert_body(&BodyDesc::dynamic()).unwrap();
    let b = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::X))
        .unwrap();
    let c = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::X * 2.0))
        .unwrap();
    let ab = world.insert_joint(rope(), a, b).unwrap();
    let bc = world.insert_joint(rope(), b, c).unwrap();
    let world_joint = world.insert_world_joint(rope(), c).unwrap();
    let removed = world.remove_body(b).unwrap();
    let handles: Vec<_> = removed.joints.iter().map(|(h, _)| *h).collect();
    assert_eq!(handles, vec![ab, bc]);
    assert!(world.joint(ab).is_none() && world.joint(bc).is_none());
    assert!(world.joint(world_joint).is_some(), "unrelated joints stay");
    assert!(
        world.remove_joint(ab).is_err(),
        "a removed joint's handle is stale"
    );
    assert!(
        world.insert_joint(rope(), a, a).is_err(),
        "a joint needs two bodies"
    );
    assert!(world.insert_joint(rope(), a, b).is_err(), "b is gone");
}

#[test]
fn a_joint_that_exceeds_its_break_force_breaks_and_is_reported() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let weight = world.insert_body(&ball()).unwrap();
    // 1 kg hanging: the rope carries about 9.81 N. A 5 N limit breaks at once; the weight then falls freely.
    let joint = world
        .insert_world_joint(rope().with_break_force(5.0).unwrap(), weight)
        .unwrap();
    let mut broke_at = None;
    for step in 0..120 {
        world.step(DT);
        if world
            .events()
            .iter()
            .any(|e| matches!(e, Event::JointBroken { joint: j } if *j == joint))
        {
            broke_at = Some(step);
            break;
        }
    }
    assert!(broke_at.is_some(), "the rope should break");
    assert!(world.joint_state(joint).unwrap().broken);
    let y0 = world.body(weight).unwrap().position().y;
    for _ in 0..30 {
        world.step(DT);
    }
    let fall = y0 - world.body(weight).unwrap().position().y;
    assert!(
        fall > 0.5 * 9.81 * 0.25 * 0.9,
        "after breaking the weight falls freely, fell {fall} m in 0.5 s"
    );
}

/// A ball hanging at rest on a taut rope from the world origin: the soft joint is a spring of stiffness
/// `m·ω²` (the anchor is immovable, so the effective mass is the ball's), so it settles stretched by
/// `g/ω²`, where `ω = 2π·f` and `f` is `WorldSettings::joints.frequency_hz` (capped at a quarter of the
/// substep rate). Checks that the world hands its joint settings to the solver: 10 Hz stretches 36× more
/// than the default 60 Hz. The direct solve of chains is switched off (also a joint setting): its position
/// projection takes the soft stretch back at the end of every step.
#[test]
fn a_hanging_rope_stretches_by_g_over_omega_squared_at_the_configured_joint_frequency() {
    for hz in [10.0_f32, 60.0] {
        let mut settings = WorldSettings::default();
        settings.joints.frequency_hz = hz;
        settings.joints.direct_chains = false;
        let mut world = World::new(settings).unwrap();
        let ball_handle = world
            .insert_body(&ball().with_position(Vec3::new(0.0, -LENGTH, 0.0)))
            .unwrap();
        world.insert_world_joint(rope(), ball_handle).unwrap();
        for _ in 0..180 {
            world.step(DT);
        }
        let stretch = world.body(ball_handle).unwrap().position().length() - LENGTH;
        let omega = core::f32::consts::TAU * hz;
        let expected = settings.gravity.length() / (omega * omega);
        assert!(
            (stretch - expected).abs() < 0.02 * expected,
            "{hz} Hz: stretched {stretch} m, expected g/ω² = {expected} m"
        );
    }
}

/// Twenty 1 kg balls hanging on 0.25 m ropes from the world origin. Solved joint by joint, a soft link
/// stretches by the load it carries over its own stiffness, `k·m·g/(m_eff·ω²)` for the link `k` balls from
/// the end: the top link by 20·g/(m·ω²)·m ≈ 1.4 mm, 0.55 % (tethers off, so that the soft step alone is
/// measured). Solved as one path, the softness acts on the effective mass of the whole chain, and every link
/// stretches by no more than a single pendulum's `g/ω²` (0.07 mm at 60 Hz) whatever the load below it; that is
/// within the position projection's 0.1 mm tolerance, so the projection leaves it.
#[test]
fn a_hanging_rope_chain_solved_directly_stretches_each_link_by_at_most_g_over_omega_squared() {
    const LINKS: usize = 20;
    const LINK: f32 = 0.25;
    let run = |direct: bool| {
        let mut settings = WorldSettings::default();
        settings.joints.direct_chains = direct;
        settings.joints.tethers = false;
        let mut world = World::new(settings).unwrap();
        let mut previous = None;
        let mut balls = Vec::new();
        for i in 0..LINKS {
            let ball = world
                .insert_body(&ball().with_position(Vec3::new(0.0, -(i as f32 + 1.0) * LINK, 0.0)))
                .unwrap();
            let rope = Joint::new(Rope::new(LINK).unwrap());
            match previous {
                None => world.insert_world_joint(rope, ball).unwrap(),
                Some(p) => world.insert_joint(rope, p, ball).unwrap(),
            };
            previous = Some(ball);
            balls.push(ball);
        }
        let mut worst = 0.0f32;
        for _ in 0..120 {
            world.step(DT);
            let mut above = Vec3::ZERO;
            for &b in &balls {
                let p = world.body(b).unwrap().position();
                worst = worst.max(p.distance(above) / LINK - 1.0);
                above = p;
            }
        }
        worst
    };
    let (direct, joint_by_joint) = (run(true), run(false));
    let omega = core::f32::consts::TAU * WorldSettings::default().joints.frequency_hz;
    let single = 9.81 / (omega * omega) / LINK;
    assert!(
        direct <= 1.05 * single,
        "direct: worst link stretched {direct}, g/ω² is {single} of a link"
    );
    assert!(
        joint_by_joint > 3e-3,
        "joint by joint: worst link stretched only {joint_by_joint}"
    );
}
