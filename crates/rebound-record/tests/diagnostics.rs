//! A frame's energy, momentum, joint error and penetration against closed forms: free fall under
//! semi-implicit Euler (which loses exactly ½·m·g²·h² of energy per substep), a stretched spring, joints
//! placed with a known error, a ball pushed into the ground.

mod support;

use rebound::prelude::*;
use rebound_record::Frame;
use support::{DT, record};

/// The frames of `steps` steps of `world` after its initial state.
fn frames(world: &mut PhysicsWorld, steps: usize) -> Vec<Frame> {
    record(world, steps).1
}

#[test]
fn free_fall_energy_and_momentum_follow_the_integrators_closed_form() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let g = 9.81f64;
    let (v0, omega) = (Vec3::new(1.0, 4.0, -2.0), Vec3::new(0.0, 3.0, 0.0));
    let ball = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(0.0, 50.0, 0.0))
                .with_linear_velocity(v0)
                .with_angular_velocity(omega),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.5), ball)
        .unwrap();
    let mass = f64::from(world.body(ball).unwrap().mass_properties().mass());
    let inertia = 0.4 * mass * 0.25;
    let substeps = f64::from(world.settings().substep_count);
    let h = f64::from(DT) / substeps;
    let frames = frames(&mut world, 120);
    let d0 = frames[0].diagnostics;
    // Frame 0: K = ½m|v|² + ½Iω², U = m·g·y, p = m·v, L = r × m·v + I·ω.
    let k0 = 0.5 * mass * f64::from(v0.length_squared()) + 0.5 * inertia * 9.0;
    assert!((f64::from(d0.kinetic_energy) - k0).abs() < 1e-5 * k0);
    assert!((f64::from(d0.potential_energy) - mass * g * 50.0).abs() < 1e-5 * mass * g * 50.0);
    let p0 = v0.as_dvec3() * mass;
    assert!((d0.linear_momentum.as_dvec3() - p0).length() < 1e-5 * p0.length());
    let l0 = Vec3::new(0.0, 50.0, 0.0).as_dvec3().cross(p0) + omega.as_dvec3() * inertia;
    assert!((d0.angular_momentum.as_dvec3() - l0).length() < 1e-5 * l0.length());
    let e0 = f64::from(d0.total_energy());
    for (n, frame) in frames.iter().enumerate() {
        let d = frame.diagnostics;
        // Each substep: ΔE = ½·m·(v₊ − v)(v₊ + v) + m·g·v₊·h = −½·m·g²·h².
        let lost = n as f64 * substeps * 0.5 * mass * g * g * h * h;
        let e = f64::from(d.total_energy());
        assert!(
            (e - (e0 - lost)).abs() < 2e-6 * e0,
            "step {n}: {e} vs {}",
            e0 - lost
        );
        // p_y falls by m·g per second.
        let py = p0.y - mass * g * n as f64 * f64::from(DT);
        assert!(
            (f64::from(d.linear_momentum.y) - py).abs() < 1e-4 * p0.length(),
            "step {n}"
        );
        assert!(
            d.worst_joint_error.abs() < f32::MIN_POSITIVE
                && d.deepest_penetration.abs() < f32::MIN_POSITIVE
        );
    }
}

#[test]
fn a_stretched_spring_stores_half_k_x_squared() {
    let mut world = PhysicsWorld::new(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    })
    .unwrap();
    let a = world.insert_body(BodyDesc::dynamic()).unwrap();
    let b = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(1.5, 0.0, 0.0)))
        .unwrap();
    let (k, rest) = (200.0f32, 1.0f32);
    world
        .insert_joint(
            Spring::new(rest, SpringModel::force(k, 0.0).unwrap()).unwrap(),
            a,
            b,
        )
        .unwrap();
    // A frequency-form spring: k = μ·(2π·f)², μ = 1/(1/m_a + 1/m_b) = 0.5 kg for two 1 kg bodies.
    let c = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 5.0, 0.0)))
        .unwrap();
    let d = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 5.0, 2.0)))
        .unwrap();
    world
        .insert_joint(
            Spring::new(rest, SpringModel::soft_frequency(2.0, 0.0).unwrap()).unwrap(),
            c,
            d,
        )
        .unwrap();
    let frames = frames(&mut world, 1);
    let omega = std::f32::consts::TAU * 2.0;
    let expected = 0.5 * k * 0.5 * 0.5 + 0.5 * (0.5 * omega * omega) * 1.0;
    let stored = frames[0].diagnostics.spring_energy;
    assert!(
        (stored - expected).abs() < 1e-5 * expected,
        "{stored} vs {expected}"
    );
    assert!(
        frames[0]
            .joints
            .iter()
            .all(|j| j.error.abs() < f32::MIN_POSITIVE),
        "a spring has no error"
    );
}

#[test]
fn joint_errors_are_the_placement_errors_of_each_kind() {
    let mut world = PhysicsWorld::new(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    })
    .unwrap();
    let mut pair = |x: f32, joint: Joint, offset: Vec3| {
        let a = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(x, 0.0, 0.0)))
            .unwrap();
        let b = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(x, 0.0, 0.0) + offset))
            .unwrap();
        world.insert_joint(joint, a, b).unwrap();
    };
    let d = Vec3::new(0.3, 0.4, 1.2); // |d| = 1.3
    pair(0.0, Joint::new(Rope::new(1.0).unwrap()), d);
    pair(10.0, Joint::new(Rope::new(2.0).unwrap()), d);
    pair(20.0, Joint::new(Rod::new(1.5).unwrap()), d);
    pair(30.0, Joint::new(BallJoint::new()), d);
    // A slider along x: only the part of d across x is error.
    pair(40.0, Joint::new(PrismaticJoint::new()), d);
    // A wheel: the suspension is A's y; the part across y is error.
    pair(
        50.0,
        Joint::new(WheelJoint::new(SoftSpring::frequency(4.0, 0.7).unwrap()).unwrap()),
        d,
    );
    let frames = frames(&mut world, 0);
    let errors: Vec<f32> = frames[0].joints.iter().map(|j| j.error).collect();
    let expected = [
        0.3,
        0.0,
        0.2,
        1.3,
        Vec3::new(0.0, 0.4, 1.2).length(),
        Vec3::new(0.3, 0.0, 1.2).length(),
    ];
    for (i, (e, x)) in errors.iter().zip(expected).enumerate() {
        assert!((e - x).abs() < 1e-6, "joint {i}: {e} vs {x}");
    }
    assert!((frames[0].diagnostics.worst_joint_error - 1.3).abs() < 1e-6);
    // The anchors are the body origins.
    let j = frames[0].joints[3];
    assert!((j.anchor_a - Vec3::new(30.0, 0.0, 0.0)).length() < 1e-6);
    assert!((j.anchor_b - (Vec3::new(30.0, 0.0, 0.0) + d)).length() < 1e-6);
}

#[test]
fn the_deepest_penetration_is_the_overlap_the_step_measured() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world.insert_body(BodyDesc::fixed()).unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(5.0, 0.5, 5.0)).with_position(Vec3::new(0.0, -0.5, 0.0)),
            ground,
        )
        .unwrap();
    // A ball of radius 0.5 with its centre 0.4 m up: 0.1 m into the ground.
    let ball = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.4, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.5), ball)
        .unwrap();
    let frames = frames(&mut world, 1);
    assert!(frames[0].contacts.is_empty(), "no step yet, no contacts");
    let deepest = frames[1].diagnostics.deepest_penetration;
    assert!((deepest - 0.1).abs() < 1e-4, "{deepest}");
    let contact = frames[1].contacts[0];
    assert!((contact.separation + 0.1).abs() < 1e-4);
    assert!((contact.normal.y.abs() - 1.0).abs() < 1e-6);
}
