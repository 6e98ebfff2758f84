//! The soft spring against the closed form of its integrator (Jolt's `TestDistanceSpring`): a 1-DOF
//! implicit-Euler spring-damper recurrence stepped in f64 next to the engine, in both parameterisations, from a
//! world anchor and between two free bodies; and the period of an undamped spring (docs/scenes.md "spring
//! oscillator").

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use core::f64::consts::TAU;
use rebound_constraints::{Joint, SoftSpring, Spring, SpringModel};
use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::Vec3;
use support::Harness;

const DT: f32 = 1.0 / 60.0;
const SUBSTEPS: u32 = 4;
const REST: f32 = 1.5;

/// One substep of the spring's closed-form map for `m·ẍ = −k·x − c·ẋ` (`docs/physics.md`, "Springs without
/// numerical damping"): `v' = α·v − α·h·(k/m)·x`, `x' = x + h·v'`, `α = min(e^{−h·c/m}, 1/(h²·k/m))` (the
/// cap only where `h²·k/m > 1`).
fn exact_oscillator(x: &mut f64, v: &mut f64, k: f64, c: f64, m: f64, h: f64) {
    let resolution = h * h * k / m;
    let physical = (-h * c / m).exp();
    let alpha = if resolution > 1.0 {
        physical.min(1.0 / resolution)
    } else {
        physical
    };
    *v = alpha * (*v - h * k / m * *x);
    *x += h * *v;
}

/// `(k, c)` of `spring` on an effective mass `m`.
fn stiffness_of(spring: SoftSpring, m: f64) -> (f64, f64) {
    match spring {
        SoftSpring::Frequency {
            frequency_hz,
            damping_ratio,
        } => {
            let omega = TAU * f64::from(frequency_hz);
            (
                m * omega * omega,
                2.0 * m * f64::from(damping_ratio) * omega,
            )
        }
        SoftSpring::Stiffness { stiffness, damping } => (f64::from(stiffness), f64::from(damping)),
    }
}

fn body(mass: f32, position: Vec3, velocity: Vec3) -> BodyDesc {
    BodyDesc::dynamic()
        .with_mass_properties(MassProperties::new(mass, Vec3::ZERO, Vec3::splat(0.2)).unwrap())
        .with_position(position)
        .with_linear_velocity(velocity)
}

/// A body of 2 kg on a spring to the world point `anchor`, stretched by 0.3 m and moving at −0.4 m/s along x.
fn world_spring_matches_the_recurrence(spring: SoftSpring) -> f64 {
    let (m, x0, v0) = (2.0f32, 0.3f32, -0.4f32);
    let anchor = Vec3::new(1.0, 2.0, 3.0);
    let mut h = Harness::zero_gravity();
    let world = h.world_anchor();
    let b = h.add(&body(m, anchor + Vec3::X * (REST + x0), Vec3::X * v0));
    let joint = Joint::new(Spring::new(REST, SpringModel::Soft(spring)).unwrap())
        .with_local_anchors(anchor, Vec3::ZERO)
        .unwrap();
    h.join(joint, world, b);

    let (k, c) = stiffness_of(spring, f64::from(m));
    let sub_h = f64::from(DT) / f64::from(SUBSTEPS);
    let (mut x, mut v) = (f64::from(x0), f64::from(v0));
    let mut worst = 0.0f64;
    for step in 0..600 {
        h.step(DT);
        for _ in 0..SUBSTEPS {
            exact_oscillator(&mut x, &mut v, k, c, f64::from(m), sub_h);
        }
        let p = h.bodies[b].position();
        let engine = f64::from(p.x - anchor.x - REST);
        let error = (engine - x).abs();
        worst = worst.max(error);
        assert!(
            error < 1e-5,
            "{spring:?}, step {step}: spring extension {engine} m, implicit Euler predicts {x} m"
        );
        assert!((p.y - anchor.y).abs() < 1e-6 && (p.z - anchor.z).abs() < 1e-6);
    }
    worst
}

#[test]
fn soft_spring_follows_exact_oscillator_in_frequency_form() {
    for (hz, zeta) in [(2.0, 0.3), (0.5, 0.0), (8.0, 1.0)] {
        let worst = world_spring_matches_the_recurrence(SoftSpring::frequency(hz, zeta).unwrap());
        println!("f = {hz} Hz, zeta = {zeta}: worst deviation {worst:.2e} m");
    }
}

#[test]
fn soft_spring_follows_exact_oscillator_in_stiffness_form() {
    for (k, c) in [(50.0, 3.0), (200.0, 0.0), (5000.0, 20.0)] {
        let worst = world_spring_matches_the_recurrence(SoftSpring::stiffness(k, c).unwrap());
        println!("k = {k} N/m, c = {c} N s/m: worst deviation {worst:.2e} m");
    }
}

#[test]
fn a_spring_between_two_free_bodies_acts_on_both_through_the_reduced_mass() {
    // m₁ = 1 kg, m₂ = 3 kg: the separation obeys the recurrence with μ = m₁m₂/(m₁ + m₂) = 0.75 kg, and the
    // centre of mass does not accelerate (course item 1: the force acts on both bodies).
    let (m1, m2) = (1.0f32, 3.0f32);
    let mu = f64::from(m1 * m2 / (m1 + m2));
    let (k, c) = (120.0f32, 1.5f32);
    let mut h = Harness::zero_gravity();
    let a = h.add(&body(
        m1,
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(-0.3, 0.0, 0.0),
    ));
    let b = h.add(&body(
        m2,
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.2, 0.0, 0.0),
    ));
    h.join(
        Joint::new(Spring::new(REST, SpringModel::soft_stiffness(k, c).unwrap()).unwrap()),
        a,
        b,
    );
    let com = |h: &Harness| (h.bodies[a].position() * m1 + h.bodies[b].position() * m2) / (m1 + m2);
    let com_velocity = Vec3::new((-0.3 * m1 + 0.2 * m2) / (m1 + m2), 0.0, 0.0);
    let com0 = com(&h);
    let (mut x, mut v) = (2.0 - f64::from(REST), 0.5f64);
    let sub_h = f64::from(DT) / f64::from(SUBSTEPS);
    for step in 1..=600 {
        h.step(DT);
        for _ in 0..SUBSTEPS {
            exact_oscillator(&mut x, &mut v, f64::from(k), f64::from(c), mu, sub_h);
        }
        let length = f64::from(h.bodies[b].position().x - h.bodies[a].position().x);
        assert!(
            (length - f64::from(REST) - x).abs() < 1e-5,
            "step {step}: extension {} vs {x}",
            length - f64::from(REST)
        );
        let expected_com = com0 + com_velocity * (step as f32 * DT);
        assert!(
            (com(&h) - expected_com).length() < 1e-5,
            "centre of mass drifted: {} vs {expected_com}",
            com(&h)
        );
    }
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
fn an_undamped_spring_oscillates_with_period_two_pi_root_m_over_k() {
    // docs/scenes.md "spring oscillator": 1 kg, k = 100 N/m, ζ = 0, world anchor. Period 2π√(m/k) = 0.6283 s.
    let (m, k) = (1.0f32, 100.0f32);
    let expected = TAU * (f64::from(m) / f64::from(k)).sqrt();
    let omega = (k / m).sqrt();
    for spring in [
        SoftSpring::stiffness(k, 0.0).unwrap(),
        SoftSpring::frequency(omega / core::f32::consts::TAU, 0.0).unwrap(),
    ] {
        let mut h = Harness::zero_gravity();
        let world = h.world_anchor();
        let b = h.add(&body(m, Vec3::new(REST + 0.2, 0.0, 0.0), Vec3::ZERO));
        h.join(
            Joint::new(Spring::new(REST, SpringModel::Soft(spring)).unwrap()),
            world,
            b,
        );
        let mut samples = Vec::new();
        for step in 1..=240 {
            h.step(DT);
            samples.push((
                f64::from(step) * f64::from(DT),
                f64::from(h.bodies[b].position().x - REST),
            ));
        }
        let crossings = upward_crossings(&samples);
        assert!(crossings.len() >= 5, "{} crossings in 4 s", crossings.len());
        let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
        println!("{spring:?}: period {period:.5} s, 2π√(m/k) = {expected:.5} s");
        assert!(
            (period - expected).abs() < 0.01 * expected,
            "period {period} s vs 2π√(m/k) = {expected} s (±1 %)"
        );
    }
}
