//! The contact kernel on hand-made contacts: a box resting on a fixed plane settles without drift or jitter; a
//! box sliding at 5 m/s with μ = 0.5 stops after v²/(2μg); a ball dropped on the plane rebounds to C_r²·h;
//! and every contact impulse conserves the momentum of the pair.

mod support;

use proptest::prelude::*;
use rebound_dynamics::contact::Bias;
use rebound_dynamics::{
    BodyDesc, BodyParams, Contact, ContactPoint, ContactSolver, MassProperties, RigidBody,
    SolverBody, SolverSettings, StepContext,
};
use rebound_math::{Quat, Vec3};
use support::{Harness, ball_on_plane, box_on_plane};

const DT: f32 = 1.0 / 60.0;
const HALF: Vec3 = Vec3::new(0.5, 0.5, 0.5);

fn ground_and_box(position: Vec3, velocity: Vec3) -> (Harness, usize, usize) {
    let mut h = Harness::new(SolverSettings::default());
    let ground = h.add(&BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)));
    let mass = MassProperties::cuboid(1.0, HALF).expect("valid");
    let body = h.add(
        &BodyDesc::dynamic()
            .with_mass_properties(mass)
            .with_position(position)
            .with_linear_velocity(velocity),
    );
    (h, ground, body)
}

#[test]
fn a_box_resting_on_a_plane_settles_without_drift_or_jitter() {
    // Dropped from 1 cm above the plane.
    let (mut h, ground, body) = ground_and_box(Vec3::new(0.0, 0.51, 0.0), Vec3::ZERO);
    let mut collide = |b: &[RigidBody]| box_on_plane(b, ground, body, HALF, 0.6, 0.0, 0.05);
    for _ in 0..60 {
        h.step(DT, &mut collide);
    }
    // After 1 s: at rest.
    let mut max_speed = 0.0f32;
    let start = h.bodies[body].position();
    for _ in 0..120 {
        h.step(DT, &mut collide);
        let b = &h.bodies[body];
        max_speed =
            max_speed.max(b.linear_velocity().length() + b.angular_velocity().length() * 0.87);
    }
    let end = h.bodies[body].position();
    assert!(
        max_speed < 1e-3,
        "jitter: max point speed {max_speed} m/s over the next 2 s"
    );
    assert!(
        (end - start).length() < 1e-4,
        "drift {} m over 2 s",
        (end - start).length()
    );
    // Resting on the surface: penetration below a millimetre, no tilt.
    assert!((end.y - 0.5).abs() < 1e-3, "rest height {}", end.y);
    assert!(h.bodies[body].rotation().angle_between(Quat::IDENTITY) < 1e-3);
    // The contact carries the weight: the stored impulse is the last substep's, Σλ = m·g·h (N·s).
    let substep = DT / h.settings.substep_count as f32;
    let total: f32 = h.contacts[0]
        .points()
        .iter()
        .map(|p| p.normal_impulse)
        .sum();
    assert!(
        (total - 9.81 * substep).abs() < 0.01 * 9.81 * substep,
        "normal impulse {total} vs m·g·h"
    );
}

#[test]
fn a_sliding_box_stops_after_v_squared_over_two_mu_g() {
    let (v0, mu, g) = (5.0f32, 0.5f32, 9.81f32);
    let (mut h, ground, body) = ground_and_box(Vec3::new(0.0, 0.5, 0.0), Vec3::new(v0, 0.0, 0.0));
    let mut collide = |b: &[RigidBody]| box_on_plane(b, ground, body, HALF, mu, 0.0, 0.05);
    for _ in 0..180 {
        h.step(DT, &mut collide);
    }
    let b = &h.bodies[body];
    assert!(
        b.linear_velocity().length() < 1e-3,
        "still moving at {}",
        b.linear_velocity()
    );
    let expected = v0 * v0 / (2.0 * mu * g);
    let distance = b.position().x;
    assert!(
        (distance - expected).abs() < 0.03 * expected,
        "stopped after {distance} m, expected {expected} m ± 3 %"
    );
    assert!(b.position().z.abs() < 1e-4, "no sideways drift");
}

#[test]
fn a_ball_rebounds_to_restitution_squared_times_the_drop_height() {
    for restitution in [0.5f32, 0.8, 1.0] {
        let mut h = Harness::new(SolverSettings::default());
        let ground = h.add(&BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)));
        let radius = 0.25;
        let drop = 2.0;
        let ball = h.add(
            &BodyDesc::dynamic()
                .with_mass_properties(MassProperties::ball(1000.0, radius).expect("valid"))
                .with_position(Vec3::new(0.0, radius + drop, 0.0)),
        );
        let mut collide = |b: &[RigidBody]| {
            // Speculative margin: what the ball can travel in one step.
            let margin = b[ball].linear_velocity().length() * DT + 0.01;
            ball_on_plane(b, ground, ball, radius, restitution, margin)
        };
        let mut bounced = false;
        let mut apex = 0.0f32;
        for _ in 0..300 {
            h.step(DT, &mut collide);
            let b = &h.bodies[ball];
            if b.linear_velocity().y > 0.0 {
                bounced = true;
            }
            if bounced {
                apex = apex.max(b.position().y - radius);
                if b.linear_velocity().y < 0.0 {
                    break;
                }
            }
        }
        let expected = restitution * restitution * drop;
        assert!(
            (apex - expected).abs() < 0.03 * expected,
            "C_r = {restitution}: apex {apex} m, expected {expected} m ± 3 %"
        );
    }
}

proptest! {
    /// Every impulse the contact kernel applies acts equally and oppositely: the pair's linear momentum and
    /// angular momentum about the world origin are unchanged by warm start, solve, relax and restitution.
    #[test]
    fn contact_impulses_conserve_the_pairs_momentum(
        va in (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0), vb in (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0),
        wa in (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0), wb in (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0),
        ma in 0.2f32..20.0, mb in 0.2f32..20.0, angle in -1.0f32..1.0,
        separation in -0.05f32..0.02, friction in 0.0f32..1.0, restitution in 0.0f32..1.0,
        warm in 0.0f32..2.0,
    ) {
        let v3 = |t: (f32, f32, f32)| Vec3::new(t.0, t.1, t.2);
        let body = |m: f32, p: Vec3, v: Vec3, w: Vec3| {
            RigidBody::new(
                &BodyDesc::dynamic()
                    .with_mass_properties(MassProperties::cuboid(m, Vec3::new(0.5, 0.3, 0.4)).expect("valid"))
                    .with_position(p)
                    .with_rotation(Quat::from_rotation_z(angle))
                    .with_linear_velocity(v)
                    .with_angular_velocity(w),
            )
            .expect("valid")
        };
        let a = body(ma, Vec3::new(0.0, 0.0, 0.0), v3(va), v3(wa));
        let b = body(mb, Vec3::new(0.2, 0.9, -0.1), v3(vb), v3(wb));
        let normal = Vec3::new(0.1, 1.0, 0.05).normalize();
        let mut contact = Contact::new(0, 1, normal, friction, restitution);
        for (i, offset) in [Vec3::new(0.3, 0.45, 0.2), Vec3::new(-0.2, 0.45, -0.3)].into_iter().enumerate() {
            contact.push_point(ContactPoint {
                anchor_a: offset - a.center_of_mass(),
                anchor_b: offset - b.center_of_mass(),
                separation,
                normal_impulse: warm,
                tangent_impulse: Vec3::new(0.1, 0.0, -0.2) * warm,
                feature_id: i as u32,
            });
        }
        let settings = SolverSettings { gravity: Vec3::ZERO, ..SolverSettings::default() };
        let ctx = StepContext::new(DT, &settings);
        let bodies = [a.clone(), b.clone()];
        let mut states: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
        let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
        // The density constructor makes mass = density × volume; use the bodies' own masses.
        let (ma, mb) = (bodies[0].mass_properties().mass(), bodies[1].mass_properties().mass());
        let momenta = |s: &[SolverBody]| {
            let linear = s[0].linear_velocity * ma + s[1].linear_velocity * mb;
            // Angular momentum about the origin at the start-of-step poses: I_w·ω + c × m·v.
            let angular = bodies[0].inertia_world() * s[0].angular_velocity
                + bodies[1].inertia_world() * s[1].angular_velocity
                + bodies[0].center_of_mass().cross(s[0].linear_velocity * ma)
                + bodies[1].center_of_mass().cross(s[1].linear_velocity * mb);
            (linear, angular)
        };
        let (l0, a0) = momenta(&states);
        let mut solver = ContactSolver::new();
        prop_assert_eq!(solver.prepare(&[contact], &states, &params, &ctx), 0);
        solver.warm_start(&mut states);
        solver.solve(&mut states, &ctx, Bias::On);
        solver.solve(&mut states, &ctx, Bias::Off);
        let (l1, a1) = momenta(&states);
        let scale = 1.0 + l0.length() + a0.length() + 20.0 * warm;
        prop_assert!((l1 - l0).length() < 1e-4 * scale, "linear {l0} → {l1}");
        prop_assert!((a1 - a0).length() < 1e-4 * scale, "angular {a0} → {a1}");
    }
}

#[test]
fn malformed_contacts_are_skipped_not_solved() {
    let bodies = [RigidBody::new(&BodyDesc::dynamic()).unwrap()];
    let states: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
    let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
    let ctx = StepContext::new(DT, &SolverSettings::default());
    let contacts = [
        Contact::new(0, 7, Vec3::Y, 0.5, 0.0),
        Contact::new(0, 0, Vec3::Y, 0.5, 0.0),
        Contact::new(0, 1, Vec3::splat(f32::NAN), 0.5, 0.0),
    ];
    let mut solver = ContactSolver::new();
    assert_eq!(solver.prepare(&contacts, &states, &params, &ctx), 3);
    assert!(solver.is_empty());
}
