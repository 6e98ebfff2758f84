//! Ropes (course item 4, docs/scenes.md "rope pendulum" and "rope slack"): a rope pendulum keeps its length within
//! 0.5 % and swings with the period 2π√(L/g); a slack rope leaves a falling body bit-identical to free fall;
//! a rope snapping taut jerks like a collision with the coefficient of restitution.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use core::f64::consts::TAU;
use rebound_constraints::{Joint, Rope};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::Vec3;
use support::Harness;

const DT: f32 = 1.0 / 60.0;

fn ball(mass: f32, position: Vec3, velocity: Vec3) -> BodyDesc {
    BodyDesc::dynamic()
        .with_mass_properties(
            MassProperties::new(mass, Vec3::ZERO, Vec3::splat(0.4 * mass * 0.01)).unwrap(),
        )
        .with_position(position)
        .with_linear_velocity(velocity)
}

/// Times of upward zero crossings of x(t), linearly interpolated.
fn upward_crossings(samples: &[(f64, f64)]) -> Vec<f64> {
    samples
        .windows(2)
        .filter(|w| w[0].1 < 0.0 && w[1].1 >= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (-w[0].1) / (w[1].1 - w[0].1))
        .collect()
}

#[test]
fn a_rope_pendulum_keeps_its_length_and_swings_with_period_two_pi_root_l_over_g() {
    // 1 kg on a 2 m rope to the world point (0, 3, 0), released from 10°.
    let (length, g) = (2.0f32, 9.81f32);
    let pivot = Vec3::new(0.0, 3.0, 0.0);
    let angle = 10f32.to_radians();
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let b = h.add(&ball(
        1.0,
        pivot + length * Vec3::new(angle.sin(), -angle.cos(), 0.0),
        Vec3::ZERO,
    ));
    h.join(
        Joint::new(Rope::new(length).unwrap())
            .with_local_anchors(pivot, Vec3::ZERO)
            .unwrap(),
        world,
        b,
    );
    let mut samples = Vec::new();
    let (mut longest, mut shortest) = (0.0f32, f32::MAX);
    for step in 1..=720 {
        h.step(DT);
        let p = h.bodies[b].position();
        let distance = (p - pivot).length();
        longest = longest.max(distance);
        shortest = shortest.min(distance);
        assert!(
            distance <= length * 1.005,
            "step {step}: rope stretched to {distance} m (max {length} m + 0.5 %)"
        );
        samples.push((f64::from(step) * f64::from(DT), f64::from(p.x)));
    }
    let crossings = upward_crossings(&samples);
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let expected = TAU * (f64::from(length) / f64::from(g)).sqrt();
    println!(
        "rope pendulum: period {period:.4} s vs 2π√(L/g) = {expected:.4} s; length in [{shortest:.5}, {longest:.5}] m"
    );
    assert!(
        (period - expected).abs() < 0.015 * expected,
        "period {period} s vs {expected} s (±1.5 %)"
    );
    // The rope stays taut all the way (tension > 0 at 10°): never more than 0.5 % slack either.
    assert!(
        shortest >= length * 0.995,
        "rope went slack to {shortest} m"
    );
}

#[test]
fn a_slack_rope_leaves_the_body_in_exact_free_fall() {
    // A 10 m rope from the origin; the ball starts 1.5 m away, spinning, and falls for 1 s (≈ 5 m).
    let desc = ball(1.0, Vec3::new(1.0, -1.0, 0.5), Vec3::new(0.3, 2.0, -0.1))
        .with_angular_velocity(Vec3::new(0.2, 1.0, -3.0));
    let mut roped = Harness::new(SolverSettings::default());
    let world = roped.world_anchor();
    let b = roped.add(&desc);
    roped.join(
        Joint::new(Rope::new(10.0).unwrap())
            .with_local_anchors(Vec3::ZERO, Vec3::new(0.1, 0.0, 0.0))
            .unwrap(),
        world,
        b,
    );
    let mut free = Harness::new(SolverSettings::default());
    free.world_anchor();
    let f = free.add(&desc);
    for step in 0..60 {
        roped.step(DT);
        free.step(DT);
        let (x, y) = (&roped.bodies[b], &free.bodies[f]);
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        assert_eq!(
            bits(x.position()),
            bits(y.position()),
            "position differs at step {step}"
        );
        assert_eq!(
            bits(x.linear_velocity()),
            bits(y.linear_velocity()),
            "velocity at step {step}"
        );
        assert_eq!(
            bits(x.angular_velocity()),
            bits(y.angular_velocity()),
            "spin at step {step}"
        );
        assert_eq!(
            x.rotation().to_array().map(f32::to_bits),
            y.rotation().to_array().map(f32::to_bits)
        );
    }
    assert!(
        roped.states[0].upper_impulse.abs() < f32::MIN_POSITIVE,
        "the slack rope carried an impulse"
    );
    assert!(
        (roped.bodies[b].position() - Vec3::ZERO).length() < 10.0,
        "the rope stayed slack"
    );
}

#[test]
fn a_rope_snapping_taut_jerks_like_a_collision() {
    // Zero gravity; a ball leaves the world anchor at 5 m/s on a 1 m rope. After the rope snaps taut the
    // radial velocity is −e·5 m/s (the course's collision, with the coefficient of restitution e).
    for e in [0.0f32, 0.5, 1.0] {
        let mut h = Harness::new(SolverSettings {
            gravity: Vec3::ZERO,
            ..SolverSettings::default()
        });
        let world = h.world_anchor();
        let b = h.add(&ball(
            1.0,
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(5.0, 0.0, 0.0),
        ));
        h.join(
            Joint::new(Rope::new(1.0).unwrap().with_restitution(e).unwrap()),
            world,
            b,
        );
        for _ in 0..12 {
            h.step(DT);
        }
        let v = h.bodies[b].linear_velocity().x;
        println!("restitution {e}: radial velocity after the jerk {v:.4} m/s");
        assert!(
            (v + e * 5.0).abs() < 0.01 * 5.0,
            "e = {e}: radial velocity {v} m/s, expected {} m/s",
            -e * 5.0
        );
        let distance = h.bodies[b].position().length();
        assert!(distance <= 1.0 + 1e-3, "rope stretched to {distance} m");
    }
}

#[test]
fn an_elastic_rope_between_free_bodies_conserves_momentum_and_energy() {
    // m₁ = 1 kg and m₂ = 3 kg fly apart at 4 and 1 m/s on a 1 m rope with e = 1: like the head-on elastic
    // collision (docs/scenes.md), the relative velocity reverses: v₁' = 2.5·… computed from the two conservation
    // laws: v₁' = v₁ − (1 + e)·m₂/(m₁ + m₂)·(v₁ − v₂), v₂' = v₂ + (1 + e)·m₁/(m₁ + m₂)·(v₁ − v₂).
    let (m1, m2, v1, v2) = (1.0f32, 3.0f32, -4.0f32, 1.0f32);
    let mut h = Harness::new(SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    });
    let a = h.add(&ball(
        m1,
        Vec3::new(-0.2, 0.0, 0.0),
        Vec3::new(v1, 0.0, 0.0),
    ));
    let b = h.add(&ball(m2, Vec3::new(0.2, 0.0, 0.0), Vec3::new(v2, 0.0, 0.0)));
    h.join(
        Joint::new(Rope::new(1.0).unwrap().with_restitution(1.0).unwrap()),
        a,
        b,
    );
    for _ in 0..20 {
        h.step(DT);
    }
    let closing = v1 - v2;
    let expected1 = v1 - 2.0 * m2 / (m1 + m2) * closing;
    let expected2 = v2 + 2.0 * m1 / (m1 + m2) * closing;
    let (w1, w2) = (
        h.bodies[a].linear_velocity().x,
        h.bodies[b].linear_velocity().x,
    );
    println!(
        "elastic rope: v₁' = {w1:.4} (expected {expected1}), v₂' = {w2:.4} (expected {expected2})"
    );
    assert!(
        (w1 - expected1).abs() < 0.01 * expected1.abs()
            && (w2 - expected2).abs() < 0.01 * expected2.abs()
    );
    let momentum = m1 * w1 + m2 * w2;
    assert!(
        (momentum - (m1 * v1 + m2 * v2)).abs() < 1e-4,
        "momentum {momentum}"
    );
    let energy = 0.5 * (m1 * w1 * w1 + m2 * w2 * w2);
    let energy0 = 0.5 * (m1 * v1 * v1 + m2 * v2 * v2);
    assert!(
        (energy - energy0).abs() < 0.01 * energy0,
        "kinetic energy {energy} vs {energy0}"
    );
}
