//! The 2-DOF axis alignment (Jolt's `HingeRotationConstraintPart`): an axis fixed in body A stays parallel to
//! an axis fixed in body B, leaving rotation about it free. Hinge and wheel joints use it.
//!
//! With `a` the axis of A and `b₁`, `b₂` two unit vectors of B perpendicular to B's axis (world):
//!
//! ```text
//! C = (a·b₁, a·b₂)                       zero when a ∥ B's axis (rad, to first order)
//! Ċᵢ = uᵢ·(ω_b − ω_a),   uᵢ = bᵢ × a       since d(a·bᵢ)/dt = (ω_a × a)·bᵢ + a·(ω_b × bᵢ)
//! K = [ uᵢ·(I_a⁻¹ + I_b⁻¹)·uⱼ ]            (2×2, 1/(kg·m²))
//! impulse λ (N·m·s): ω_a −= I_a⁻¹·(u₁λ₁ + u₂λ₂),  ω_b += I_b⁻¹·(u₁λ₁ + u₂λ₂)
//! angular impulse Jᵀλ = u₁λ₁ + u₂λ₂ = (λ₁b₁ + λ₂b₂) × a
//! ```
//!
//! The directions `uᵢ` are stated once (`directions`), and the errors (`error`): the Gauss–Seidel solve makes
//! the block from them, and the direct solve of a path ([`crate::path`]) takes them as two angular rows
//! ([`AlignPart::push_rows`], each an [`AnglePart::row`]).

use super::{AnglePart, block_target2, inverse2_or_zero, solve_block2};
use crate::pair::BodyPair;
use crate::path::{JointRows, TargetRule};
use crate::stage::Stage;
use rebound_dynamics::{Bias, Softness, SolverBody};
use rebound_math::glam::Vec3A;
use rebound_math::{Mat2, Quat, Vec2, Vec3};

/// An axis-alignment block, built each iteration (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AlignPart {
    u: [Vec3; 2],
    w_a: [Vec3; 2],
    w_b: [Vec3; 2],
    error: Vec2,
    effective_mass: Mat2,
}

impl AlignPart {
    /// The block keeping `axis_a` (unit, world, fixed in A) perpendicular to `perpendicular_b`, two unit
    /// world vectors fixed in B and perpendicular to B's axis.
    #[inline]
    #[must_use]
    pub fn new(pair: &BodyPair, axis_a: Vec3, perpendicular_b: [Vec3; 2]) -> Self {
        let u = directions(axis_a, perpendicular_b);
        let (w_a, w_b) = turned(pair, u);
        let k01 = u[0].dot(w_a[1] + w_b[1]);
        let k = Mat2::from_cols(
            Vec2::new(u[0].dot(w_a[0] + w_b[0]), k01),
            Vec2::new(k01, u[1].dot(w_a[1] + w_b[1])),
        );
        Self {
            u,
            w_a,
            w_b,
            error: Vec2::new(
                error(axis_a, perpendicular_b[0]),
                error(axis_a, perpendicular_b[1]),
            ),
            effective_mass: inverse2_or_zero(&k),
        }
    }

    /// B's two perpendiculars `b₁`, `b₂` (world) for the joint frame `frame_b` of B, whose axis is the
    /// frame's X: the frame's Y and Z (a hinge's, a wheel's).
    #[inline]
    #[must_use]
    pub fn perpendiculars(frame_b: Quat) -> [Vec3; 2] {
        [frame_b * Vec3::Y, frame_b * Vec3::Z]
    }

    /// The alignment error `C` (rad, to first order).
    #[inline]
    #[must_use]
    pub fn error(&self) -> Vec2 {
        self.error
    }

    /// `Ċ` (rad/s).
    #[inline]
    #[must_use]
    pub fn velocity(&self, a: &SolverBody, b: &SolverBody) -> Vec2 {
        let w = b.angular_velocity - a.angular_velocity;
        Vec2::new(self.u[0].dot(w), self.u[1].dot(w))
    }

    /// Applies the impulse `impulse` (N·m·s, in the block's two directions).
    #[inline]
    pub fn apply(&self, a: &mut SolverBody, b: &mut SolverBody, impulse: Vec2) {
        if impulse == Vec2::ZERO {
            return;
        }
        a.angular_velocity -= self.w_a[0] * impulse.x + self.w_a[1] * impulse.y;
        b.angular_velocity += self.w_b[0] * impulse.x + self.w_b[1] * impulse.y;
    }

    /// [`AlignPart::new`] followed by [`AlignPart::apply`], without the effective mass and the error, which a
    /// warm start does not use: the same velocity changes, bit for bit.
    #[inline]
    pub fn apply_about(
        pair: &BodyPair,
        axis_a: Vec3,
        perpendicular_b: [Vec3; 2],
        a: &mut SolverBody,
        b: &mut SolverBody,
        impulse: Vec2,
    ) {
        if impulse == Vec2::ZERO {
            return;
        }
        let (w_a, w_b) = turned(pair, directions(axis_a, perpendicular_b));
        a.angular_velocity -= w_a[0] * impulse.x + w_a[1] * impulse.y;
        b.angular_velocity += w_b[0] * impulse.x + w_b[1] * impulse.y;
    }

    /// One iteration toward `C = 0` (soft in the bias pass, velocity only in the relax pass); returns the
    /// applied increment.
    #[inline]
    pub fn solve(
        &self,
        a: &mut SolverBody,
        b: &mut SolverBody,
        bias: Bias,
        joint_softness: Softness,
        accumulated: &mut Vec2,
    ) -> Vec2 {
        let target = block_target2(self.error, bias, joint_softness);
        let applied = solve_block2(
            &self.effective_mass,
            self.velocity(a, b),
            target,
            accumulated,
        );
        self.apply(a, b, applied);
        applied
    }

    /// The angular impulse `Jᵀλ = (λ₁b₁ + λ₂b₂) × a` (N·m·s, world) of the impulses `λ` given as
    /// `weighted_perpendicular = λ₁b₁ + λ₂b₂`, for A's `axis`: `+` on B, `−` on A. What
    /// [`AlignPart::apply`] turns by each inverse inertia, for a warm start that sums a joint's parts first
    /// ([`crate::part::PointPart::apply_with_twist`]).
    #[inline]
    #[must_use]
    pub fn twist(axis: Vec3A, weighted_perpendicular: Vec3A) -> Vec3A {
        weighted_perpendicular.cross(axis)
    }

    /// The block's two rows for the direct solve of a path, pushed into `out`: `Ċᵢ = uᵢ·(ω_b − ω_a)` with
    /// [`AlignPart::new`]'s `uᵢ`, each an equality row on its error `a·bᵢ` ([`AlignPart::errors`]).
    #[inline]
    pub(crate) fn push_rows(
        axis_a: Vec3,
        perpendicular_b: [Vec3; 2],
        stage: &Stage,
        out: &mut JointRows,
    ) {
        let u = directions(axis_a, perpendicular_b);
        for (u, perpendicular) in u.into_iter().zip(perpendicular_b) {
            let c = error(axis_a, perpendicular);
            let rule = TargetRule::Equality;
            let target = rule.target(c, stage);
            out.push(AnglePart::row(u, target), c, rule);
        }
    }

    /// The position errors `C = a·bᵢ` (rad, to first order) of [`AlignPart::push_rows`]' rows and their
    /// target rules (equality: soft in the bias pass, `Ċ = 0` in the relax pass), without building the rows.
    #[inline]
    pub(crate) fn errors(axis_a: Vec3, perpendicular_b: [Vec3; 2]) -> [(f32, TargetRule); 2] {
        perpendicular_b.map(|p| (error(axis_a, p), TargetRule::Equality))
    }
}

/// The Jacobian's directions `uᵢ = bᵢ × a` (world): the one statement of the block's `J`.
#[inline]
fn directions(axis_a: Vec3, perpendicular_b: [Vec3; 2]) -> [Vec3; 2] {
    [
        perpendicular_b[0].cross(axis_a),
        perpendicular_b[1].cross(axis_a),
    ]
}

/// `(I_a⁻¹·uᵢ, I_b⁻¹·uᵢ)` of the directions `u` ([`directions`]): what an impulse along them turns each
/// body by.
#[inline]
fn turned(pair: &BodyPair, u: [Vec3; 2]) -> ([Vec3; 2], [Vec3; 2]) {
    (
        [pair.inv_inertia_a * u[0], pair.inv_inertia_a * u[1]],
        [pair.inv_inertia_b * u[0], pair.inv_inertia_b * u[1]],
    )
}

/// The alignment error `C = a·b` of one perpendicular `b` of B with A's axis `a` (rad, to first order).
#[inline]
fn error(axis_a: Vec3, perpendicular: Vec3) -> f32 {
    axis_a.dot(perpendicular)
}
