//! The angular one-degree-of-freedom part (Jolt's `AngleConstraintPart`): the relative angular velocity of
//! two bodies about a unit axis. Hinge limits, motors and springs, and the wheel's drive motor.
//!
//! ```text
//! Ċ = a·(ω_b − ω_a)
//! J = [ 0   −aᵀ   0   aᵀ ]
//! K = a·I_a⁻¹·a + a·I_b⁻¹·a                                          (1/(kg·m²))
//! impulse λ about a (N·m·s): ω_a −= λ·I_a⁻¹·a,  ω_b += λ·I_b⁻¹·a
//! ```
//!
//! The Gauss–Seidel part is made from the axis `a`; the direct solve of a path ([`crate::path`]) takes the
//! same `J` as a row ([`AnglePart::row`]: the hinge's alignment rows, about each of their directions).

use super::{RowTarget, inverse_or_zero, solve_row};
use crate::pair::BodyPair;
use crate::path::{Row, Side};
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;
use rebound_math::glam::Vec3A;

/// An angular row about a unit axis, built each iteration (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnglePart {
    axis: Vec3,
    w_a: Vec3,
    w_b: Vec3,
    effective_mass: f32,
}

impl AnglePart {
    /// The row about the unit world `axis`.
    #[inline]
    #[must_use]
    pub fn new(pair: &BodyPair, axis: Vec3) -> Self {
        let w_a = pair.inv_inertia_a * axis;
        let w_b = pair.inv_inertia_b * axis;
        Self {
            axis,
            w_a,
            w_b,
            effective_mass: inverse_or_zero(axis.dot(w_a) + axis.dot(w_b)),
        }
    }

    /// `1/K` (kg·m²).
    #[inline]
    #[must_use]
    pub fn effective_mass(&self) -> f32 {
        self.effective_mass
    }

    /// `Ċ`: the relative angular velocity about the axis (rad/s).
    #[inline]
    #[must_use]
    pub fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        self.axis.dot(b.angular_velocity - a.angular_velocity)
    }

    /// Applies the angular impulse `impulse` (N·m·s) about the axis: `+` on B, `−` on A.
    #[inline]
    pub fn apply(&self, a: &mut SolverBody, b: &mut SolverBody, impulse: f32) {
        if impulse == 0.0 {
            return;
        }
        a.angular_velocity -= self.w_a * impulse;
        b.angular_velocity += self.w_b * impulse;
    }

    /// One iteration: the impulse from [`solve_row`], clamped to `[lower, upper]`, applied. Returns the
    /// applied increment (N·m·s).
    #[inline]
    pub fn solve(
        &self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        target: RowTarget,
        accumulated: &mut f32,
        lower: f32,
        upper: f32,
    ) -> f32 {
        let velocity = self.velocity(a, b);
        let applied = solve_row(
            self.effective_mass,
            velocity,
            target,
            accumulated,
            lower,
            upper,
        );
        self.apply(a, b, applied);
        applied
    }

    /// The angular impulse `Jᵀλ = a·λ` (N·m·s, world) of the impulse `impulse` about the unit `axis`: `+` on
    /// B, `−` on A. What [`AnglePart::apply`] turns by each inverse inertia, for a warm start that sums a
    /// joint's parts first ([`crate::part::PointPart::apply_with_twist`]).
    #[inline]
    #[must_use]
    pub fn twist(axis: Vec3A, impulse: f32) -> Vec3A {
        axis * impulse
    }

    /// The row about the unit `axis` (world) for the direct solve of a path: `Ċ = a·(ω_b − ω_a)`, the part's
    /// `J = [ 0  −aᵀ  0  aᵀ ]` as A's and B's sides, with the target `target`, unbounded.
    #[inline]
    pub(crate) fn row(axis: Vec3, target: RowTarget) -> Row {
        let side = |angular| Side {
            linear: Vec3::ZERO,
            angular,
        };
        Row::new([side(-axis), side(axis)], target)
    }
}
