//! Impulses and the course's collision response (course items 7–13), as free functions on plain numbers —
//! the textbook layer under the contact solver.
//!
//! Sign conventions: the normal `n` is a unit vector pointing **from body 1 to body 2**. The closing velocity
//! `V_c = (v₁ − v₂)·n` is positive while the bodies approach; the separating velocity `v_s = (v₁' − v₂')·n`
//! is negative once they part; the coefficient of restitution is `C_r = −v_s / V_c` (course item 7).
//!
//! # The course's restitution formula is wrong for C_r < 1
//!
//! The course ends with `v₁' = v₁ − 2·m₂/(m₁ + m₂)·V_c·C_r`. That equals the correct result only at
//! `C_r = 1`; in general it yields an observed restitution of `2·C_r − 1` (at `C_r = 0.5` the bodies stop dead
//! together, at `C_r = 0` they pass through each other). The impulse that meets the course's own definition
//! of `C_r` and conserves momentum is
//!
//! ```text
//! j = (1 + C_r)·V_c / (1/m₁ + 1/m₂),    v₁' = v₁ − j/m₁·n,    v₂' = v₂ + j/m₂·n
//! ```
//!
//! written on inverse masses so an immovable body (`1/m = 0`, course item 11) needs no special case.
//! [`course_response_1d`] keeps the course's version for the test that shows the difference.

use rebound_math::{Mat3, Vec3};

/// Closing velocity `V_c = (v₁ − v₂)·n` (m/s) of two bodies along the normal `n` (unit, from 1 to 2):
/// positive while they approach. Only the normal component takes part (course item 12).
#[inline]
#[must_use]
pub fn closing_velocity(v1: Vec3, v2: Vec3, normal: Vec3) -> f32 {
    (v1 - v2).dot(normal)
}

/// Separating velocity `v_s = (v₁' − v₂')·n` (m/s): negative once the bodies part.
#[inline]
#[must_use]
pub fn separating_velocity(v1_after: Vec3, v2_after: Vec3, normal: Vec3) -> f32 {
    (v1_after - v2_after).dot(normal)
}

/// The magnitude (N·s) of the collision impulse along the normal: `j = (1 + C_r)·V_c / (1/m₁ + 1/m₂)`, or 0
/// when the bodies are not approaching or both are immovable.
#[inline]
#[must_use]
pub fn collision_impulse(
    closing_velocity: f32,
    inv_mass_1: f32,
    inv_mass_2: f32,
    restitution: f32,
) -> f32 {
    let inv_mass_sum = inv_mass_1 + inv_mass_2;
    if closing_velocity <= 0.0 || inv_mass_sum <= 0.0 {
        return 0.0;
    }
    (1.0 + restitution) * closing_velocity / inv_mass_sum
}

/// The course's collision of two particles along a 3D normal, done right: returns `(v₁', v₂')` (m/s).
///
/// `normal` is unit, from body 1 to body 2; `restitution` `C_r` in `[0, 1]`. Inverse masses in 1/kg, 0 for
/// an immovable body. Bodies already separating are returned unchanged. Linear momentum is conserved exactly
/// (up to rounding), kinetic energy at `C_r = 1`, and it never grows for `C_r ≤ 1`.
///
/// ```
/// use rebound_dynamics::impulse::resolve_collision;
/// use rebound_math::Vec3;
/// // m₁ = 1 kg at 4 m/s meets m₂ = 3 kg at −1 m/s, elastic (docs/scenes.md "head-on elastic").
/// let (v1, v2) = resolve_collision(Vec3::new(4.0, 0.0, 0.0), 1.0, Vec3::new(-1.0, 0.0, 0.0), 1.0 / 3.0, Vec3::X, 1.0);
/// assert!((v1.x + 3.5).abs() < 1e-5 && (v2.x - 1.5).abs() < 1e-5);
/// ```
#[must_use]
pub fn resolve_collision(
    v1: Vec3,
    inv_mass_1: f32,
    v2: Vec3,
    inv_mass_2: f32,
    normal: Vec3,
    restitution: f32,
) -> (Vec3, Vec3) {
    let j = collision_impulse(
        closing_velocity(v1, v2, normal),
        inv_mass_1,
        inv_mass_2,
        restitution,
    );
    (
        v1 - normal * (j * inv_mass_1),
        v2 + normal * (j * inv_mass_2),
    )
}

/// The same in 1D (velocities along the line from body 1 to body 2).
#[must_use]
pub fn resolve_collision_1d(
    v1: f32,
    inv_mass_1: f32,
    v2: f32,
    inv_mass_2: f32,
    restitution: f32,
) -> (f32, f32) {
    let j = collision_impulse(v1 - v2, inv_mass_1, inv_mass_2, restitution);
    (v1 - j * inv_mass_1, v2 + j * inv_mass_2)
}

/// **The course's formula as printed**, kept to show what is wrong with it (see the module docs):
/// `v₁' = v₁ − 2·m₂/(m₁ + m₂)·V_c·C_r`, `v₂' = v₂ + 2·m₁/(m₁ + m₂)·V_c·C_r`, with masses in kg.
///
/// Do not use it for physics: for `C_r < 1` its observed restitution is `2·C_r − 1`.
#[must_use]
pub fn course_response_1d(
    v1: f32,
    mass_1: f32,
    v2: f32,
    mass_2: f32,
    restitution: f32,
) -> (f32, f32) {
    let closing = v1 - v2;
    let total = mass_1 + mass_2;
    (
        v1 - 2.0 * mass_2 / total * closing * restitution,
        v2 + 2.0 * mass_1 / total * closing * restitution,
    )
}

/// The effective mass (kg) of two bodies for an impulse along the unit `direction` at anchors `r₁`, `r₂`
/// (relative to their centres of mass, m), including rotation:
///
/// ```text
/// k = 1/m₁ + 1/m₂ + (r₁ × d)·I₁⁻¹·(r₁ × d) + (r₂ × d)·I₂⁻¹·(r₂ × d),    m_eff = 1/k
/// ```
///
/// Returns 0 when `k = 0` (both bodies immovable along `direction`).
#[must_use]
pub fn effective_mass(
    inv_mass_1: f32,
    inv_inertia_1: &Mat3,
    anchor_1: Vec3,
    inv_mass_2: f32,
    inv_inertia_2: &Mat3,
    anchor_2: Vec3,
    direction: Vec3,
) -> f32 {
    let rn1 = anchor_1.cross(direction);
    let rn2 = anchor_2.cross(direction);
    let k = inv_mass_1 + inv_mass_2 + rn1.dot(*inv_inertia_1 * rn1) + rn2.dot(*inv_inertia_2 * rn2);
    if k > 0.0 { 1.0 / k } else { 0.0 }
}

/// Resolves an interpenetration of `depth` (m, ≥ 0) along the unit `normal` (from body 1 to body 2) by moving
/// the bodies apart in proportion to their inverse masses (the course's previous unit): returns the position
/// corrections `(Δx₁, Δx₂)` (m). An immovable body does not move; two immovable bodies give zeros.
///
/// The engine's contact solver does this softly, with a push-out speed cap, inside the substeps; this is the
/// direct projection.
#[must_use]
pub fn separate_by_inverse_mass(
    inv_mass_1: f32,
    inv_mass_2: f32,
    normal: Vec3,
    depth: f32,
) -> (Vec3, Vec3) {
    let inv_mass_sum = inv_mass_1 + inv_mass_2;
    if inv_mass_sum <= 0.0 || depth <= 0.0 {
        return (Vec3::ZERO, Vec3::ZERO);
    }
    let per_inv_mass = depth / inv_mass_sum;
    (
        -normal * (per_inv_mass * inv_mass_1),
        normal * (per_inv_mass * inv_mass_2),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn separation_moves_the_lighter_body_more_and_closes_the_gap_exactly() {
        let (d1, d2) = separate_by_inverse_mass(1.0, 0.25, Vec3::Y, 0.1);
        assert!((d2 - d1).dot(Vec3::Y) - 0.1 < 1e-7);
        assert!((d1.length() / d2.length() - 4.0).abs() < 1e-5);
        let (d1, d2) = separate_by_inverse_mass(0.0, 1.0, Vec3::Y, 0.1);
        assert_eq!(d1, Vec3::ZERO);
        assert!((d2.y - 0.1).abs() < 1e-7);
        assert_eq!(
            separate_by_inverse_mass(0.0, 0.0, Vec3::Y, 0.1),
            (Vec3::ZERO, Vec3::ZERO)
        );
    }

    #[test]
    fn effective_mass_through_the_centre_is_the_reduced_mass() {
        let i = Mat3::IDENTITY;
        let m = effective_mass(1.0, &i, Vec3::ZERO, 1.0 / 3.0, &i, Vec3::ZERO, Vec3::X);
        assert!(
            (m - 0.75).abs() < 1e-6,
            "reduced mass m₁m₂/(m₁+m₂) = 3/4, got {m}"
        );
        // An off-centre anchor adds the rotational term: r = (0, 1, 0), d = x̂ → r × d = −ẑ, I⁻¹ = 1.
        let m = effective_mass(1.0, &i, Vec3::Y, 0.0, &Mat3::ZERO, Vec3::ZERO, Vec3::X);
        assert!((m - 0.5).abs() < 1e-6);
        assert!(
            effective_mass(
                0.0,
                &Mat3::ZERO,
                Vec3::Y,
                0.0,
                &Mat3::ZERO,
                Vec3::ZERO,
                Vec3::X
            )
            .abs()
                < f32::EPSILON
        );
    }
}
