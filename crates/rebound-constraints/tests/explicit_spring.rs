//! The course's explicit spring (`SpringModel::Force`, course items 1–3) against the closed form of its
//! integrator, and the course's question answered with numbers (docs/scenes.md "explicit spring limit", "stiff
//! spring"): the explicit force is bounded at h·ω = 1.9 — it conserves the discrete energy of symplectic
//! Euler exactly — and grows by the predicted factor every substep at h·ω = 2.1; the soft spring with
//! k = 1e7 N/m on 1 kg at dt = 1/30 s never diverges and its length error converges to 0.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use rebound_constraints::{Joint, Spring, SpringModel};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::Vec3;
use support::Harness;

const DT: f32 = 1.0 / 60.0;
const SUBSTEPS: u32 = 4;

/// A 1 kg body on a spring of rest length `rest` to the world origin, displaced by `x0` along x.
fn oscillator(
    model: SpringModel,
    rest: f32,
    x0: f32,
    settings: SolverSettings,
) -> (Harness, usize) {
    let mut h = Harness::new(settings);
    let world = h.world_anchor();
    let b = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.1)).unwrap())
            .with_position(Vec3::new(rest + x0, 0.0, 0.0)),
    );
    h.join(Joint::new(Spring::new(rest, model).unwrap()), world, b);
    (h, b)
}

fn zero_gravity() -> SolverSettings {
    SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    }
}

/// The stiffness (N/m) that gives `h·ω = h_omega` on 1 kg at the substep length of `DT`.
fn stiffness_for(h_omega: f64) -> f64 {
    let h = f64::from(DT) / f64::from(SUBSTEPS);
    (h_omega / h).powi(2)
}

#[test]
fn the_force_spring_is_symplectic_euler_of_hookes_law() {
    // Course items 1–2: the force is turned into a velocity change each substep, then the position moves with
    // the new velocity: v' = v + h·(−k·x − c·v)/m, x' = x + h·v'. Stepped in f64 next to the engine.
    let (k, c, rest, x0) = (stiffness_for(0.5), 2.0f64, 1.0f32, 0.25f32);
    let (mut h, b) = oscillator(
        SpringModel::force(k as f32, c as f32).unwrap(),
        rest,
        x0,
        zero_gravity(),
    );
    let sub_h = f64::from(DT) / f64::from(SUBSTEPS);
    let (mut x, mut v) = (f64::from(x0), 0.0f64);
    for step in 0..600 {
        h.step(DT);
        for _ in 0..SUBSTEPS {
            v += sub_h * (-k * x - c * v);
            x += sub_h * v;
        }
        let engine = f64::from(h.bodies[b].position().x - rest);
        assert!(
            (engine - x).abs() < 1e-5,
            "step {step}: extension {engine} m vs symplectic Euler {x} m"
        );
    }
}

/// The quantity symplectic Euler conserves for `ẍ = −ω²x` (after the position update):
/// `Q = ω²x² + v² − h·ω²·x·v`. Its minimum over v bounds the amplitude: `|x| ≤ √(Q / (ω²(1 − h²ω²/4)))`.
fn discrete_energy(x: f64, v: f64, omega: f64, h: f64) -> f64 {
    omega * omega * x * x + v * v - h * omega * omega * x * v
}

#[test]
fn the_force_spring_is_bounded_at_h_omega_1_9() {
    // Zero rest length makes f = −k·d linear for any d, so the 1-D analysis is exact.
    let h_omega = 1.9f64;
    let sub_h = f64::from(DT) / f64::from(SUBSTEPS);
    let omega = h_omega / sub_h;
    let x0 = 0.1f32;
    let (mut h, b) = oscillator(
        SpringModel::force(stiffness_for(h_omega) as f32, 0.0).unwrap(),
        0.0,
        x0,
        zero_gravity(),
    );
    let q0 = discrete_energy(f64::from(x0), 0.0, omega, sub_h);
    let bound = (q0 / (omega * omega * (1.0 - h_omega * h_omega / 4.0))).sqrt();
    let mut max_x = 0.0f64;
    let mut worst_q = 0.0f64;
    for step in 0..600 {
        h.step(DT);
        let body = &h.bodies[b];
        let (x, v) = (
            f64::from(body.position().x),
            f64::from(body.linear_velocity().x),
        );
        let q = discrete_energy(x, v, omega, sub_h);
        worst_q = worst_q.max((q / q0 - 1.0).abs());
        max_x = max_x.max(x.abs());
        assert!(
            (q / q0 - 1.0).abs() < 1e-3,
            "step {step}: discrete energy {q} drifted from {q0}"
        );
        assert!(
            x.abs() <= bound * 1.001,
            "step {step}: |x| = {x} beyond the bound {bound}"
        );
    }
    println!(
        "h·ω = 1.9: max |x| = {max_x:.4} m (bound {bound:.4} m = {:.2}·x₀), worst |Q/Q₀ − 1| = {worst_q:.1e}",
        bound / f64::from(x0)
    );
}

#[test]
fn the_force_spring_diverges_at_h_omega_2_1_by_the_predicted_factor() {
    let h_omega = 2.1f64;
    let s = h_omega * h_omega;
    // The dominant eigenvalue of the substep map: λ = (2 − s − √((2 − s)² − 4))/2 = −1.877.
    let lambda = ((2.0 - s) - ((2.0 - s) * (2.0 - s) - 4.0).sqrt()) / 2.0;
    let per_step = lambda.abs().powi(SUBSTEPS as i32);
    let x0 = 1e-3f32;
    let (mut h, b) = oscillator(
        SpringModel::force(stiffness_for(h_omega) as f32, 0.0).unwrap(),
        0.0,
        x0,
        zero_gravity(),
    );
    let mut previous = f64::from(x0);
    for step in 1..=6 {
        h.step(DT);
        let x = f64::from(h.bodies[b].position().x).abs();
        let growth = x / previous;
        println!(
            "h·ω = 2.1, step {step}: |x| = {x:.3e} m, growth ×{growth:.3} (predicted ×{per_step:.3})"
        );
        // After the first step the other eigenvalue (−0.533) has died out.
        if step >= 3 {
            assert!(
                (growth - per_step).abs() < 0.01 * per_step,
                "growth ×{growth} per step, |λ|⁴ = {per_step}"
            );
        }
        previous = x;
    }
    assert!(previous > 1e5 * f64::from(x0), "|x| = {previous} m");
}

#[test]
fn a_stiff_soft_spring_never_diverges_and_its_error_converges_to_zero() {
    // docs/scenes.md "stiff spring": k = 1e7 N/m on 1 kg at dt = 1/30 s (h·ω = 26 per substep).
    let k = 1.0e7f32;
    let dt = 1.0 / 30.0;
    let x0 = 0.1f32;
    let rest = 1.0f32;
    let sub_h = f64::from(dt) / f64::from(SUBSTEPS);
    // Beyond h·ω = 1 the soft step keeps at most α = 1/(h·ω)² of the energy, so the undamped error contracts
    // by 1/(h·ω) = 0.038 per substep at least.
    let contraction = 1.0 / (sub_h * f64::from(k).sqrt());
    let (mut h, b) = oscillator(
        SpringModel::soft_stiffness(k, 0.0).unwrap(),
        rest,
        x0,
        zero_gravity(),
    );
    let mut bound = f64::from(x0);
    for step in 1..=60 {
        h.step(dt);
        let error = f64::from(h.bodies[b].position().x - rest).abs();
        bound *= contraction.powi(SUBSTEPS as i32);
        // f32 resolution of the position (1 ulp at 1 m is 1.2e-7 m).
        assert!(
            error <= bound + 2e-7,
            "step {step}: length error {error} m above the bound {bound} m"
        );
        assert!(h.bodies[b].linear_velocity().length() < 10.0);
    }
    // With gravity it converges to the static stretch m·g/k = 0.98 µm (along y, hanging).
    let (mut h, b) = {
        let mut h = Harness::new(SolverSettings::default());
        let world = h.world_anchor();
        let b = h.add(
            &BodyDesc::dynamic()
                .with_mass_properties(
                    MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.1)).unwrap(),
                )
                .with_position(Vec3::new(0.0, -rest - x0, 0.0)),
        );
        h.join(
            Joint::new(Spring::new(rest, SpringModel::soft_stiffness(k, 0.0).unwrap()).unwrap()),
            world,
            b,
        );
        (h, b)
    };
    for _ in 0..30 {
        h.step(dt);
    }
    let stretch = -h.bodies[b].position().y - rest;
    let expected = 9.81 / k;
    assert!(
        (stretch - expected).abs() < 2e-7,
        "static stretch {stretch} m vs m·g/k = {expected} m"
    );
}

#[test]
fn the_force_spring_explodes_where_the_soft_spring_does_not() {
    // Same k = 1e7 N/m, 1 kg, dt = 1/30 s: h·ω = 26.4 ≫ 2. Two steps grow the 0.1 m error beyond 1e6 m.
    let (mut h, b) = oscillator(
        SpringModel::force(1.0e7, 0.0).unwrap(),
        1.0,
        0.1,
        zero_gravity(),
    );
    h.step(1.0 / 30.0);
    h.step(1.0 / 30.0);
    let error = (h.bodies[b].position().x - 1.0).abs();
    assert!(error > 1e6, "explicit spring error {error} m after 2 steps");
}
