//! The 3-DOF rotation lock (Jolt's `RotationEulerConstraintPart`): the two joint frames keep the same
//! orientation. Fixed and prismatic joints use it.
//!
//! With `F_a`, `F_b` the world orientations of the joint frames, the error rotation `q_e = F_b·F_a⁻¹` (world)
//! is written as a rotation vector to first order:
//!
//! ```text
//! C = 2·sign(w_e)·(x_e, y_e, z_e)       (rad; exact direction, |C| = 2 sin(θ/2) ≈ θ)
//! Ċ ≈ ω_b − ω_a,     J = [ 0   −1   0   1 ]
//! K = I_a⁻¹ + I_b⁻¹                     (1/(kg·m²))
//! impulse L (N·m·s): ω_a −= I_a⁻¹·L,  ω_b += I_b⁻¹·L
//! ```

use super::{block_target, inverse3_or_zero, solve_block3};
use crate::pair::BodyPair;
use crate::stage::Stage;
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::{Mat3, Quat, Vec3};

/// The rotation error `C` (rad, world axes) that takes frame A onto frame B: zero when they coincide.
#[inline]
#[must_use]
pub fn rotation_error(frame_a: Quat, frame_b: Quat) -> Vec3 {
    let e = frame_b * frame_a.conjugate();
    let sign = if e.w < 0.0 { -2.0 } else { 2.0 };
    sign * Vec3::new(e.x, e.y, e.z)
}

/// A rotation-lock block (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotationPart {
    effective_mass: Mat3,
}

impl RotationPart {
    /// The block of the pair (depends only on the inverse inertias, so it is built once at prepare).
    #[inline]
    #[must_use]
    pub fn new(pair: &BodyPair) -> Self {
        Self {
            effective_mass: inverse3_or_zero(&(pair.inv_inertia_a + pair.inv_inertia_b)),
        }
    }

    /// `Ċ = ω_b − ω_a` (rad/s).
    #[inline]
    #[must_use]
    pub fn velocity(a: &SolverBody, b: &SolverBody) -> Vec3 {
        b.angular_velocity - a.angular_velocity
    }

    /// Applies the angular impulse `impulse` (N·m·s, world): `+` on B, `−` on A.
    #[inline]
    pub fn apply(pair: &BodyPair, a: &mut SolverBody, b: &mut SolverBody, impulse: Vec3) {
        if impulse == Vec3::ZERO {
            return;
        }
        a.angular_velocity -= pair.inv_inertia_a * impulse;
        b.angular_velocity += pair.inv_inertia_b * impulse;
    }

    /// One iteration toward `Ċ + bias = 0`; returns the applied increment (N·m·s).
    #[inline]
    pub fn solve(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        target: (Vec3, Softness),
        accumulated: &mut Vec3,
    ) -> Vec3 {
        let applied = solve_block3(
            &self.effective_mass,
            Self::velocity(a, b),
            target,
            accumulated,
        );
        Self::apply(pair, a, b, applied);
        applied
    }

    /// One iteration of the lock between the joint frames `(F_a, F_b)` (world) in a pass of `stage`: toward
    /// the rotation error [`rotation_error`] as an equality block ([`block_target`]); returns the applied
    /// increment (N·m·s).
    #[inline]
    pub(crate) fn solve_frames(
        &self,
        pair: &BodyPair,
        (frame_a, frame_b): (Quat, Quat),
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
        accumulated: &mut Vec3,
    ) -> Vec3 {
        let c = rotation_error(frame_a, frame_b);
        let target = block_target(c, stage.bias, stage.joint_softness);
        self.solve(pair, a, b, target, accumulated)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rotation_error_is_the_rotation_vector_to_first_order() {
        let a = Quat::from_rotation_z(1.0);
        assert!(rotation_error(a, a).length() < 1e-6);
        // A small rotation by θ about ω̂ (world) applied after A: C ≈ θ·ω̂.
        let axis = Vec3::new(1.0, 2.0, -2.0).normalize();
        let theta = 1e-3f32;
        let b = Quat::from_axis_angle(axis, theta) * a;
        assert!((rotation_error(a, b) - axis * theta).length() < 1e-6);
        // q and −q are the same rotation: the same error.
        assert!((rotation_error(a, -b) - rotation_error(a, b)).length() < 1e-6);
    }
}
