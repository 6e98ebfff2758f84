//! Free fall against the closed form of the integrator (docs/scenes.md "free fall"): semi-implicit Euler at 1, 2 and
//! 4 substeps, and the course's explicit Euler, each to 1e-5 m relative.

mod support;

use rebound_dynamics::{BodyDesc, Integrator, SolverSettings};
use rebound_math::Vec3;
use support::Harness;

const DT: f64 = 1.0 / 60.0;
const G: f64 = -9.81;

/// Position after `n` substeps of length h from (x₀, v₀): semi-implicit adds a·h²·n(n+1)/2, explicit
/// a·h²·n(n−1)/2.
fn predicted(x0: f64, v0: f64, h: f64, n: f64, explicit: bool) -> f64 {
    let k = if explicit {
        n * (n - 1.0)
    } else {
        n * (n + 1.0)
    };
    x0 + v0 * n * h + G * h * h * k / 2.0
}

fn fall(substeps: u32, integrator: Integrator) {
    let settings = SolverSettings {
        substep_count: substeps,
        ..SolverSettings::default()
    };
    let mut h = Harness::new(settings);
    let body = h.add(
        &BodyDesc::dynamic()
            .with_position(Vec3::new(0.0, 100.0, 0.0))
            .with_linear_velocity(Vec3::new(1.0, 2.0, 0.0))
            .with_integrator(integrator),
    );
    let sub_h = DT / f64::from(substeps);
    for step in 1..=120u32 {
        h.step_free(DT as f32);
        let n = f64::from(step * substeps);
        let explicit = integrator == Integrator::ExplicitEuler;
        let y = predicted(100.0, 2.0, sub_h, n, explicit);
        let p = h.bodies[body].position();
        assert!(
            (f64::from(p.y) - y).abs() < 1e-5 * y.abs().max(1.0),
            "{integrator:?} at {substeps} substeps, step {step}: y = {} predicted {y}",
            p.y
        );
        let x = 1.0 * n * sub_h;
        assert!(
            (f64::from(p.x) - x).abs() < 1e-5 * x.max(1.0),
            "x = {} predicted {x}",
            p.x
        );
        let v = 2.0 + G * n * sub_h;
        assert!((f64::from(h.bodies[body].linear_velocity().y) - v).abs() < 1e-4);
    }
}

#[test]
fn semi_implicit_free_fall_matches_its_closed_form_at_1_2_and_4_substeps() {
    for substeps in [1, 2, 4] {
        fall(substeps, Integrator::SemiImplicitEuler);
    }
}

#[test]
fn explicit_euler_free_fall_matches_its_closed_form() {
    fall(4, Integrator::ExplicitEuler);
}

#[test]
fn gravity_scale_and_damping_follow_their_formulas() {
    let settings = SolverSettings {
        substep_count: 1,
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    };
    let mut h = Harness::new(settings);
    let damped = h.add(
        &BodyDesc::dynamic()
            .with_linear_velocity(Vec3::X * 10.0)
            .with_linear_damping(0.5),
    );
    for _ in 0..60 {
        h.step_free(1.0 / 60.0);
    }
    // v_n = v₀ / (1 + c·h)ⁿ.
    let expected = 10.0 / (1.0f32 + 0.5 / 60.0).powi(60);
    let v = h.bodies[damped].linear_velocity().x;
    assert!(
        (v - expected).abs() < 1e-4 * expected,
        "damped {v} vs {expected}"
    );

    let mut h = Harness::new(SolverSettings::default());
    let floating = h.add(&BodyDesc::dynamic().with_gravity_scale(0.0));
    let fixed = h.add(&BodyDesc::fixed().with_position(Vec3::ONE));
    for _ in 0..30 {
        h.step_free(1.0 / 60.0);
    }
    assert_eq!(
        h.bodies[floating].position(),
        Vec3::ZERO,
        "gravity scale 0 floats"
    );
    assert_eq!(
        h.bodies[fixed].position(),
        Vec3::ONE,
        "a fixed body never moves"
    );
}
