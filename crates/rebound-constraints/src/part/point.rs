//! The 3-DOF point part (Jolt's `PointConstraintPart`): two anchor points held together. Ball, hinge and fixed
//! joints are built on it.
//!
//! ```text
//! C = d = p_b − p_a                                                   (m)
//! Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a
//! J = [ −1   [r_a]×   1   −[r_b]× ]
//! K = (1/m_a + 1/m_b)·1 − [r_a]×·I_a⁻¹·[r_a]× − [r_b]×·I_b⁻¹·[r_b]×       (symmetric, 1/kg)
//! impulse P (N·s): v_a −= P/m_a, ω_a −= I_a⁻¹·(r_a × P), v_b += P/m_b, ω_b += I_b⁻¹·(r_b × P)
//! ```

use super::{inverse3_or_zero, solve_block3};
use crate::pair::BodyPair;
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::{Mat3, Vec3, skew};

/// A point-to-point block, built each iteration (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointPart {
    r_a: Vec3,
    r_b: Vec3,
    effective_mass: Mat3,
}

impl PointPart {
    /// The block for lever arms `r_a`, `r_b` (m, world axes, from each centre of mass).
    #[inline]
    #[must_use]
    pub fn new(pair: &BodyPair, r_a: Vec3, r_b: Vec3) -> Self {
        let (sa, sb) = (skew(r_a), skew(r_b));
        let k = Mat3::from_diagonal(Vec3::splat(pair.inv_mass_a + pair.inv_mass_b))
            - sa * pair.inv_inertia_a * sa
            - sb * pair.inv_inertia_b * sb;
        Self {
            r_a,
            r_b,
            effective_mass: inverse3_or_zero(&k),
        }
    }

    /// `Ċ`: the relative velocity of the anchor points (m/s).
    #[inline]
    #[must_use]
    pub fn velocity(&self, a: &SolverBody, b: &SolverBody) -> Vec3 {
        b.velocity_at(self.r_b) - a.velocity_at(self.r_a)
    }

    /// Applies the impulse `impulse` (N·s, world): `+` at B's anchor, `−` at A's.
    #[inline]
    pub fn apply(&self, pair: &BodyPair, a: &mut SolverBody, b: &mut SolverBody, impulse: Vec3) {
        Self::apply_at(pair, self.r_a, self.r_b, a, b, impulse);
    }

    /// [`PointPart::apply`] for lever arms `r_a`, `r_b` without building the block: a warm start applies an
    /// impulse and needs no effective mass (its 3 × 3 inverse was most of a bridge's warm start).
    #[inline]
    pub fn apply_at(
        pair: &BodyPair,
        r_a: Vec3,
        r_b: Vec3,
        a: &mut SolverBody,
        b: &mut SolverBody,
        impulse: Vec3,
    ) {
        if impulse == Vec3::ZERO {
            return;
        }
        a.linear_velocity -= impulse * pair.inv_mass_a;
        a.angular_velocity -= pair.inv_inertia_a * r_a.cross(impulse);
        b.linear_velocity += impulse * pair.inv_mass_b;
        b.angular_velocity += pair.inv_inertia_b * r_b.cross(impulse);
    }

    /// One iteration toward `Ċ + bias = 0` with the given softness; returns the applied increment (N·s).
    #[inline]
    pub fn solve(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        target: (Vec3, Softness),
        accumulated: &mut Vec3,
    ) -> Vec3 {
        let velocity = self.velocity(a, b);
        let applied = solve_block3(&self.effective_mass, velocity, target, accumulated);
        self.apply(pair, a, b, applied);
        applied
    }
}
