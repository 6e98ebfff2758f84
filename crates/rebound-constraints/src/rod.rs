//! The rod: a fixed distance between two anchors (a massless rigid rod with ball ends; Box2D's rigid distance
//! joint). Stages: *prepare*, *warm start*, *solve* and *relax*.

use crate::error::ConstraintError;
use crate::pair::BodyPair;
use crate::part::{AxisPart, Bound, DistanceRow};
use crate::path::{JointRows, MAX_ROWS};
use crate::spring::initial_axis;
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;
use rebound_math::validity::check_positive;

rebound_math::checked_serde! { "Rod", Rod::validated;
/// A rod of fixed length.
///
/// ```text
/// C = |d| − L = 0                                      (m)
/// Ċ = n·(v_b + ω_b × r_b − v_a − ω_a × r_a),   n = d/|d|,   J = [ −nᵀ  −(r_a × n)ᵀ  nᵀ  (r_b × n)ᵀ ]
/// m_eff = 1 / (1/m_a + 1/m_b + (r_a × n)·I_a⁻¹·(r_a × n) + (r_b × n)·I_b⁻¹·(r_b × n))
/// ```
///
/// Softness: the joint softness of [`crate::JointSettings`] in the bias pass, none (velocity only) in the
/// relax pass. The impulse is unclamped: a rod pushes and pulls.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Rod {
    length: f32,
}
}

impl Rod {
    /// A rod of `length` (m, > 0; for zero length use a [`crate::BallJoint`]).
    ///
    /// # Errors
    /// A non-finite or non-positive `length`.
    pub fn new(length: f32) -> Result<Self, ConstraintError> {
        Ok(Self {
            length: check_positive("length", length)?,
        })
    }

    /// Returns `self` if its length passes the check of [`Rod::new`] (for values that bypassed it:
    /// deserialised).
    ///
    /// # Errors
    /// As [`Rod::new`].
    pub fn validated(self) -> Result<Self, ConstraintError> {
        Self::new(self.length)
    }

    /// The length (m).
    #[must_use]
    pub fn length(&self) -> f32 {
        self.length
    }

    /// Changes the length (m); nothing changes on error.
    ///
    /// # Errors
    /// A non-finite or non-positive `length`.
    pub fn set_length(&mut self, length: f32) -> Result<(), ConstraintError> {
        self.length = check_positive("length", length)?;
        Ok(())
    }

    pub(crate) fn prepare(&self, pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> PreparedRod {
        PreparedRod {
            length: self.length,
            fallback_axis: initial_axis(pair, a, b),
            between_centres: pair.is_between_centres(),
        }
    }
}

/// A rod ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedRod {
    length: f32,
    fallback_axis: Vec3,
    /// [`BodyPair::is_between_centres`] of the joint's pair, which every pass of the step asks.
    between_centres: bool,
}

impl PreparedRod {
    pub(crate) fn length(&self) -> f32 {
        self.length
    }

    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let dist = pair.distance_known(a, b, self.fallback_axis, self.between_centres);
        AxisPart::along(pair, &dist).apply(pair, a, b, state.axial_impulse);
    }

    /// The accumulated impulse of the rod's direct row ([`PreparedRod::direct_row`]), as its row order.
    #[inline]
    pub(crate) fn direct_impulses(state: &JointState) -> [f32; MAX_ROWS] {
        [state.axial_impulse, 0.0, 0.0, 0.0, 0.0]
    }

    /// Writes the impulse a direct solve gave the rod's row back into `state`.
    #[inline]
    pub(crate) fn store_direct_impulses(state: &mut JointState, lambda: [f32; MAX_ROWS]) {
        state.axial_impulse = lambda[0];
    }

    /// The rod's row for the direct solve of a chain ([`crate::path`]) at the current pose, pushed into
    /// `out` with its position error `C = |d| − length` for the passes that reuse it.
    pub(crate) fn direct_row(
        &mut self,
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
        stage: &Stage,
        out: &mut JointRows,
    ) {
        self.measure(pair, (a, b)).push(stage, out);
    }

    /// The rod's row at the current pose (`|d| = length`), its direction kept as the next fallback.
    #[inline(always)]
    fn measure(&mut self, pair: &BodyPair, bodies: (&SolverBody, &SolverBody)) -> DistanceRow {
        let row = DistanceRow::measure_known(
            pair,
            bodies,
            self.fallback_axis,
            self.length,
            (Bound::Exactly, self.between_centres),
        );
        self.fallback_axis = row.axis();
        row
    }

    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let row = self.measure(pair, (&*a, &*b));
        row.solve(pair, a, b, stage, &mut state.axial_impulse);
    }
}
