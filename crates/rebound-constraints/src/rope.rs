//! The rope (course item 4): a one-sided maximum distance between two anchors. While slack it applies
//! nothing; once the anchors would move farther apart than its length an impulse acts on both bodies, like a
//! collision — a hard constraint. Stages: *prepare*, *warm start*, *solve* and *relax*, *restitution*.

use crate::error::ConstraintError;
use crate::error::check_in_range;
use crate::pair::BodyPair;
use crate::part::{AxisPart, Bound, DistanceLink, RowTarget};
use crate::path::{JointRows, MAX_ROWS, one_row};
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::{SolverBody, StepContext};
use rebound_math::validity::check_non_negative;

rebound_math::checked_serde! { "Rope", Rope::validated;
/// A rope: a maximum distance between the anchors.
///
/// ```text
/// C = |d| − L_max ≤ 0                                  (m)
/// Ċ = n·(v_b + ω_b × r_b − v_a − ω_a × r_a),   n = d/|d|,   J = [ −nᵀ  −(r_a × n)ᵀ  nᵀ  (r_b × n)ᵀ ]
/// m_eff = 1 / (1/m_a + 1/m_b + (r_a × n)·I_a⁻¹·(r_a × n) + (r_b × n)·I_b⁻¹·(r_b × n))
/// λ ≤ 0 (a rope only pulls)
/// ```
///
/// Slack (`C < 0`): speculative, `bias = C/h`: the anchors may separate by the remaining slack in this substep
/// and no more, so a slack rope applies exactly nothing and a rope going taut stops at its length instead of
/// overshooting and being pulled back. Taut (`C ≥ 0`): the joint softness of [`crate::JointSettings`] in the
/// bias pass (the rigid end of the softness scale), no bias in the relax pass.
///
/// **Restitution.** With a coefficient `e > 0`, a rope that went taut during the step while its anchors were
/// separating faster than the world's restitution threshold gets, once after the substeps, the velocity
/// `Ċ = −e·Ċ⁻` (Ċ⁻ the separating speed before the step): the jerk of a rope snapping taut, handled like a
/// collision with the course's coefficient of restitution.
///
/// # Examples
///
/// ```
/// use rebound_constraints::Rope;
/// let rope = Rope::new(2.0)?.with_restitution(0.3)?;
/// assert_eq!(rope.max_length(), 2.0);
/// assert!(Rope::new(f32::NAN).is_err());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Rope {
    max_length: f32,
    restitution: f32,
}
}

impl Rope {
    /// A rope of `max_length` (m, ≥ 0) without restitution.
    ///
    /// # Errors
    /// A negative or non-finite `max_length`.
    pub fn new(max_length: f32) -> Result<Self, ConstraintError> {
        Ok(Self {
            max_length: check_non_negative("max_length", max_length)?,
            restitution: 0.0,
        })
    }

    /// Sets the coefficient of restitution of the rope going taut (dimensionless, in `[0, 1]`). Default: 0.
    ///
    /// # Errors
    /// `restitution` outside `[0, 1]` or NaN.
    pub fn with_restitution(mut self, restitution: f32) -> Result<Self, ConstraintError> {
        self.set_restitution(restitution)?;
        Ok(self)
    }

    /// The maximum length (m).
    #[must_use]
    pub fn max_length(&self) -> f32 {
        self.max_length
    }

    /// The coefficient of restitution (dimensionless).
    #[must_use]
    pub fn restitution(&self) -> f32 {
        self.restitution
    }

    /// Changes the maximum length (m); nothing changes on error.
    ///
    /// # Errors
    /// A negative or non-finite `max_length`.
    pub fn set_max_length(&mut self, max_length: f32) -> Result<(), ConstraintError> {
        self.max_length = check_non_negative("max_length", max_length)?;
        Ok(())
    }

    /// Returns `self` if every parameter passes the checks of [`Rope::new`] and [`Rope::set_restitution`]:
    /// for values that bypassed them (deserialised).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        Self::new(self.max_length)?.with_restitution(self.restitution)
    }

    /// Changes the coefficient of restitution; nothing changes on error.
    ///
    /// # Errors
    /// `restitution` outside `[0, 1]` or NaN.
    pub fn set_restitution(&mut self, restitution: f32) -> Result<(), ConstraintError> {
        self.restitution = check_in_range("restitution", restitution, 0.0, 1.0)?;
        Ok(())
    }

    pub(crate) fn prepare(&self, pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> PreparedRope {
        let (link, dist) = DistanceLink::prepare(pair, (a, b), self.max_length);
        // Read by the restitution alone: a rope without one leaves it at 0.
        let separating_speed = if self.restitution == 0.0 {
            0.0
        } else {
            AxisPart::along(pair, &dist).velocity(a, b)
        };
        PreparedRope {
            restitution: self.restitution,
            link,
            separating_speed,
            taut: false,
        }
    }
}

/// A rope ready for the substeps: its distance row ([`DistanceLink`], `|d| ≤ max_length`) and what its
/// restitution needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedRope {
    restitution: f32,
    link: DistanceLink,
    /// `Ċ` before the step (m/s), positive while the anchors separate; 0 for a rope without restitution
    /// (only the restitution reads it).
    separating_speed: f32,
    /// Whether the rope pulled at any time during the step.
    taut: bool,
}

impl PreparedRope {
    pub(crate) fn max_length(&self) -> f32 {
        self.link.length()
    }

    /// Whether the rope has a coefficient of restitution (stage *restitution* leaves it alone otherwise).
    pub(crate) fn has_restitution(&self) -> bool {
        self.restitution != 0.0
    }

    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        if state.upper_impulse == 0.0 {
            return;
        }
        self.link.warm_start(pair, a, b, state.upper_impulse);
    }

    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        bodies: (&mut SolverBody, &mut SolverBody),
        stage: &Stage,
    ) {
        let row = (stage, Bound::AtMost);
        self.link.solve(pair, bodies, row, &mut state.upper_impulse);
        self.taut |= state.upper_impulse < 0.0;
    }

    /// The rope's row for the direct solve of a chain ([`crate::path`]) at the current pose, pushed into
    /// `out`: the row [`PreparedRope::solve`] solves, bounded to `λ ≤ 0`, with its position error
    /// `C = |d| − max_length` for the passes that reuse it.
    pub(crate) fn direct_row(
        &mut self,
        pair: &BodyPair,
        bodies: (&SolverBody, &SolverBody),
        stage: &Stage,
        out: &mut JointRows,
    ) {
        self.link
            .direct_row(pair, bodies, (stage, Bound::AtMost), out);
    }

    /// The accumulated impulse of the rope's direct row ([`PreparedRope::direct_row`]), as its row order.
    #[inline]
    pub(crate) fn direct_impulses(state: &JointState) -> [f32; MAX_ROWS] {
        one_row(state.upper_impulse)
    }

    /// Writes the impulse a direct solve gave the rope's row back into `state`, and notes it for the
    /// restitution.
    #[inline]
    pub(crate) fn store_direct_impulses(
        &mut self,
        state: &mut JointState,
        lambda: [f32; MAX_ROWS],
    ) {
        state.upper_impulse = lambda[0];
        self.note_impulse(lambda[0]);
    }

    /// Records that the rope pulled (for restitution), after a direct solve.
    pub(crate) fn note_impulse(&mut self, impulse: f32) {
        self.taut |= impulse < 0.0;
    }

    /// Stage *restitution*: drives `Ċ` to `−e·Ċ⁻` for a rope that snapped taut this step.
    pub(crate) fn apply_restitution(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
    ) {
        if !self.has_restitution()
            || !self.taut
            || self.separating_speed <= ctx.restitution_threshold
        {
            return;
        }
        let dist = self.link.distance(pair, a, b);
        let part = AxisPart::along(pair, &dist);
        let target = RowTarget::speed(-self.restitution * self.separating_speed);
        part.solve(
            pair,
            a,
            b,
            target,
            &mut state.upper_impulse,
            f32::NEG_INFINITY,
            0.0,
        );
    }
}
