//! The course's collision response (course items 7–12) with the correct `(1 + C_r)` impulse, proven by
//! conservation laws on random inputs, and the course's own formula shown to break its definition of C_r.

use proptest::prelude::*;
use rebound_dynamics::impulse::{
    closing_velocity, course_response_1d, resolve_collision, resolve_collision_1d,
    separating_velocity,
};
use rebound_math::Vec3;

fn unit_vector() -> impl Strategy<Value = Vec3> {
    (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
        .prop_filter("non-zero", |v| v.length() > 0.1)
        .prop_map(Vec3::normalize)
}

fn velocity() -> impl Strategy<Value = Vec3> {
    (-20.0f32..20.0, -20.0f32..20.0, -20.0f32..20.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Inverse mass: mostly finite masses from 0.1 to 100 kg, sometimes 0 (an immovable body).
fn inv_mass() -> impl Strategy<Value = f32> {
    prop_oneof![4 => (0.1f32..100.0).prop_map(|m| 1.0 / m), 1 => Just(0.0)]
}

fn energy(inv_mass: f32, v: Vec3) -> f32 {
    if inv_mass > 0.0 {
        0.5 * v.length_squared() / inv_mass
    } else {
        0.0
    }
}

/// Kinetic energy of the pair in the rest frame of an immovable body, if there is one (an immovable body that
/// moves — a kinematic one — hands energy to what it hits; in its own frame energy is still never created).
fn pair_energy(inv1: f32, v1: Vec3, inv2: f32, v2: Vec3, frame: Vec3) -> f32 {
    energy(inv1, v1 - frame) + energy(inv2, v2 - frame)
}

fn rest_frame(inv1: f32, v1: Vec3, inv2: f32, v2: Vec3) -> Vec3 {
    if inv1 == 0.0 {
        v1
    } else if inv2 == 0.0 {
        v2
    } else {
        Vec3::ZERO
    }
}

fn momentum(inv_mass: f32, v: Vec3) -> Vec3 {
    if inv_mass > 0.0 {
        v / inv_mass
    } else {
        Vec3::ZERO
    }
}

proptest! {
    #[test]
    fn response_conserves_momentum_sets_restitution_and_never_creates_energy(
        v1 in velocity(), v2 in velocity(), inv1 in inv_mass(), inv2 in inv_mass(),
        normal in unit_vector(), restitution in 0.0f32..=1.0,
    ) {
        let (a1, a2) = resolve_collision(v1, inv1, v2, inv2, normal, restitution);
        let closing = closing_velocity(v1, v2, normal);

        // A body with inverse mass 0 never changes velocity (course item 11).
        if inv1 == 0.0 { prop_assert_eq!(a1, v1); }
        if inv2 == 0.0 { prop_assert_eq!(a2, v2); }

        // Linear momentum of the movable bodies is conserved whenever neither is immovable.
        if inv1 > 0.0 && inv2 > 0.0 {
            let before = momentum(inv1, v1) + momentum(inv2, v2);
            let after = momentum(inv1, a1) + momentum(inv2, a2);
            let scale = momentum(inv1, v1).length() + momentum(inv2, v2).length() + 1.0;
            prop_assert!((after - before).length() <= 1e-5 * scale, "momentum {before} → {after}");
        }

        // Only the normal component takes part (course item 12): tangential velocities are untouched.
        let tangential = |v: Vec3| v - normal * v.dot(normal);
        prop_assert!(tangential(a1).abs_diff_eq(tangential(v1), 1e-3));
        prop_assert!(tangential(a2).abs_diff_eq(tangential(v2), 1e-3));

        let frame = rest_frame(inv1, v1, inv2, v2);
        let e_before = pair_energy(inv1, v1, inv2, v2, frame);
        let e_after = pair_energy(inv1, a1, inv2, a2, frame);
        let approaching = closing > 1e-3 && inv1 + inv2 > 0.0;
        if approaching {
            // The observed restitution is the requested one: C_r = −v_s / V_c.
            let observed = -separating_velocity(a1, a2, normal) / closing;
            prop_assert!((observed - restitution).abs() <= 1e-3 * (1.0 + 40.0 / closing),
                "C_r {restitution} observed {observed}");
            // Energy is never created; at C_r = 1 it is conserved.
            prop_assert!(e_after <= e_before * (1.0 + 1e-5) + 1e-3, "energy {e_before} → {e_after}");
        } else if closing <= 0.0 {
            // Separating (or resting) bodies are left alone.
            prop_assert_eq!((a1, a2), (v1, v2));
        } else {
            // Closing slower than the 1 mm/s the checks above need to be meaningful: the response still acts,
            // and changes each body's velocity by at most (1 + C_r)·closing ≤ 2·closing (its share of the
            // relative normal velocity).
            prop_assert!((a1 - v1).length() <= 2.0 * closing + 1e-6, "{v1} → {a1}");
            prop_assert!((a2 - v2).length() <= 2.0 * closing + 1e-6, "{v2} → {a2}");
        }
    }

    #[test]
    fn elastic_collisions_conserve_kinetic_energy(
        v1 in velocity(), v2 in velocity(), inv1 in inv_mass(), inv2 in inv_mass(), normal in unit_vector(),
    ) {
        let (a1, a2) = resolve_collision(v1, inv1, v2, inv2, normal, 1.0);
        let frame = rest_frame(inv1, v1, inv2, v2);
        let e_before = pair_energy(inv1, v1, inv2, v2, frame);
        let e_after = pair_energy(inv1, a1, inv2, a2, frame);
        prop_assert!((e_after - e_before).abs() <= 1e-4 * e_before + 1e-3, "energy {e_before} → {e_after}");
    }
}

#[test]
fn head_on_elastic_scene_is_exact() {
    // docs/scenes.md "head-on elastic": m1 = 1, m2 = 3, v1 = 4, v2 = −1 m/s, C_r = 1 → v1' = −3.5, v2' = 1.5.
    let (v1, v2) = resolve_collision_1d(4.0, 1.0, -1.0, 1.0 / 3.0, 1.0);
    assert!((v1 + 3.5).abs() < 1e-5, "v1' = {v1}");
    assert!((v2 - 1.5).abs() < 1e-5, "v2' = {v2}");
    assert!((1.0 * v1 + 3.0 * v2 - (4.0 - 3.0)).abs() < 1e-5, "momentum");
    let energy = |a: f32, b: f32| 0.5 * a * a + 1.5 * b * b;
    assert!(
        (energy(v1, v2) - energy(4.0, -1.0)).abs() < 1e-4,
        "kinetic energy"
    );
}

#[test]
fn infinite_mass_scene_is_exact() {
    // docs/scenes.md "infinite mass": a ball at 5 m/s hits a fixed body (inverse mass 0), C_r = 1.
    let (ball, wall) =
        resolve_collision(Vec3::new(5.0, 0.0, 0.0), 1.0, Vec3::ZERO, 0.0, Vec3::X, 1.0);
    assert!(
        (ball.x + 5.0).abs() < 1e-6,
        "ball returns at 5 m/s, got {ball}"
    );
    assert_eq!(wall, Vec3::ZERO, "the fixed body does not move, exactly");
}

#[test]
fn the_course_formula_violates_its_own_definition_below_cr_one() {
    // Equal masses, V_c = 2 m/s. The definition C_r = −v_s / V_c must give back the C_r put in.
    let (v1, v2) = (1.0f32, -1.0f32);
    let closing = v1 - v2;
    for restitution in [0.0f32, 0.25, 0.5, 0.8] {
        let (c1, c2) = course_response_1d(v1, 1.0, v2, 1.0, restitution);
        let course_observed = -(c1 - c2) / closing;
        // The course's formula observes 2·C_r − 1 instead.
        assert!(
            (course_observed - (2.0 * restitution - 1.0)).abs() < 1e-6,
            "course formula at C_r = {restitution} observed {course_observed}"
        );
        assert!(
            (course_observed - restitution).abs() > 0.1,
            "the course's formula is wrong for C_r < 1"
        );
        // Rebound's impulse observes C_r itself.
        let (r1, r2) = resolve_collision_1d(v1, 1.0, v2, 1.0, restitution);
        assert!((-(r1 - r2) / closing - restitution).abs() < 1e-6);
    }
    // At C_r = 0.5 the course's bodies stop dead; at C_r = 0 they pass through each other.
    let (c1, c2) = course_response_1d(v1, 1.0, v2, 1.0, 0.5);
    assert!(c1.abs() < 1e-6 && c2.abs() < 1e-6);
    let (c1, c2) = course_response_1d(v1, 1.0, v2, 1.0, 0.0);
    assert!((c1 - v1).abs() < 1e-6 && (c2 - v2).abs() < 1e-6);
    // Both agree at C_r = 1.
    let (c1, c2) = course_response_1d(v1, 1.0, v2, 3.0, 1.0);
    let (r1, r2) = resolve_collision_1d(v1, 1.0, v2, 1.0 / 3.0, 1.0);
    assert!((c1 - r1).abs() < 1e-6 && (c2 - r2).abs() < 1e-6);
}
