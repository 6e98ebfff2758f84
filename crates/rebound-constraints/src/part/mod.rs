//! The solver core: the impulse maths of a soft, clamped, warm-started constraint row, written once, and the
//! parts every joint is built from (Jolt's `ConstraintPart/`, Box2D's joint blocks). Used by the stages
//! *warm start*, *solve* (bias on), *relax* (bias off) and *restitution*.
//!
//! # One row
//!
//! A row constrains one velocity `Ċ = J·v` (a relative speed along an axis, or about one). Each iteration
//! computes the impulse
//!
//! ```text
//! Δλ = −m_eff·mass_scale·(Ċ + bias) − impulse_scale·λ          m_eff = 1 / (J·M⁻¹·Jᵀ)
//! λ' = clamp(λ + Δλ, λ_min, λ_max),   apply λ' − λ,   λ ← λ'
//! ```
//!
//! with `λ` the impulse accumulated over the substep (warm-started from the last substep), and `bias`,
//! `mass_scale`, `impulse_scale` from a [`RowTarget`]:
//!
//! | target | bias (m/s or rad/s) | softness | clamp |
//! |---|---|---|---|
//! | equality (rod, ball, locks), bias on | `bias_rate·C` | joint softness | none |
//! | equality, relax | 0 | rigid | none |
//! | lower limit `C = x − x_min ≥ 0` | `C/h` while `C > 0` (speculative), else as equality | | `λ ≥ 0` |
//! | upper limit `C = x − x_max ≤ 0` | `C/h` while `C < 0` (speculative), else as equality | | `λ ≤ 0` |
//! | spring (implicit, soft) | `bias_rate·C` | the spring's [`Softness`] | the force caps · h |
//! | motor | `−target speed` | rigid | `±max force·h` |
//!
//! A speculative limit lets the bodies close exactly the remaining gap in this substep and no more, so a
//! slack rope applies nothing and a rope going taut stops at its length (Box2D v3's limits).
//!
//! For a single spring row the accumulated form is a fixed point of the iteration: with
//! `mass_scale + impulse_scale = 1` the first pass gives `λ = −m_eff·mass_scale·(Ċ₀ + bias_rate·C)` whatever
//! was warm-started, and a second pass adds nothing. That is exactly one implicit-Euler step of the
//! spring-damper (see `crate::spring`).
//!
//! # Blocks
//!
//! The 3-DOF point part, the 3-DOF rotation lock and the 2-DOF axis alignment solve the same formula with
//! vectors, `Δλ = −mass_scale·K⁻¹·(Ċ + bias) − impulse_scale·λ`, without clamping.

mod align;
mod angle;
mod axis;
mod distance;
mod pivot_angle;
mod point;
mod rotation;
mod swing_twist;

pub use align::AlignPart;
pub use angle::AnglePart;
pub use axis::AxisPart;
pub(crate) use axis::CentreAxis;
pub(crate) use distance::{Bound, DistanceLink, DistanceRow};
pub use pivot_angle::PivotAnglePart;
pub use point::PointPart;
pub use rotation::{RotationPart, rotation_error};
pub use swing_twist::{MIN_TWIST_DENOMINATOR, SwingTwist};

use crate::pair::BodyPair;
use rebound_dynamics::{Bias, Softness, SolverBody};
use rebound_math::{Mat2, Mat3, Vec2, Vec3};

/// A one-row part, linear ([`AxisPart`]) or angular ([`AnglePart`]), so that code driving a joint
/// coordinate (spring, motor, limits) is written once for both. Static dispatch only.
pub trait Row {
    /// `1/K` (kg or kg·m²).
    fn effective_mass(&self) -> f32;
    /// `Ċ` (m/s or rad/s).
    fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32;
    /// Applies `impulse` (N·s or N·m·s): `+` on B, `−` on A.
    fn apply_impulse(&self, pair: &BodyPair, a: &mut SolverBody, b: &mut SolverBody, impulse: f32);

    /// One iteration of the row ([`solve_row`]) and its application; returns the applied increment.
    #[inline]
    fn solve_clamped(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        target: RowTarget,
        accumulated: &mut f32,
        lower: f32,
        upper: f32,
    ) -> f32 {
        let velocity = self.velocity(a, b);
        let applied = solve_row(
            self.effective_mass(),
            velocity,
            target,
            accumulated,
            lower,
            upper,
        );
        self.apply_impulse(pair, a, b, applied);
        applied
    }
}

impl Row for AxisPart {
    #[inline]
    fn effective_mass(&self) -> f32 {
        AxisPart::effective_mass(self)
    }
    #[inline]
    fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        AxisPart::velocity(self, a, b)
    }
    #[inline]
    fn apply_impulse(&self, pair: &BodyPair, a: &mut SolverBody, b: &mut SolverBody, impulse: f32) {
        self.apply(pair, a, b, impulse);
    }
}

impl Row for AnglePart {
    #[inline]
    fn effective_mass(&self) -> f32 {
        AnglePart::effective_mass(self)
    }
    #[inline]
    fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        AnglePart::velocity(self, a, b)
    }
    #[inline]
    fn apply_impulse(
        &self,
        _pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        impulse: f32,
    ) {
        self.apply(a, b, impulse);
    }
}

/// What one row drives toward in one iteration: a velocity bias and the softness to do it with.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RowTarget {
    /// Velocity bias added to `Ċ` (m/s or rad/s): `bias_rate·C` for a soft correction, `C/h` for a
    /// speculative limit, `−v_target` for a motor.
    pub bias: f32,
    /// Mass and impulse scales (and the bias rate the bias was made with).
    pub softness: Softness,
}

impl RowTarget {
    /// Drives `Ċ` to `target_speed` (m/s or rad/s) rigidly: a motor.
    #[inline]
    #[must_use]
    pub const fn speed(target_speed: f32) -> Self {
        Self {
            bias: -target_speed,
            softness: Softness::RIGID,
        }
    }

    /// A soft spring on the position error `c` (m or rad): the row behaves as a spring-damper integrated with
    /// implicit Euler (Catto, "Soft Constraints", GDC 2011).
    #[inline]
    #[must_use]
    pub fn spring(c: f32, softness: Softness) -> Self {
        Self {
            bias: softness.bias_rate * c,
            softness,
        }
    }

    /// An equality `C = 0`: corrected with `joint_softness` in the bias pass, velocity only in the relax pass.
    #[inline]
    #[must_use]
    pub fn equality(c: f32, bias: Bias, joint_softness: Softness) -> Self {
        match bias {
            Bias::On => Self::spring(c, joint_softness),
            Bias::Off => Self::speed(0.0),
        }
    }

    /// A lower limit with `c = x − x_min` (≥ 0 when satisfied): speculative while `c > 0`, else as
    /// [`RowTarget::equality`]. Clamp the accumulated impulse to `λ ≥ 0`.
    #[inline]
    #[must_use]
    pub fn lower_limit(c: f32, bias: Bias, joint_softness: Softness, inv_h: f32) -> Self {
        if c > 0.0 {
            Self {
                bias: c * inv_h,
                softness: Softness::RIGID,
            }
        } else {
            Self::equality(c, bias, joint_softness)
        }
    }

    /// An upper limit with `c = x − x_max` (≤ 0 when satisfied): speculative while `c < 0`, else as
    /// [`RowTarget::equality`]. Clamp the accumulated impulse to `λ ≤ 0`.
    #[inline]
    #[must_use]
    pub fn upper_limit(c: f32, bias: Bias, joint_softness: Softness, inv_h: f32) -> Self {
        if c < 0.0 {
            Self {
                bias: c * inv_h,
                softness: Softness::RIGID,
            }
        } else {
            Self::equality(c, bias, joint_softness)
        }
    }
}

/// The impulse of one row (see the module docs): updates the accumulated impulse `accumulated` (N·s or
/// N·m·s), clamped to `[lower, upper]`, and returns the increment to apply.
///
/// `effective_mass` is `1/(J·M⁻¹·Jᵀ)` (kg or kg·m²; 0 when neither body can move), `velocity` is `Ċ`.
/// Never panics: the clamp is a bound from below then one from above (`clamp_impulse`), so even a reversed
/// range gives a value.
#[inline]
#[must_use]
pub fn solve_row(
    effective_mass: f32,
    velocity: f32,
    target: RowTarget,
    accumulated: &mut f32,
    lower: f32,
    upper: f32,
) -> f32 {
    let s = target.softness;
    let delta =
        -effective_mass * s.mass_scale * (velocity + target.bias) - s.impulse_scale * *accumulated;
    let new = clamp_impulse(*accumulated + delta, lower, upper);
    let applied = new - *accumulated;
    *accumulated = new;
    applied
}

/// `x` clamped to `[lower, upper]`: `max(x, lower)`, then `min(·, upper)`, with a NaN `x` giving `lower` as
/// [`f32::max`] does — written as comparisons so that each bound compiles to a plain min or max
/// (`f32::max` also handles a NaN bound, which no row has, and the clamp runs for every row of every pass).
/// A reversed range gives `upper`.
#[inline]
#[must_use]
pub(crate) fn clamp_impulse(x: f32, lower: f32, upper: f32) -> f32 {
    let above = if x > lower { x } else { lower };
    if above < upper { above } else { upper }
}

/// The bias and softness of an equality block `C = 0` of three rows: [`RowTarget::equality`] of each
/// component, so that a block and its rows in the direct solve of a path (equality rows) have the same
/// targets.
#[inline]
#[must_use]
pub fn block_target(c: Vec3, bias: Bias, joint_softness: Softness) -> (Vec3, Softness) {
    let [x, y, z] = c
        .to_array()
        .map(|c| RowTarget::equality(c, bias, joint_softness));
    (Vec3::new(x.bias, y.bias, z.bias), x.softness)
}

/// [`block_target`] of a block of two rows.
#[inline]
#[must_use]
pub fn block_target2(c: Vec2, bias: Bias, joint_softness: Softness) -> (Vec2, Softness) {
    let [x, y] = c
        .to_array()
        .map(|c| RowTarget::equality(c, bias, joint_softness));
    (Vec2::new(x.bias, y.bias), x.softness)
}

/// The impulse of a 3-row block with effective-mass matrix `effective_mass = K⁻¹`: updates `accumulated`
/// and returns the increment to apply.
#[inline]
#[must_use]
pub fn solve_block3(
    effective_mass: &Mat3,
    velocity: Vec3,
    target: (Vec3, Softness),
    accumulated: &mut Vec3,
) -> Vec3 {
    let (bias, s) = target;
    let delta =
        -s.mass_scale * (*effective_mass * (velocity + bias)) - s.impulse_scale * *accumulated;
    *accumulated += delta;
    delta
}

/// The impulse of a 2-row block (see [`solve_block3`]).
#[inline]
#[must_use]
pub fn solve_block2(
    effective_mass: &Mat2,
    velocity: Vec2,
    target: (Vec2, Softness),
    accumulated: &mut Vec2,
) -> Vec2 {
    let (bias, s) = target;
    let delta =
        -s.mass_scale * (*effective_mass * (velocity + bias)) - s.impulse_scale * *accumulated;
    *accumulated += delta;
    delta
}

/// `1/k`, or 0 when `k` is not positive (neither body can move along the row).
#[inline]
#[must_use]
pub(crate) fn inverse_or_zero(k: f32) -> f32 {
    if k > 0.0 { 1.0 / k } else { 0.0 }
}

/// `K⁻¹`, or zero when `K` is singular (neither body can move in the block's directions).
#[inline]
#[must_use]
pub(crate) fn inverse3_or_zero(k: &Mat3) -> Mat3 {
    let det = k.determinant();
    if det.abs() > f32::MIN_POSITIVE {
        let inverse = k.inverse();
        if inverse.is_finite() {
            return inverse;
        }
    }
    Mat3::ZERO
}

/// `K⁻¹` of a 2×2 block, or zero when singular.
#[inline]
#[must_use]
pub(crate) fn inverse2_or_zero(k: &Mat2) -> Mat2 {
    let det = k.determinant();
    if det.abs() > f32::MIN_POSITIVE {
        let inverse = k.inverse();
        if inverse.is_finite() {
            return inverse;
        }
    }
    Mat2::ZERO
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_soft_row_is_a_fixed_point_after_one_pass() {
        let s = Softness::new(3.0, 0.2, 1.0 / 240.0);
        let (m, v0, c) = (2.0f32, 0.7f32, 0.1f32);
        // Any warm start: the first pass lands on the same impulse.
        for warm in [0.0f32, 0.5, -3.0] {
            let mut lambda = warm;
            let mut v = v0 + warm / m;
            let applied = solve_row(
                m,
                v,
                RowTarget::spring(c, s),
                &mut lambda,
                f32::MIN,
                f32::MAX,
            );
            v += applied / m;
            let expected = -m * s.mass_scale * (v0 + s.bias_rate * c);
            assert!((lambda - expected).abs() < 1e-5, "{lambda} vs {expected}");
            let again = solve_row(
                m,
                v,
                RowTarget::spring(c, s),
                &mut lambda,
                f32::MIN,
                f32::MAX,
            );
            assert!(again.abs() < 1e-6, "second pass applied {again}");
        }
    }

    #[test]
    fn limits_are_speculative_inside_and_clamped() {
        let inv_h = 240.0;
        // 1 cm of slack, closing at 1 m/s: 1 m/s · h = 4.2 mm < 1 cm, so nothing is applied.
        let target = RowTarget::upper_limit(-0.01, Bias::On, Softness::RIGID, inv_h);
        let mut lambda = 0.0;
        let applied = solve_row(1.0, 1.0, target, &mut lambda, f32::NEG_INFINITY, 0.0);
        assert!(applied == 0.0);
        // Closing at 5 m/s: only the gap is allowed, Ċ' = 0.01·240 = 2.4 m/s.
        let applied = solve_row(1.0, 5.0, target, &mut lambda, f32::NEG_INFINITY, 0.0);
        assert!((5.0 + applied - 2.4).abs() < 1e-5);
        // Reversed range never panics.
        let mut lambda = 0.0;
        let _ = solve_row(1.0, 1.0, RowTarget::speed(0.0), &mut lambda, 1.0, -1.0);
        assert!(lambda.is_finite());
    }

    #[test]
    fn singular_blocks_give_zero_mass() {
        assert_eq!(inverse3_or_zero(&Mat3::ZERO), Mat3::ZERO);
        assert_eq!(inverse2_or_zero(&Mat2::ZERO), Mat2::ZERO);
        assert!(inverse_or_zero(0.0).abs() < f32::EPSILON);
        let k = Mat3::from_diagonal(Vec3::new(2.0, 4.0, 8.0));
        assert!((inverse3_or_zero(&k) * k).abs_diff_eq(Mat3::IDENTITY, 1e-6));
    }
}
