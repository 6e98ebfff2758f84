//! The default (soft) spring against the damped oscillator's conservation and decay laws (issue 28): an
//! undamped spring at h·ω = 0.5 per substep keeps its mean energy per period, a damped one loses it as
//! `exp(−2ζωt)`, and a spring of any stiffness stays bounded (`docs/physics.md`, "Springs without numerical
//! damping").

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use core::f64::consts::TAU;
use rebound_constraints::{Joint, SoftSpring, Spring, SpringModel};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::Vec3;
use support::Harness;

const REST: f32 = 1.0;
/// The substep (s): one substep per step, so that every substep is sampled.
const H: f32 = 1.0 / 240.0;

/// A 1 kg body on `spring` to the world origin, stretched by `x0` along x, stepped one substep at a time for
/// `duration` seconds; returns `(t, E)` after every substep with `E = ½·k·x² + ½·m·v²` (J).
fn energy_samples(spring: SoftSpring, k: f64, x0: f32, duration: f64) -> Vec<(f64, f64)> {
    let mut h = Harness::new(SolverSettings {
        gravity: Vec3::ZERO,
        substep_count: 1,
        ..SolverSettings::default()
    });
    let world = h.world_anchor();
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.1)).unwrap())
            .with_position(Vec3::new(REST + x0, 0.0, 0.0)),
    );
    h.join(
        Joint::new(Spring::new(REST, SpringModel::Soft(spring)).unwrap()),
        world,
        b,
    );
    let steps = (duration / f64::from(H)).ceil() as usize;
    (1..=steps)
        .map(|n| {
            h.step(H);
            let body = &h.bodies[b];
            let x = f64::from(body.position().x - REST);
            let v = f64::from(body.linear_velocity().x);
            (n as f64 * f64::from(H), 0.5 * k * x * x + 0.5 * v * v)
        })
        .collect()
}

/// The mean of `E` over each whole period `period` (s) of the samples.
fn mean_per_period(samples: &[(f64, f64)], period: f64) -> Vec<(f64, f64)> {
    let periods = (samples.last().map_or(0.0, |s| s.0) / period).floor() as usize;
    (0..periods)
        .map(|p| {
            let (start, end) = (p as f64 * period, (p + 1) as f64 * period);
            let window: Vec<f64> = samples
                .iter()
                .filter(|s| s.0 > start && s.0 <= end)
                .map(|s| s.1)
                .collect();
            (
                0.5 * (start + end),
                window.iter().sum::<f64>() / window.len() as f64,
            )
        })
        .collect()
}

#[test]
fn an_undamped_spring_at_h_omega_one_half_keeps_its_energy_for_50_periods() {
    // ω = 0.5/h = 120 rad/s on 1 kg: k = 14,400 N/m, period 52 ms.
    let omega = 0.5 / f64::from(H);
    let k = omega * omega;
    let period = TAU / omega;
    for spring in [
        SoftSpring::stiffness(k as f32, 0.0).unwrap(),
        SoftSpring::frequency((omega / TAU) as f32, 0.0).unwrap(),
    ] {
        let samples = energy_samples(spring, k, 0.1, 51.0 * period);
        let means = mean_per_period(&samples, period);
        assert!(means.len() >= 50);
        // The first period's mean: the orbit's mean energy sits 1/(1 − (h·ω/2)²) = 1.067 above the start's
        // `½·k·x0²` (the state at a substep's end is on an ellipse of the step's invariant, not of `E`),
        // and must stay there.
        let e0 = means[0].1;
        let start = 0.5 * k * 0.01;
        assert!(
            (e0 / start - 1.0 / (1.0 - 0.0625)).abs() < 0.01,
            "first period {e0} J vs {start} J"
        );
        for (n, (t, e)) in means.iter().enumerate() {
            assert!(
                (e / e0 - 1.0).abs() < 0.02,
                "{spring:?}: period {n} (t = {t:.3} s): mean energy {e:.4} J vs {e0:.4} J"
            );
        }
        let last = means.last().map_or(0.0, |m| m.1);
        println!(
            "{spring:?}: mean energy of period 50 / period 1 = {:.5}",
            last / e0
        );
    }
}

#[test]
fn a_damped_spring_loses_energy_as_exp_minus_two_zeta_omega_t() {
    // The same 120 rad/s spring with ζ = 0.05: five time constants (1/(ζω) each, of the amplitude) are
    // 0.83 s, sixteen periods.
    let omega = 0.5 / f64::from(H);
    let zeta = 0.05;
    let k = omega * omega;
    let period = TAU / omega;
    for spring in [
        SoftSpring::stiffness(k as f32, (2.0 * zeta * omega) as f32).unwrap(),
        SoftSpring::frequency((omega / TAU) as f32, zeta as f32).unwrap(),
    ] {
        let samples = energy_samples(spring, k, 0.1, 5.0 / (zeta * omega) + period);
        let means = mean_per_period(&samples, period);
        // Mean energy over a period of the decaying oscillation, against the first period's: the law fixes
        // the ratio `exp(−2ζω·Δt)` whatever the windowing does to the absolute value.
        let (t0, e0) = means[0];
        for &(t, e) in &means[1..] {
            let law = (-2.0 * zeta * omega * (t - t0)).exp();
            assert!(
                (e / e0 / law - 1.0).abs() < 0.05,
                "{spring:?}, t = {t:.3} s: E/E(t0) = {:.4e}, exp(−2ζωΔt) = {law:.4e}",
                e / e0
            );
        }
        assert!(means.last().map_or(0.0, |m| m.0) - t0 >= 4.5 / (zeta * omega));
    }
}

#[test]
fn a_spring_of_1e9_newtons_per_metre_at_30_hz_never_diverges() {
    // k = 1e9 N/m on 1 kg at dt = 1/30 s (four substeps: h·ω = 264): the step keeps `√α = 1/(h·ω)` of the
    // stretch per substep at most, and under gravity the static stretch is m·g/k (below one f32 ulp at 1 m).
    let k = 1.0e9f32;
    let dt = 1.0 / 30.0;
    let x0 = 0.1f32;
    let mut h = Harness::zero_gravity();
    let world = h.world_anchor();
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.1)).unwrap())
            .with_position(Vec3::new(REST + x0, 0.0, 0.0)),
    );
    let spring = Spring::new(REST, SpringModel::soft_stiffness(k, 0.0).unwrap()).unwrap();
    h.join(Joint::new(spring), world, b);
    let sub_h = f64::from(dt) / 4.0;
    let per_substep = 1.0 / (sub_h * f64::from(k).sqrt());
    let mut bound = f64::from(x0);
    for step in 1..=600 {
        h.step(dt);
        let error = f64::from(h.bodies[b].position().x - REST).abs();
        bound *= per_substep.powi(4);
        assert!(
            error <= bound.max(0.0) + 2e-7,
            "step {step}: stretch {error} m above the bound {bound} m"
        );
        assert!(h.bodies[b].linear_velocity().length() < 10.0);
    }
    let mut h = Harness::new(SolverSettings::default());
    let world = h.world_anchor();
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.1)).unwrap())
            .with_position(Vec3::new(0.0, -REST - x0, 0.0)),
    );
    h.join(Joint::new(spring), world, b);
    for _ in 0..600 {
        h.step(dt);
        assert!(h.bodies[b].position().is_finite());
    }
    let stretch = -h.bodies[b].position().y - REST;
    assert!(
        stretch.abs() < 2e-7,
        "static stretch {stretch} m vs m·g/k = 9.8e-9 m"
    );
}
