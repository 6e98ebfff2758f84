//! Forces and impulses at points (course item 8 and beyond): a force at an offset point gives the linear
//! acceleration F/m and the angular acceleration I⁻¹(r × F); an impulse at a point changes v by J/m and ω by
//! I⁻¹(r × J); bad input is refused and changes nothing.

mod support;

use rebound_dynamics::{BodyDesc, MassProperties, RigidBody, SolverSettings};
use rebound_math::{Quat, Vec3};
use support::Harness;

fn box_body() -> BodyDesc {
    // 2 kg box, half-extents (0.5, 0.25, 1.0), rotated so the world inertia is not diagonal.
    let mass = MassProperties::cuboid(2.0 / 1.0, Vec3::new(0.5, 0.25, 1.0)).expect("valid");
    BodyDesc::dynamic()
        .with_mass_properties(mass)
        .with_rotation(Quat::from_rotation_y(0.3) * Quat::from_rotation_x(0.2))
        .with_position(Vec3::new(1.0, 2.0, 3.0))
}

#[test]
fn impulse_at_a_point_changes_velocity_by_j_over_m_and_spin_by_inverse_inertia_times_r_cross_j() {
    let mut body = RigidBody::new(&box_body()).unwrap();
    let point = body.center_of_mass() + Vec3::new(0.3, 0.1, -0.4);
    let impulse = Vec3::new(0.0, 5.0, 1.0);
    let inv_inertia = body.inv_inertia_world();
    let mass = body.mass_properties().mass();
    body.apply_impulse_at_point(impulse, point).unwrap();
    assert!(body.linear_velocity().abs_diff_eq(impulse / mass, 1e-6));
    let expected_omega = inv_inertia * (point - body.center_of_mass()).cross(impulse);
    assert!(body.angular_velocity().abs_diff_eq(expected_omega, 1e-5));
    // Angular momentum about the application point's line is exactly r × J (spin) + 0 (orbit about c).
    let spin = body.inertia_world() * body.angular_velocity();
    assert!(spin.abs_diff_eq((point - body.center_of_mass()).cross(impulse), 1e-4));
}

#[test]
fn force_at_an_offset_point_gives_the_expected_accelerations() {
    let settings = SolverSettings {
        gravity: Vec3::ZERO,
        substep_count: 1,
        ..SolverSettings::default()
    };
    let mut h = Harness::new(settings);
    let body = h.add(&box_body().with_gyroscopic(false));
    let force = Vec3::new(3.0, 0.0, 0.0);
    let offset = Vec3::new(0.0, 0.25, 0.0);
    let point = h.bodies[body].center_of_mass() + offset;
    let inv_inertia = h.bodies[body].inv_inertia_world();
    let mass = h.bodies[body].mass_properties().mass();
    h.bodies[body].apply_force_at_point(force, point).unwrap();
    let dt = 1.0 / 60.0;
    h.step_free(dt);
    let b = &h.bodies[body];
    assert!(
        b.linear_velocity().abs_diff_eq(force / mass * dt, 1e-6),
        "Δv = F/m·dt"
    );
    let expected = inv_inertia * offset.cross(force) * dt;
    assert!(
        b.angular_velocity().abs_diff_eq(expected, 1e-5),
        "Δω = I⁻¹(r × F)·dt: {} vs {expected}",
        b.angular_velocity()
    );
    // The accumulators are cleared after the step.
    assert_eq!(b.force(), Vec3::ZERO);
    assert_eq!(b.torque(), Vec3::ZERO);
}

#[test]
fn fixed_and_kinematic_bodies_ignore_impulses_and_forces() {
    let mut fixed = RigidBody::new(&BodyDesc::fixed()).unwrap();
    fixed.apply_impulse(Vec3::X * 100.0).unwrap();
    fixed
        .apply_impulse_at_point(Vec3::X * 100.0, Vec3::Y)
        .unwrap();
    assert_eq!(fixed.linear_velocity(), Vec3::ZERO);
    assert_eq!(fixed.angular_velocity(), Vec3::ZERO);
    assert!(
        fixed.inv_mass().abs() < f32::EPSILON,
        "infinite mass is inverse mass 0, never a huge number"
    );

    let mut h = Harness::new(SolverSettings::default());
    let kinematic = h.add(&BodyDesc::kinematic().with_linear_velocity(Vec3::X));
    h.bodies[kinematic].apply_force(Vec3::Y * 1000.0).unwrap();
    for _ in 0..60 {
        h.step_free(1.0 / 60.0);
    }
    let p = h.bodies[kinematic].position();
    assert!(
        (p - Vec3::X).length() < 1e-5,
        "kinematic moves by its velocity only, got {p}"
    );
}

#[test]
fn bad_input_is_refused_and_changes_nothing() {
    let mut body = RigidBody::new(&box_body()).unwrap();
    let before = body.clone();
    assert!(body.apply_impulse(Vec3::new(f32::NAN, 0.0, 0.0)).is_err());
    assert!(
        body.apply_impulse_at_point(Vec3::X, Vec3::splat(f32::INFINITY))
            .is_err()
    );
    assert!(body.apply_force(Vec3::splat(f32::NEG_INFINITY)).is_err());
    assert!(body.apply_torque(Vec3::new(0.0, f32::NAN, 0.0)).is_err());
    assert!(body.set_linear_velocity(Vec3::splat(f32::NAN)).is_err());
    assert!(
        body.set_rotation(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0))
            .is_err()
    );
    assert!(body.set_linear_damping(-1.0).is_err());
    assert!(body.set_gravity_scale(f32::NAN).is_err());
    assert_eq!(body, before);
    let err = RigidBody::new(&BodyDesc::dynamic().with_linear_damping(-0.5)).unwrap_err();
    assert!(
        err.to_string().contains("`linear_damping`") && err.to_string().contains("-0.5"),
        "{err}"
    );
    assert!(RigidBody::new(&BodyDesc::dynamic().with_position(Vec3::splat(f32::NAN))).is_err());
}

#[test]
fn an_impulse_that_would_overflow_the_velocity_is_refused_and_changes_nothing() {
    // A finite impulse on a tiny mass (1e-20 kg): J/m = 1e30 / 1e-20 overflows f32. Found by the facade's
    // API fuzz test (an impulse of 1e30 N·s on a body of density 1e-20).
    let tiny = MassProperties::cuboid(1e-20, Vec3::splat(0.5)).expect("valid");
    let mut body = RigidBody::new(&BodyDesc::dynamic().with_mass_properties(tiny)).unwrap();
    let before = body.clone();
    let huge = Vec3::new(0.0, 1e30, 0.0);
    let err = body.apply_impulse(huge).unwrap_err();
    assert!(err.to_string().contains("`linear_velocity`"), "{err}");
    assert!(body.apply_impulse_at_point(huge, Vec3::X).is_err());
    assert!(body.apply_angular_impulse(huge).is_err());
    assert_eq!(body, before);
    // A large impulse that stays finite is applied: Δv = J/m exactly as before the check.
    body.apply_impulse(Vec3::new(0.0, 1e-3, 0.0)).unwrap();
    let expected = 1e-3 / tiny.mass();
    assert!(
        (body.linear_velocity().y - expected).abs() <= 1e-6 * expected,
        "{} vs {expected}",
        body.linear_velocity().y
    );
}
