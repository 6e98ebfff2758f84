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
//!
//! `J` is stated once, as its angular blocks `([r_a]×, −[r_b]×)` (`angular_jacobian`): the Gauss–Seidel
//! solve makes the block's `K` from them, and the direct solve of a path ([`crate::path`]) takes their rows
//! as three rows along the world axes ([`PointPart::push_rows`]), each row's error the component of `d` and
//! its target the component of [`block_target`]'s. Every impulse of the part, and of the joints' other parts
//! with it in a warm start, is applied by [`PointPart::apply_with_twist`].

use super::{inverse3_or_zero, solve_block3};
use crate::pair::BodyPair;
use crate::path::{JointRows, Row, Side, TargetRule};
use crate::stage::Stage;
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::glam::{Mat3A, Vec3A};
use rebound_math::{Mat3, Vec3, skew};

#[cfg(doc)]
use super::block_target;

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
        let (ja, jb) = angular_jacobian(r_a, r_b);
        let k = Mat3::from_diagonal(Vec3::splat(pair.inv_mass_a + pair.inv_mass_b))
            + ja * pair.inv_inertia_a * ja.transpose()
            + jb * pair.inv_inertia_b * jb.transpose();
        Self {
            r_a,
            r_b,
            effective_mass: inverse3_or_zero(&k),
        }
    }

    /// `K⁻¹` (kg), zero when neither body can move.
    #[inline]
    #[must_use]
    pub fn effective_mass(&self) -> Mat3 {
        self.effective_mass
    }

    /// The lever arms `(r_a, r_b)` (m, world).
    #[inline]
    #[must_use]
    pub fn levers(&self) -> (Vec3, Vec3) {
        (self.r_a, self.r_b)
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
        let levers = (Vec3A::from(r_a), Vec3A::from(r_b));
        Self::apply_with_twist(pair, levers, impulse.into(), Vec3A::ZERO, a, b);
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

    /// Applies the impulse `p` (N·s, world) at lever arms `r_a`, `r_b` (m), together with the angular impulse
    /// `twist` (N·m·s, world) of the joint's other parts (zero for the part alone), `+` on B and `−` on A:
    /// `v_a −= p/m_a`, `ω_a −= I_a⁻¹·(twist + r_a × p)` and the opposite on B — each body's torques summed and
    /// turned by its inverse inertia once (`Jᵀ·λ` of all the parts, then `M⁻¹`), in 16-byte vectors. The one
    /// statement of the part's impulse: [`PointPart::apply`] and [`PointPart::apply_at`] call it, and a
    /// hinge's warm start applies all its accumulated impulses with it.
    #[inline]
    pub fn apply_with_twist(
        pair: &BodyPair,
        (r_a, r_b): (Vec3A, Vec3A),
        p: Vec3A,
        twist: Vec3A,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        a.linear_velocity -= Vec3::from(p * pair.inv_mass_a);
        a.angular_velocity -= Vec3::from(Mat3A::from(pair.inv_inertia_a) * (twist + r_a.cross(p)));
        b.linear_velocity += Vec3::from(p * pair.inv_mass_b);
        b.angular_velocity += Vec3::from(Mat3A::from(pair.inv_inertia_b) * (twist + r_b.cross(p)));
    }

    /// The block's rows for the direct solve of a path, pushed into `out` at lever arms `r_a`, `r_b` (m) and
    /// separation `d` (m): `Ċ` along each world axis, as [`PointPart::new`]'s `J`, with the errors and rules
    /// of [`PointPart::errors`].
    #[inline]
    pub(crate) fn push_rows(r_a: Vec3, r_b: Vec3, d: Vec3, stage: &Stage, out: &mut JointRows) {
        let (ja, jb) = angular_jacobian(r_a, r_b);
        let angular = [
            (ja.row(0), jb.row(0)),
            (ja.row(1), jb.row(1)),
            (ja.row(2), jb.row(2)),
        ];
        for ((axis, c), (angular_a, angular_b)) in axes_and_errors(d).into_iter().zip(angular) {
            let rule = TargetRule::Equality;
            let target = rule.target(c, stage);
            let sides = [
                Side {
                    linear: -axis,
                    angular: angular_a,
                },
                Side {
                    linear: axis,
                    angular: angular_b,
                },
            ];
            out.push(Row::new(sides, target), c, rule);
        }
    }

    /// The position errors `C` of [`PointPart::push_rows`]' rows (the components of the separation `d`, m)
    /// and their target rules, in row order, without building the rows.
    #[inline]
    pub(crate) fn errors(d: Vec3) -> [(f32, TargetRule); 3] {
        axes_and_errors(d).map(|(_, c)| (c, TargetRule::Equality))
    }
}

/// The point rows' world axes and position errors `C`, the components of `d`: the one statement of the rows
/// [`PointPart::push_rows`] builds and [`PointPart::errors`] measures.
#[inline]
fn axes_and_errors(d: Vec3) -> [(Vec3, f32); 3] {
    [(Vec3::X, d.x), (Vec3::Y, d.y), (Vec3::Z, d.z)]
}

/// The angular blocks of the part's `J = [ −1   [r_a]×   1   −[r_b]× ]` for lever arms `r_a`, `r_b` (m):
/// `([r_a]×, −[r_b]×)`, row `i` of each the angular side of the row along world axis `i`. The one statement of
/// the part's Jacobian, from which [`PointPart::new`] makes `K` and [`PointPart::push_rows`] the rows.
#[inline]
fn angular_jacobian(r_a: Vec3, r_b: Vec3) -> (Mat3, Mat3) {
    (skew(r_a), -skew(r_b))
}
