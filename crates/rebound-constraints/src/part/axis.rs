//! The linear one-degree-of-freedom part (Jolt's `AxisConstraintPart`, the block of Box2D's distance joint):
//! the relative velocity of two anchor points along a unit axis. Springs, ropes and rods are one of these;
//! prismatic and wheel joints use them for the directions across and along their axis.
//!
//! ```text
//! Ċ = n·(v_b + ω_b × r_b − v_a − ω_a × r_a)
//! J = [ −nᵀ   −(r_a × n)ᵀ   nᵀ   (r_b × n)ᵀ ]
//! K = J·M⁻¹·Jᵀ = 1/m_a + 1/m_b + (r_a × n)·I_a⁻¹·(r_a × n) + (r_b × n)·I_b⁻¹·(r_b × n)     (1/kg)
//! impulse λ along n: v_a −= λ·n/m_a, ω_a −= λ·I_a⁻¹·(r_a × n), v_b += λ·n/m_b, ω_b += λ·I_b⁻¹·(r_b × n)
//! ```
//!
//! `r_a`, `r_b` are the lever arms from each centre of mass; a prismatic joint passes `r_a + d` for body A so
//! that both bodies are pushed at the same point (the exact Jacobian of `C = n_a·d` with `n_a` turning with A,
//! and no spurious torque: angular momentum is conserved).
//!
//! `J` is stated once (`jacobian`): the Gauss–Seidel solve makes the part from it, and the direct solve of
//! a path ([`crate::path`]) takes it as one row ([`AxisPart::push_row`], a rope's and a rod's;
//! [`AxisPart::row`] for the path's own rows).

use super::{RowTarget, inverse_or_zero, solve_row};
use crate::pair::{BodyPair, Distance};
use crate::path::{JointRows, Row, Side, TargetRule};
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;

/// A linear row, built each iteration from the current geometry (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisPart {
    axis: Vec3,
    rn_a: Vec3,
    rn_b: Vec3,
    w_a: Vec3,
    w_b: Vec3,
    effective_mass: f32,
}

impl AxisPart {
    /// The row along the unit `axis` with lever arms `r_a`, `r_b` (m, world axes, from each centre of mass).
    #[inline]
    #[must_use]
    pub fn new(pair: &BodyPair, axis: Vec3, r_a: Vec3, r_b: Vec3) -> Self {
        let [ja, jb] = jacobian(axis, r_a, r_b);
        let (rn_a, rn_b) = (-ja.angular, jb.angular);
        let w_a = pair.inv_inertia_a * rn_a;
        let w_b = pair.inv_inertia_b * rn_b;
        let k = pair.inv_mass_a + pair.inv_mass_b + rn_a.dot(w_a) + rn_b.dot(w_b);
        Self {
            axis,
            rn_a,
            rn_b,
            w_a,
            w_b,
            effective_mass: inverse_or_zero(k),
        }
    }

    /// The row along `dist`'s axis between its anchors: [`AxisPart::new`] for a distance row (a spring's, a
    /// rope's, a rod's, a tether's).
    #[inline]
    #[must_use]
    pub fn along(pair: &BodyPair, dist: &Distance) -> Self {
        Self::new(pair, dist.axis, dist.anchors.r_a, dist.anchors.r_b)
    }

    /// The unit axis.
    #[inline]
    #[must_use]
    pub fn axis(&self) -> Vec3 {
        self.axis
    }

    /// `1/K` (kg); 0 when neither body can move along the axis.
    #[inline]
    #[must_use]
    pub fn effective_mass(&self) -> f32 {
        self.effective_mass
    }

    /// `Ċ`: the relative velocity of the anchors along the axis (m/s), positive when B moves away from A
    /// along `n`.
    #[inline]
    #[must_use]
    pub fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        self.axis.dot(b.linear_velocity - a.linear_velocity) + self.rn_b.dot(b.angular_velocity)
            - self.rn_a.dot(a.angular_velocity)
    }

    /// Applies the impulse `impulse` (N·s) along the axis: `+` on B, `−` on A. Zero applies nothing (not even
    /// a rounding: a slack rope leaves the bodies bit-identical).
    #[inline]
    pub fn apply(&self, pair: &BodyPair, a: &mut SolverBody, b: &mut SolverBody, impulse: f32) {
        if impulse == 0.0 {
            return;
        }
        a.linear_velocity -= self.axis * (impulse * pair.inv_mass_a);
        a.angular_velocity -= self.w_a * impulse;
        b.linear_velocity += self.axis * (impulse * pair.inv_mass_b);
        b.angular_velocity += self.w_b * impulse;
    }

    /// One iteration of the row: the impulse from [`solve_row`], clamped to `[lower, upper]`, applied.
    /// Returns the applied increment (N·s).
    #[inline]
    pub fn solve(
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
            self.effective_mass,
            velocity,
            target,
            accumulated,
            lower,
            upper,
        );
        self.apply(pair, a, b, applied);
        applied
    }

    /// The row along the unit `axis` with lever arms `r_a`, `r_b` (m) for the direct solve of a path, with
    /// the part's `J` and the target `target`, unbounded.
    #[inline]
    pub(crate) fn row(axis: Vec3, r_a: Vec3, r_b: Vec3, target: RowTarget) -> Row {
        Row::new(jacobian(axis, r_a, r_b), target)
    }

    /// [`AxisPart::row`] between the two centres of mass (`r_a = r_b = 0`): no angular sides, without the cross
    /// products of zero lever arms.
    #[inline]
    pub(crate) fn row_between_centres(axis: Vec3, target: RowTarget) -> Row {
        let side = |linear| Side {
            linear,
            angular: Vec3::ZERO,
        };
        Row::new([side(-axis), side(axis)], target)
    }

    /// Pushes the row along `dist`'s axis between the joint's anchors into `out` (a rope's, a rod's), with
    /// the impulse bounds `[lower, upper]` and position error `c` under `rule`: [`AxisPart::row`] at `dist`'s
    /// axis and lever arms, or for a joint between both centres of mass (`between_centres`:
    /// [`BodyPair::is_between_centres`]) [`AxisPart::row_between_centres`], which has nothing to turn. Inlined
    /// into the path pass, which builds a rope's row at every new pose.
    #[inline(always)]
    pub(crate) fn push_row(
        between_centres: bool,
        dist: &Distance,
        target: RowTarget,
        (lower, upper): (f32, f32),
        (c, rule): (f32, TargetRule),
        out: &mut JointRows,
    ) {
        if between_centres {
            let row = Self::row_between_centres(dist.axis, target).clamped(lower, upper);
            out.push_turned(row, c, rule, [Vec3::ZERO; 2]);
        } else {
            let row = Self::row(dist.axis, dist.anchors.r_a, dist.anchors.r_b, target)
                .clamped(lower, upper);
            out.push(row, c, rule);
        }
    }
}

/// [`AxisPart`] between the two centres of mass (`r_a = r_b = 0`, [`BodyPair::is_between_centres`]): `J =
/// [ −nᵀ  0  nᵀ  0 ]`, no angular side, so neither its velocity nor its impulse touches an angular velocity,
/// and `K = 1/m_a + 1/m_b` does not change within a step (the caller keeps [`AxisPart::effective_mass`] of
/// the same pair). The same values as [`AxisPart`] of zero lever arms, without its products of zeros: a
/// spring between two balls runs it every substep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CentreAxis {
    axis: Vec3,
}

impl CentreAxis {
    /// The row along `dist`'s unit axis.
    #[inline]
    #[must_use]
    pub(crate) fn along(dist: &Distance) -> Self {
        Self { axis: dist.axis }
    }

    /// `Ċ = n·(v_b − v_a)` (m/s).
    #[inline]
    #[must_use]
    pub(crate) fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        self.axis.dot(b.linear_velocity - a.linear_velocity)
    }

    /// Applies `impulse` (N·s) along the axis, `+` on B and `−` on A, as [`AxisPart::apply`]; zero applies
    /// nothing.
    #[inline]
    pub(crate) fn apply(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        impulse: f32,
    ) {
        if impulse == 0.0 {
            return;
        }
        a.linear_velocity -= self.axis * (impulse * pair.inv_mass_a);
        b.linear_velocity += self.axis * (impulse * pair.inv_mass_b);
    }
}

/// The part's `J = [ −nᵀ   −(r_a × n)ᵀ   nᵀ   (r_b × n)ᵀ ]` along the unit `axis` n with lever arms `r_a`,
/// `r_b` (m), as A's and B's sides: the one statement of the part's Jacobian.
#[inline(always)]
fn jacobian(axis: Vec3, r_a: Vec3, r_b: Vec3) -> [Side; 2] {
    [
        Side {
            linear: -axis,
            angular: -r_a.cross(axis),
        },
        Side {
            linear: axis,
            angular: r_b.cross(axis),
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn vec3() -> impl Strategy<Value = Vec3> {
        (-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    fn body() -> impl Strategy<Value = SolverBody> {
        (vec3(), vec3()).prop_map(|(linear_velocity, angular_velocity)| SolverBody {
            linear_velocity,
            angular_velocity,
            ..SolverBody::STATIC
        })
    }

    fn bits(body: &SolverBody) -> [u32; 6] {
        let (v, w) = (body.linear_velocity, body.angular_velocity);
        [v.x, v.y, v.z, w.x, w.y, w.z].map(f32::to_bits)
    }

    proptest! {
        /// `CentreAxis` is `AxisPart` of zero lever arms: the same velocity along the axis, and the same
        /// velocities after an impulse, to the bit.
        #[test]
        fn the_centre_axis_is_the_axis_part_of_zero_lever_arms(
            (a, b) in (body(), body()),
            (inv_mass_a, inv_mass_b) in (0.0f32..4.0, 0.01f32..4.0),
            (inertia_a, inertia_b) in (vec3(), vec3()),
            d in vec3().prop_filter("a direction", |d| d.length() > 1e-3),
            impulse in -50.0f32..50.0,
        ) {
            let pair = BodyPair {
                inv_mass_a,
                inv_mass_b,
                inv_inertia_a: rebound_math::Mat3::from_diagonal(inertia_a.abs()),
                inv_inertia_b: rebound_math::Mat3::from_diagonal(inertia_b.abs()),
                ..BodyPair::default()
            };
            let dist = Distance {
                anchors: crate::pair::Anchors { r_a: Vec3::ZERO, r_b: Vec3::ZERO, d },
                axis: d.normalize(),
                length: d.length(),
            };
            let (general, centre) = (AxisPart::along(&pair, &dist), CentreAxis::along(&dist));
            prop_assert_eq!(
                general.velocity(&a, &b).to_bits(),
                centre.velocity(&a, &b).to_bits()
            );
            let (mut a1, mut b1, mut a2, mut b2) = (a, b, a, b);
            general.apply(&pair, &mut a1, &mut b1, impulse);
            centre.apply(&pair, &mut a2, &mut b2, impulse);
            prop_assert_eq!(bits(&a1), bits(&a2));
            prop_assert_eq!(bits(&b1), bits(&b2));
        }
    }
}
