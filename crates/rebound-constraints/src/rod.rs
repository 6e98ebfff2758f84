//! The rod: a fixed distance between two anchors (a massless rigid rod with ball ends; Box2D's rigid distance
//! joint). Stages: *prepare*, *warm start*, *solve* and *relax*.

use crate::error::ConstraintError;
use crate::pair::BodyPair;
use crate::part::{Bound, DistanceLink};
use crate::path::{JointRows, MAX_ROWS, one_row};
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::SolverBody;
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
            link: DistanceLink::prepare(pair, (a, b), self.length).0,
        }
    }
}

/// A rod ready for the substeps: its distance row ([`DistanceLink`], `|d| = length`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedRod {
    link: DistanceLink,
}

impl PreparedRod {
    pub(crate) fn length(&self) -> f32 {
        self.link.length()
    }

    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        self.link.warm_start(pair, a, b, state.axial_impulse);
    }

    /// The accumulated impulse of the rod's direct row ([`PreparedRod::direct_row`]), as its row order.
    #[inline]
    pub(crate) fn direct_impulses(state: &JointState) -> [f32; MAX_ROWS] {
        one_row(state.axial_impulse)
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
        bodies: (&SolverBody, &SolverBody),
        stage: &Stage,
        out: &mut JointRows,
    ) {
        self.link
            .direct_row(pair, bodies, (stage, Bound::Exactly), out);
    }

    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        bodies: (&mut SolverBody, &mut SolverBody),
        stage: &Stage,
    ) {
        let row = (stage, Bound::Exactly);
        self.link.solve(pair, bodies, row, &mut state.axial_impulse);
    }
}
